#ifndef squeal_tribology_fatigue_h
#define squeal_tribology_fatigue_h

/**
 * @file
 * Cycle counting and fatigue-damage indices of local contact-stress
 * histories (thesis ch. 5 read as fatigue, made quantitative): rainflow
 * counting per ASTM E1049-85, a Findley-type critical-plane damage sum on the
 * contact plane with Basquin life and Palmgren-Miner accumulation, the
 * Crossland index of the laterally constrained surface layer, and per-node
 * statistics of the pressure history.
 *
 * Histories are sampled signals: a `std::vector<double>` of n samples, equally
 * spaced in time. Pressures p are compressive-positive contact pressures and q
 * the tangential traction along the sliding direction, both in Pa.
 */

#include <cstddef>
#include <string>
#include <vector>

namespace squeal
{
  namespace tribology
  {
    /**
     * How the residue left after the ASTM E1049-85 rainflow pass is counted.
     * `half_cycles`: each remaining range is half a cycle (a transient
     * history, ASTM § 5.4.4). `repeating`: the history is taken as one period
     * of a steady, repeating signal (a limit cycle): it is restarted at its
     * largest absolute value, so that every range closes as a full cycle.
     */
    enum class Residue
    {
      half_cycles,
      repeating
    };

    /** Parses "half cycles" or "repeating"; throws std::invalid_argument. */
    Residue
    residue_from_string(const std::string &name);

    /**
     * One rainflow cycle. `start` and `end` are the sample indices of the two
     * reversals that bound its range, in the order they occur; in the
     * `repeating` convention a cycle may wrap around the end of the record,
     * then `end < start`.
     */
    struct Cycle
    {
      double      range; ///< peak-to-valley range, units of the signal
      double      mean;  ///< (peak + valley) / 2, units of the signal
      double      count; ///< 1 (full cycle) or 0.5 (half cycle)
      std::size_t start; ///< sample index of the first reversal
      std::size_t end;   ///< sample index of the second reversal
    };

    /**
     * Sample indices of the reversals (turning points) of @p x, with the
     * first and last samples. A flat plateau (equal consecutive samples, as
     * in the separation phases where p_N = 0) counts once, at its first
     * sample; a plateau on a monotone flank is no reversal.
     * Returns an empty vector for an empty @p x.
     */
    std::vector<std::size_t>
    reversals(const std::vector<double> &x);

    /**
     * Rainflow cycles of @p x by the three-point algorithm of ASTM E1049-85
     * § 5.4.4 (Fig. 6 of the standard is verification C1), with the residue
     * counted as @p residue says. Exact: the ranges are differences of
     * samples. O(n) time.
     */
    std::vector<Cycle>
    rainflow(const std::vector<double> &x, Residue residue);

    /**
     * Parameters of the Findley-type damage sum. No S-N data of phenolic
     * friction materials exists in the open literature, so the defaults only
     * set a scale and the indices are relative: compare maps, not values.
     */
    struct FindleyParameters
    {
      /// Findley's normal-stress sensitivity k [-] (0.2-0.3 for most
      /// materials; Findley 1959, Socie & Marquis 2000 § 5).
      double k = 0.3;
      /// Basquin exponent m [-] = -1/b; b = -0.1 is typical of polymers and
      /// polymer composites.
      double m = 10.;
      /// Shear fatigue-strength coefficient tau_f' [Pa] of the Basquin law
      /// N = 0.5 (tau_eq / tau_f')^(-m); 20 MPa, the order of the shear
      /// strength of resin-bonded friction composites (an assumption).
      double tau_f = 20e6;
      /// Residue convention of the rainflow count of q.
      Residue residue = Residue::half_cycles;
    };

    /** Damage of one node's history. */
    struct FindleyDamage
    {
      double relative   = 0.; ///< D* = sum n tau_eq^m [Pa^m]
      double miner      = 0.; ///< D = sum n / N (Palmgren-Miner) [-]
      double max_tau_eq = 0.; ///< largest tau_eq of any cycle [Pa]
      double n_cycles   = 0.; ///< sum of cycle counts n [-]
    };

    /**
     * Findley-type damage on the contact plane (verification C4): rainflow
     * of the tangential traction @p q along the sliding direction; per cycle
     * tau_eq = max(0, dq / 2 - k p_min), p_min the smallest pressure @p p
     * over the samples the cycle spans (separation, p = 0, gives no
     * crack-closing benefit); Basquin life N = 0.5 (tau_eq / tau_f)^(-m);
     * D = sum n / N and D* = sum n tau_eq^m.
     *
     * @param p pressure history, n samples [Pa]
     * @param q tangential traction history, n samples [Pa]
     * @throws std::invalid_argument if the lengths differ.
     */
    FindleyDamage
    findley_damage(const std::vector<double> &p,
                   const std::vector<double> &q,
                   const FindleyParameters   &parameters);

    /** Crossland index of one node (Crossland 1956). */
    struct CrosslandIndex
    {
      double sqrt_j2_amplitude = 0.; ///< sqrt(J2,a) [Pa]
      double hydrostatic_max   = 0.; ///< sigma_H,max [Pa] (tension > 0)
      double index             = 0.; ///< sqrt(J2,a) + alpha sigma_H,max [Pa]
    };

    /**
     * Crossland index of the surface layer under pressure p and traction q,
     * laterally constrained: sigma_xx = sigma_yy = -nu / (1 - nu) p,
     * sigma_zz = -p, sigma_xz = q. Its deviator lies in a plane where
     * sqrt(J2) = |(sqrt(3) a p, q)|, a = (1 - 2 nu) / (3 (1 - nu)); sqrt(J2,a)
     * is the radius of the minimum circumscribed circle of the path there
     * (Welzl's algorithm in double precision).
     *
     * @param p, q histories of equal length [Pa]
     * @param poisson_ratio nu of the pad, 0 <= nu < 0.5
     * @param alpha Crossland's hydrostatic sensitivity [-]
     * @throws std::invalid_argument on different lengths or nu out of range.
     */
    CrosslandIndex
    crossland_index(const std::vector<double> &p,
                    const std::vector<double> &q,
                    double                     poisson_ratio,
                    double                     alpha);

    /** Statistics of one node's pressure and status histories. */
    struct NodeStatistics
    {
      double mean_pressure        = 0.; ///< [Pa]
      double relative_oscillation = 0.; ///< (max p - min p) / mean p [-]
      double max_pressure         = 0.; ///< [Pa]
      double separated_fraction   = 0.; ///< share of samples with status 0 [-]
      double stick_fraction       = 0.; ///< share of samples with status 1 [-]
      double slip_fraction        = 0.; ///< share of samples with status 2 [-]
      /// rainflow cycles of p whose range exceeds 10 % of the largest range,
      /// per second [1/s]: the squeal frequency where the pressure oscillates
      double cycles_per_second = 0.;
    };

    /**
     * Statistics of one node. @p status holds 0 (separated), 1 (stick) or
     * 2 (slip) per sample. @p sampling_rate in Hz.
     * @throws std::invalid_argument on different lengths or no samples.
     */
    NodeStatistics
    node_statistics(const std::vector<double> &p,
                    const std::vector<int>    &status,
                    double                     sampling_rate);
  } // namespace tribology
} // namespace squeal

#endif
