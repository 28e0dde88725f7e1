#ifndef squeal_base_errors_h
#define squeal_base_errors_h

/**
 * @file
 * Error messages in one line: what a user reads after `squeal: error:`.
 */

#include <deal.II/base/exceptions.h>

#include <exception>
#include <sstream>
#include <string>

namespace squeal
{
  /**
   * The message of @p e on one line. For a deal.II exception (a PETSc,
   * SLEPc, MUMPS or LAPACK failure reported through deal.II's wrappers) that
   * is its additional information, without the source location and stack
   * deal.II's what() adds; for any other exception, what() with its line
   * breaks folded into spaces.
   */
  inline std::string
  one_line(const std::exception &e)
  {
    std::ostringstream info;
    if (const auto *d = dynamic_cast<const dealii::ExceptionBase *>(&e))
      d->print_info(info);
    else
      info << e.what();
    std::istringstream words(info.str());
    std::string        folded, w;
    while (words >> w)
      folded += (folded.empty() ? "" : " ") + w;
    return folded;
  }
} // namespace squeal

#endif
