// Verification C1-C4: rainflow counting (ASTM E1049-85) on the standard's
// Fig. 6 history, on a pressure history with separation plateaus, and on a
// squeal-like history, with both residue conventions; Findley damage sums;
// Palmgren-Miner against its closed form; Crossland's sqrt(J2,a) against
// closed forms for in-phase and 90-degree out-of-phase paths; node statistics.
// Reference values: verification.md C1-C4 (independent Python computation).

#include <squeal/tribology/fatigue.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <map>

using namespace squeal::tribology;
using test_tools::check;

namespace
{
  std::map<double, double>
  count_by_range(const std::vector<Cycle> &cycles)
  {
    std::map<double, double> t;
    for (const auto &c : cycles)
      t[c.range] += c.count;
    return t;
  }

  double
  sum_of(const std::vector<Cycle> &cycles, double power, bool weighted)
  {
    double s = 0.;
    for (const auto &c : cycles)
      s += (weighted ? c.count : 1.) * std::pow(c.range, power);
    return s;
  }

  std::vector<double>
  c3_history()
  {
    std::vector<double> p(10000);
    for (std::size_t n = 0; n < p.size(); ++n)
      p[n] = std::max(0.,
                      1. + 15. * std::sin(2. * M_PI * 3400. * n / 1e6) +
                        3. * std::sin(2. * M_PI * 10200. * n / 1e6 + 0.7));
    return p;
  }

