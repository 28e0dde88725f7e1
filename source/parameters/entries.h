// Helpers shared by the parameter declarations of source/parameters/ (not
// part of the installed interface): numbers as entry defaults, the pattern
// of positive reals, and the check that throws a parameter error.

#ifndef squeal_source_parameters_entries_h
#define squeal_source_parameters_entries_h

#include <deal.II/base/patterns.h>

#include <sstream>
#include <stdexcept>
#include <string>

namespace squeal
{
  namespace parameters
  {
    namespace internal
    {
      /// @p x with 12 significant digits, as an entry's default text
      inline std::string
      str(const double x)
      {
        std::ostringstream s;
        s.precision(12);
        s << x;
        return s.str();
      }

      /// Reals in (0, max]
      inline const dealii::Patterns::Double
        positive(0., dealii::Patterns::Double::max_double_value);

      /// @throws std::runtime_error "invalid parameter: WHAT" unless @p ok
      inline void
      check(const bool ok, const std::string &what)
      {
        if (!ok)
          throw std::runtime_error("invalid parameter: " + what);
      }
    } // namespace internal
  }   // namespace parameters
} // namespace squeal

#endif
