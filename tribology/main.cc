// squeal-tribology: fatigue-damage maps from contact-stress histories, crack
// and exfoliation maps from SEM images, and their correlation. Usage:
//   squeal-tribology [--overwrite] [--output DIR] FILE.prm   run
//   squeal-tribology --validate FILE.prm      parse and report, run nothing
//   squeal-tribology --print-parameters       every parameter: default, range,
//   help

#include <squeal/base/errors.h>
#include <squeal/tribology/tribology_analysis.h>

#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

int
main(int argc, char **argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  const std::string              usage =
    "usage: squeal-tribology [--overwrite] [--output DIR] FILE.prm | "
    "--validate FILE.prm | --print-parameters";
  try
    {
      squeal::tribology::TribologyParameters prm;
      dealii::ParameterHandler               handler;
      if (args.size() == 1 && args[0] == "--print-parameters")
        {
          prm.declare_parameters(handler);
          handler.print_parameters(std::cout, dealii::ParameterHandler::PRM);
          return 0;
        }
      bool        validate = false, overwrite = false;
      std::string file, output;
      for (std::size_t i = 0; i < args.size(); ++i)
        if (const std::string &a = args[i]; a == "--validate")
          validate = true;
        else if (a == "--overwrite")
          overwrite = true;
        else if (a == "--output")
          {
            if (i + 1 == args.size() || args[i + 1].empty())
              throw std::runtime_error("--output needs a directory\n" + usage);
            output = args[++i];
          }
        else if (!a.empty() && a[0] == '-')
          throw std::runtime_error("unknown option '" + a + "'\n" + usage);
        else if (file.empty())
          file = a;
        else
          throw std::runtime_error("more than one parameter file given\n" +
                                   usage);
      if (file.empty())
        throw std::runtime_error("no parameter file given\n" + usage);
      prm.read(handler, file);
      prm.output.overwrite = prm.output.overwrite || overwrite;
      if (!output.empty())
        prm.output.directory = output;
      if (validate)
        {
          std::cout << file << ": valid (contact history '" << prm.history.file
                    << "', " << prm.images.files.size() << " image entr"
                    << (prm.images.files.size() == 1 ? "y" : "ies")
                    << ", output to " << prm.output.directory << ")"
                    << std::endl;
          return 0;
        }
      squeal::tribology::TribologyAnalysis analysis(prm, handler);
      analysis.run();
    }
  catch (const std::bad_alloc &)
    {
      std::cerr << "squeal-tribology: error: out of memory (std::bad_alloc): "
                   "the contact history, the images or the correlation grid "
                   "need more than this machine has; use fewer samples, "
                   "smaller images or a coarser Correlation/Cell size"
                << std::endl;
      return 1;
    }
  catch (const std::exception &e)
    {
      std::cerr << "squeal-tribology: error: " << squeal::one_line(e)
                << std::endl;
      return 1;
    }
  return 0;
}