  std::vector<double>
  scaled(const std::vector<double> &x, double a, double b = 0.)
  {
    std::vector<double> y(x);
    for (double &v : y)
      v = a * v + b;
    return y;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // C1: ASTM E1049-85 Fig. 6.
  {
    const std::vector<double>      x{-2, 1, -3, 5, -1, 3, -4, 4, -2};
    const auto                     cycles = rainflow(x, Residue::half_cycles);
    const auto                     t      = count_by_range(cycles);
    const std::map<double, double> expected{
      {3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}};
    check("C1 number of distinct ranges", t.size(), expected.size(), 0.);
    for (const auto &[r, n] : expected)
      check("C1 count of range " + std::to_string(int(r)),
            t.count(r) ? t.at(r) : -1.,
            n,
            0.);
    double total = 0.;
    for (const auto &c : cycles)
      total += c.count;
    check("C1 total count 4.0", total, 4., 0.);
    // (range, mean, count) of every cycle
    const std::vector<std::vector<double>> rmc{{3, -0.5, 0.5},
                                               {4, -1, 0.5},
                                               {4, 1, 1},
                                               {8, 1, 0.5},
                                               {9, 0.5, 0.5},
                                               {8, 0, 0.5},
                                               {6, 1, 0.5}};
    unsigned int                           found = 0;
    for (const auto &e : rmc)
      for (const auto &c : cycles)
        if (c.range == e[0] && c.mean == e[1] && c.count == e[2])
          {
            ++found;
            break;
          }
    check("C1 cycles as (range, mean, count)", found, rmc.size(), 0.);
    double s = 0.;
    for (const auto &c : cycles)
      s += c.count * std::pow(c.range / 2., 3);
    check("C1 sum n (R/2)^3 = 136.75", s, 136.75, 1e-14);
    // start/end samples bound the range
    bool bounds = true;
    for (const auto &c : cycles)
      bounds &= std::abs(x[c.end] - x[c.start]) == c.range && c.start < c.end;
    check("C1 start and end samples bound each range", bounds, 1., 0.);
  }

  // C2: pressure with separation plateaus.
  const std::vector<double> c2{
    0, 0, 6, 0, 0, 15, 4, 10, 0, 0, 0, 12, 2, 8, 5, 16, 0, 0};
  {
    const auto                r = reversals(c2);
    const std::vector<double> expected{
      0, 6, 0, 15, 4, 10, 0, 12, 2, 8, 5, 16, 0};
    std::vector<double> got;
    for (auto i : r)
      got.push_back(c2[i]);
    check("C2 reversals", got == expected, 1., 0.);
    const auto t = count_by_range(rainflow(c2, Residue::half_cycles));
    const std::map<double, double> astm{
      {3, 1}, {6, 2}, {10, 1}, {15, 1}, {16, 1}};
    check("C2 ASTM counts", t == astm, 1., 0.);
    const auto          rep = rainflow(c2, Residue::repeating);
    std::vector<double> ranges;
    bool                full = true;
    for (const auto &c : rep)
      {
        ranges.push_back(c.range);
        full &= c.count == 1.;
      }
    std::sort(ranges.begin(), ranges.end());
    check("C2 repeating ranges {3, 6, 6, 10, 15, 16}",
          ranges == std::vector<double>{3, 6, 6, 10, 15, 16},
          1.,
          0.);
    check("C2 repeating: full cycles only", full, 1., 0.);
    check("C2 sum n R = 56 (ASTM)",
          sum_of(rainflow(c2, Residue::half_cycles), 1., true),
          56.,
          1e-14);
    check("C2 sum n R = 56 (repeating)", sum_of(rep, 1., true), 56., 1e-14);
  }

  // C3: squeal-like history at 1 MHz.
  const std::vector<double> c3 = c3_history();
  {
    std::size_t zeros = 0;
    double      mean  = 0.;
    for (double v : c3)
      {
        zeros += (v == 0.);
        mean += v;
      }
    check("C3 separated fraction 0.486200", zeros / 1e4, 0.4862, 1e-12);
    check("C3 max 15.929365098134",
          *std::max_element(c3.begin(), c3.end()),
          15.929365098134,
          1e-12);
    check("C3 mean 5.551624175111", mean / 1e4, 5.551624175111, 1e-12);
    check("C3 70 reversals", reversals(c3).size(), 70., 0.);
    const auto   astm   = rainflow(c3, Residue::half_cycles);
    unsigned int n_full = 0, n_half = 0;
    for (const auto &c : astm)
      (c.count == 1. ? n_full : n_half) += 1;
    check("C3 ASTM 37 cycles", astm.size(), 37., 0.);
    check("C3 ASTM 32 full", n_full, 32., 0.);
    check("C3 ASTM 5 half", n_half, 5., 0.);
    check("C3 ASTM sum n R = 541.343926965",
          sum_of(astm, 1., true),
          541.343926965,
          1e-11);
    const auto rep = rainflow(c3, Residue::repeating);
    check("C3 repeating 34 cycles", rep.size(), 34., 0.);
    check("C3 repeating sum R = 541.579595886",
          sum_of(rep, 1., false),
          541.579595886,
          1e-11);
  }

  // C4: Findley-type damage with q = 0.4 p, k = 0.3, m = 10.
  {
    FindleyParameters f;
    f.k                    = 0.3;
    f.m                    = 10.;
    const FindleyDamage d2 = findley_damage(c2, scaled(c2, 0.4), f);
    check("C4 D* on C2 = 1.7167410789e5", d2.relative, 1.7167410789e5, 1e-9);
    const std::vector<double> c2s = scaled(c2, 1., 2.);
    check("C4 D* on C2 + 2 = 2.0457161083e4",
          findley_damage(c2s, scaled(c2s, 0.4), f).relative,
          2.0457161083e4,
          1e-9);
    check("C4 D* on C3 = 3.607364580e6",
          findley_damage(c3, scaled(c3, 0.4), f).relative,
          3.607364580e6,
          1e-9);
    // Palmgren-Miner with Basquin N = 0.5 (tau / tau_f)^-m: D = 2 D* / tau_f^m
    f.tau_f               = 7.;
    const FindleyDamage d = findley_damage(c2, scaled(c2, 0.4), f);
    check("Palmgren-Miner D = 2 D* / tau_f^m",
          d.miner,
          2. * d.relative / std::pow(7., 10.),
          1e-12);
    // separation removes the clamping: shifting the pressure up lowers D*
    check("C4 separation raises D* (ratio > 8)",
          std::min(d2.relative / 2.0457161083e4, 8.),
          8.,
          0.);
  }

  // Crossland: in phase (p and q oscillate together, a straight path) and
  // 90 degrees out of phase (an ellipse that is a circle when
  // sqrt(3) a dp = dq).
  {
    const double nu = 0.3,
                 a  = std::sqrt(3.) * (1. - 2. * nu) / (3. * (1. - nu));
    std::vector<double> p(2000), q(2000);
    for (std::size_t n = 0; n < p.size(); ++n)
      {
        const double w = 2. * M_PI * n / 200.;
        p[n]           = 10. + 4. * std::sin(w);
        q[n]           = 3. * std::sin(w);
      }
    const CrosslandIndex in_phase = crossland_index(p, q, nu, 0.3);
    check("Crossland in phase: sqrt(J2,a) = half the path length",
          in_phase.sqrt_j2_amplitude,
          std::sqrt(std::pow(a * 4., 2) + 9.),
          1e-5);
    check("Crossland sigma_H,max = -(1+nu)/(3(1-nu)) p_min",
          in_phase.hydrostatic_max,
          -(1. + nu) / (3. * (1. - nu)) * 6.,
          1e-12);
    check("Crossland index = sqrt(J2,a) + alpha sigma_H,max",
          in_phase.index,
          in_phase.sqrt_j2_amplitude + 0.3 * in_phase.hydrostatic_max,
          1e-14);
    for (std::size_t n = 0; n < p.size(); ++n)
      {
        const double w = 2. * M_PI * n / 200.;
        p[n]           = 10. + 4. * std::sin(w);
        q[n]           = 4. * a * std::cos(w);
      }
    check("Crossland out of phase (circle): sqrt(J2,a) = radius",
          crossland_index(p, q, nu, 0.3).sqrt_j2_amplitude,
          4. * a,
          1e-5);
  }

  // Node statistics on C3 (status from the pressure).
  {
    std::vector<int> status(c3.size());
    for (std::size_t n = 0; n < c3.size(); ++n)
      status[n] = c3[n] > 0. ? 2 : 0;
    const NodeStatistics s = node_statistics(c3, status, 1e6);
    check("stats: separated fraction", s.separated_fraction, 0.4862, 1e-12);
    check("stats: slip fraction", s.slip_fraction, 0.5138, 1e-12);
    check("stats: relative oscillation = max / mean",
          s.relative_oscillation,
          15.929365098134 / 5.551624175111,
          1e-11);
    check("stats: cycles per second = 3400 Hz within 3 %",
          s.cycles_per_second,
          3400.,
          0.03);
  }

  // Errors: different lengths.
  {
    bool thrown = false;
    try
      {
        findley_damage(c2, c3, FindleyParameters());
      }
    catch (const std::invalid_argument &)
      {
        thrown = true;
      }
    check("different history lengths are refused", thrown, 1., 0.);
  }
  return test_tools::finish();
}
