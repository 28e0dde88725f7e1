// Output/Modal contributions: each unstable region's mode, at the sweep
// point of its largest growth rate, written on the real modes of the
// frictionless assembly (eigen/modal_contribution.h). The few frictionless
// modes that carry an unstable mode, and their names, say which modes lock
// in.

#include <squeal/analyses/cea.h>
#include <squeal/eigen/modal_contribution.h>

#include <algorithm>
#include <iomanip>
#include <map>
#include <numeric>
#include <sstream>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;

    void
    ComplexEigenvalueAnalysis::decompose_unstable_modes()
    {
      if (!prm.output.modal_contributions)
        return;
      TimerOutput::Scope t(timer, "modal contributions");
      ConditionalOStream quiet(std::cout, false);
      const auto        &scene  = *model->scene;
      const auto         first  = scene.parameter(prm.sweep.first.parameter);
      const auto         second = scene.parameter(prm.sweep.second.parameter);
      const auto         band   = band_options();
      // the frictionless modes and their names, once per point
      struct Basis
      {
        eigen::FrictionlessModes            modes;
        std::map<unsigned int, std::string> names; ///< of the listed ones
      };
      std::map<unsigned int, Basis> bases;
      if (regions.empty())
        pcout << "Modal contributions: no unstable mode to decompose"
              << std::endl;
      for (const auto &region : regions)
        {
          const unsigned int p  = region.point_of_max;
          const auto        &pt = points[p];
          const auto         record =
            std::find_if(modes.begin(), modes.end(), [&](const ModeRecord &m) {
              return m.point == p && m.track == region.track;
            });
          if (record == modes.end())
            continue;
          const unsigned int k = record->mode;
          eigen::EigenPair   x;
          if (!pt.q.empty())
            reduced.expand(pt.q[k], x.re, x.im);
          else
            {
              x.re = pt.full[k].re;
              x.im = pt.full[k].im;
            }
          if (bases.count(p) == 0)
            {
              Basis b;
              b.modes = eigen::frictionless_modes(
                model->parts(), pt.values, band, band.basis_factor, quiet);
              bases.emplace(p, std::move(b));
            }
          Basis &b = bases.at(p);
          // names only for the modes that are listed (collective: every
          // rank takes the same contributors)
          const auto name = [&](const unsigned int i) -> const std::string & {
            if (b.names.count(i) == 0)
              {
                physics::PETScVector zero(b.modes.shape[i]);
                zero       = 0.;
                b.names[i] = describe_mode(pt.values, b.modes.shape[i], zero);
              }
            return b.names[i];
          };
          const auto c = eigen::modal_contributions(b.modes, x);
          // the contributors by share, those above 1 % (at most 10)
          std::vector<unsigned int> order(c.coefficient.size());
          std::iota(order.begin(), order.end(), 0u);
          std::sort(order.begin(), order.end(), [&](auto i, auto j) {
            return std::norm(c.coefficient[i]) > std::norm(c.coefficient[j]);
          });
          std::ostringstream line;
          line << "  unstable mode " << std::setprecision(5)
               << pt.lambda[k].imag() / (2 * M_PI) << " Hz, Re lambda "
               << pt.lambda[k].real() << " 1/s (point " << p
               << "): frictionless modes";
          for (unsigned int r = 0; r < order.size() && r < 10; ++r)
            {
              const unsigned int i     = order[r];
              const double       share = std::norm(c.coefficient[i]);
              if (share < 0.01)
                break;
              std::ostringstream row;
              row << std::setprecision(10) << p << ','
                  << pt.values.get(first.name) << ','
                  << pt.values.get(second.name) << ',' << k << ','
                  << pt.lambda[k].imag() / (2 * M_PI) << ','
                  << pt.lambda[k].real() << ',' << c.captured << ',' << r << ','
                  << i << ',' << b.modes.frequency[i] << ",\"" << name(i)
                  << "\"," << share << ',' << c.coefficient[i].real() << ','
                  << c.coefficient[i].imag();
              contribution_rows.push_back(row.str());
              if (r < 3)
                line << (r == 0 ? " " : ", ") << i << " ("
                     << std::setprecision(5) << b.modes.frequency[i] << " Hz, "
                     << name(i) << ") " << std::setprecision(3) << 100 * share
                     << " %";
            }
          pcout << line.str() << std::endl;
        }
    }
  } // namespace analyses
} // namespace squeal
