// Text input shared by the tribology module's parameters and image sidecars
// (not part of the installed interface): lists of numbers and points, a
// parameter file read with one clear error, paths relative to a file.

#ifndef squeal_tribology_text_input_h
#define squeal_tribology_text_input_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <opencv2/core.hpp>

#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace squeal
{
  namespace tribology
  {
    namespace internal
    {
      using dealii::ParameterHandler;
      inline const double nan = std::numeric_limits<double>::quiet_NaN();

      inline std::vector<double>
      parse_doubles(const std::string &text, const std::string &what)
      {
        std::vector<double> out;
        for (const std::string &s : dealii::Utilities::split_string_list(text))
          {
            try
              {
                std::size_t pos = 0;
                out.push_back(std::stod(s, &pos));
                if (pos != s.size())
                  throw std::invalid_argument(s);
              }
            catch (const std::exception &)
              {
                throw std::runtime_error(what + ": '" + s +
                                         "' is not a number");
              }
          }
        return out;
      }

      // "x,y; x,y; ..." -> points
      inline std::vector<cv::Point2d>
      parse_points(const std::string &text, const std::string &what)
      {
        std::vector<cv::Point2d> out;
        for (const std::string &p :
             dealii::Utilities::split_string_list(text, ';'))
          {
            const std::vector<double> v = parse_doubles(p, what);
            if (v.size() != 2)
              throw std::runtime_error(what + ": '" + p +
                                       "' is not a pair x, y");
            out.emplace_back(v[0], v[1]);
          }
        return out;
      }

      inline std::string
      resolve(const std::string &base, const std::string &file)
      {
        return std::filesystem::path(file).is_absolute() ?
                 file :
                 (std::filesystem::path(base) / file).string();
      }
    } // namespace internal
  }   // namespace tribology
} // namespace squeal

#endif
