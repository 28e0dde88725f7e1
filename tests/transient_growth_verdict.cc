// The braking run's growth verdict (transient::fit_growth) on signals with
// a known envelope A(t), x = A(t) sin(2 pi f t), f = 4060 Hz sampled at
// 100 kHz for 10 ms:
// 1. growth then saturation with an overshoot, as a braking run at
//    E_pad = 16 GPa, mu = 0.7 showed (0.08 -> 0.84 m/s in 5 ms, settling at
//    0.48 m/s): growing and a limit cycle, the growth rate before saturation
//    (ln 10.5 / 5 ms) within 5 %, the limit-cycle amplitude within 3 %, the
//    saturation time (A first reaches 0.48) within two periods;
// 2. still growing at the end (500 1/s): growing, no limit cycle, rate
//    within 5 %;
// 3. a decay (-200 1/s): not growing, rate within 5 %;
// 4. a burst that rises tenfold and dies away again: not growing;
// 5. the beat of two modes 200 Hz apart with equal amplitudes (the envelope
//    falls to zero and rises again every 5 ms): not growing.

#include <squeal/transient/signal.h>

#include "check.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

namespace
{
  constexpr double f = 4060., rate = 1e5, duration = 0.01;

  squeal::transient::GrowthFit
  fit(const std::function<double(double)> &amplitude)
  {
    std::vector<double> x;
    for (unsigned int i = 0; i < duration * rate; ++i)
      {
        const double t = i / rate;
        x.push_back(amplitude(t) * std::sin(2. * M_PI * f * t));
      }
    return squeal::transient::fit_growth(x, rate, 0., 1. / f);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using test_tools::check;

  // 1. growth, overshoot, limit cycle
  const double sigma = std::log(0.84 / 0.08) / 5e-3;
  const auto   g1    = fit([&](const double t) {
    return t < 5e-3 ? 0.08 * std::exp(sigma * t) :
                           0.48 + 0.36 * std::exp(-(t - 5e-3) / 5e-4);
  });
  check("overshoot: growing", g1.growing, 1., 0.);
  check("overshoot: limit cycle", g1.limit_cycle, 1., 0.);
  check("overshoot: growth rate before saturation",
        g1.growth_rate,
        sigma,
        0.05);
  check("overshoot: limit-cycle amplitude", g1.final_amplitude, 0.48, 0.03);
  check("overshoot: saturation time",
        g1.saturation_time,
        std::log(0.48 / 0.08) / sigma,
        2. / f,
        1.);

  // 2. growing to the end
  const auto g2 = fit([](const double t) { return 0.01 * std::exp(500. * t); });
  check("growing: growing", g2.growing, 1., 0.);
  check("growing: no limit cycle", g2.limit_cycle, 0., 0.);
  check("growing: growth rate", g2.growth_rate, 500., 0.05);

  // 3. decay
  const auto g3 = fit([](const double t) { return std::exp(-200. * t); });
  check("decay: not growing", g3.growing, 0., 0.);
  check("decay: growth rate", g3.growth_rate, -200., 0.05);

  // 4. a burst that dies away
  const auto g4 = fit([](const double t) {
    return 0.08 + 0.8 * std::exp(-std::pow((t - 3e-3) / 5e-4, 2));
  });
  check("burst: not growing", g4.growing, 0., 0.);
  check("burst: no limit cycle", g4.limit_cycle, 0., 0.);

  // 5. a beat: |cos(pi 200 t)| envelope
  const auto g5 = fit(
    [](const double t) { return 0.5 * std::abs(std::cos(M_PI * 200. * t)); });
  check("beat: not growing", g5.growing, 0., 0.);
  return test_tools::finish();
}
