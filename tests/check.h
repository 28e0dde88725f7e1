// The relative-error check every test prints: a stable line for numdiff and
// a failure count so that the test also exits non-zero.
#ifndef squeal_tests_check_h
#define squeal_tests_check_h

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace test_tools
{
  inline int n_failures = 0;

  /** Prints "name: ok" or "name: FAILED (value, reference, error)" on rank
   *  0; ok when |value - reference| <= tolerance * scale. */
  inline void
  check(const std::string &name,
        const double       value,
        const double       reference,
        const double       tolerance,
        const double       scale = -1.)
  {
    const double s   = scale > 0 ? scale : std::abs(reference);
    const double err = std::abs(value - reference) / (s > 0 ? s : 1.);
    const bool   ok  = err <= tolerance;
    if (!ok)
      ++n_failures;
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        std::cout << name << ": " << (ok ? "ok" : "FAILED");
        if (!ok)
          std::cout << std::setprecision(12) << " (value " << value
                    << ", reference " << reference << ", error " << err << " > "
                    << tolerance << ")";
        std::cout << std::endl;
      }
  }

  /** Prints "name: ok" when @p ok, else "name: FAILED", and records the
   *  failure: for a condition that has no error to show. */
  inline void
  check_true(const std::string &name, const bool ok)
  {
    check(name, ok ? 0. : 1., 0., 0., 1.);
  }

  /** A stream for measured values worth seeing but not comparing (they
   *  are not in the .output files): std::cerr when SQUEAL_VERBOSE is set,
   *  else a sink. */
  inline std::ostream &
  verbose()
  {
    static std::ostream sink(nullptr);
    return std::getenv("SQUEAL_VERBOSE") ? std::cerr : sink;
  }

  /** The message of the exception @p run throws, "" if it throws none. */
  inline std::string
  error_of(const std::function<void()> &run)
  {
    try
      {
        run();
      }
    catch (const std::exception &e)
      {
        return e.what();
      }
    return "";
  }

  /** Checks that @p message (an error's) contains every one of @p parts:
   *  prints "name: ok" or FAILED, and the message with SQUEAL_VERBOSE. */
  inline void
  check_message(const std::string              &name,
                const std::string              &message,
                const std::vector<std::string> &parts)
  {
    bool all = !message.empty();
    for (const auto &part : parts)
      all = all && message.find(part) != std::string::npos;
    check(name, all ? 0. : 1., 0., 0., 1.);
    if (!all)
      verbose() << message << std::endl;
  }

  inline int
  finish()
  {
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << (n_failures == 0 ? "all checks passed" : "CHECKS FAILED")
                << std::endl;
    return n_failures == 0 ? 0 : 1;
  }
} // namespace test_tools

#endif
