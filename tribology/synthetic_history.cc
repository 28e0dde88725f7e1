// A synthetic squeal-like contact history (synthetic_history.h).

#include <squeal/tribology/synthetic_history.h>

#include <cmath>
#include <stdexcept>

namespace squeal
{
  namespace tribology
  {
    namespace
    {
      const double pi = 3.14159265358979323846;
    } // namespace

    io::ContactHistory
    synthetic_squeal_history(const unsigned int n,
                             const std::size_t  samples,
                             const double       sampling_rate,
                             const double       frequency,
                             const double       p_mean,
                             const double       mu,
                             const double       pad_size,
                             const double       pad_radius,
                             const double       trailing_amplitude)
    {
      if (n < 2 || samples < 2 || !(sampling_rate > 0.))
        throw std::invalid_argument(
          "synthetic history: need n >= 2 nodes per side, >= 2 samples and a "
          "positive sampling rate");
      // 10 rpm at the pad radius, the rig's usual speed.
      const double       sliding_speed = 10. * 2. * pi / 60. * pad_radius;
      io::ContactHistory h;
      h.sampling_rate = sampling_rate;
      h.time.resize(samples);
      for (std::size_t k = 0; k < samples; ++k)
        h.time[k] = k / sampling_rate;
      for (unsigned int j = 0; j < n; ++j)   // along the sliding direction y
        for (unsigned int i = 0; i < n; ++i) // along the radius x
          {
            const double s = double(j) / (n - 1), r = double(i) / (n - 1);
            h.coordinates.push_back(
              {{pad_radius + (r - 0.5) * pad_size, (s - 0.5) * pad_size, 0.}});
            const double amplitude =
              (1. - (1. - trailing_amplitude) * s) * (1. - 0.4 * r);
            std::vector<double> p(samples), q(samples), zero(samples, 0.),
              v(samples, 0.);
            std::vector<int> st(samples);
            for (std::size_t k = 0; k < samples; ++k)
              {
                const double w = 2. * pi * frequency * k / sampling_rate;
                p[k]           = p_mean *
                       std::max(0.,
                                1. + amplitude * (15. * std::sin(w) +
                                                  3. * std::sin(3. * w + 0.7)));
                q[k]  = mu * p[k];
                st[k] = p[k] > 0. ? 2 : 0;
                v[k]  = p[k] > 0. ? sliding_speed : 0.;
              }
            h.p_N.push_back(p);
            h.t_T1.push_back(q);
            h.t_T2.push_back(zero);
            h.slip_velocity.push_back(v);
            h.status.push_back(st);
          }
      return h;
    }
  } // namespace tribology
} // namespace squeal
