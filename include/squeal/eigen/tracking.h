#ifndef squeal_eigen_tracking_h
#define squeal_eigen_tracking_h

/**
 * @file
 * Mode tracking across a parameter sweep and stability classification.
 * Near mode lock-in the two coalescing modes become parallel, so the complex
 * MAC alone cannot tell them apart; the matching cost therefore adds the
 * relative eigenvalue jump: cost = (1 - MAC) + w |lambda_a - lambda_b| /
 * |lambda_a|, and the links between consecutive points are the one-to-one
 * assignment of least total cost (the Hungarian method), a link allowed only
 * when MAC >= a threshold and cost < 1.5.
 */

#include <Eigen/Dense>

#include <complex>
#include <string>
#include <vector>

namespace squeal
{
  namespace eigen
  {
    /**
     * Assigns track ids to the modes of consecutive sweep points.
     * @param lambdas eigenvalues per point [1/s]
     * @param macs macs[p](i, j): MAC between mode i of point p-1 and mode j
     *   of point p (macs[0] unused), in [0, 1]
     * @param next_id first free track id; advanced past the ids used
     * @param weight w of the eigenvalue-jump term
     * @param mac_threshold the least MAC of a link: a mode whose every
     *   possible predecessor has a lower MAC (or a cost >= 1.5) starts a
     *   new track
     * @return track id of every mode of every point
     */
    std::vector<std::vector<int>>
    track_modes(const std::vector<std::vector<std::complex<double>>> &lambdas,
                const std::vector<Eigen::MatrixXd>                   &macs,
                int                                                  &next_id,
                const double weight        = 10.,
                const double mac_threshold = 0.3);

    /**
     * Whether an eigenvalue @p lambda [1/s] is unstable: Re lambda above
     * both @p tolerance [1/s] and @p relative_tolerance |lambda|.
     */
    inline bool
    is_unstable(const std::complex<double> lambda,
                const double               tolerance,
                const double               relative_tolerance)
    {
      return lambda.real() > tolerance &&
             lambda.real() > relative_tolerance * std::abs(lambda);
    }

    /**
     * One interval of the first swept parameter (for example the pad
     * modulus, Pa) over which a track is unstable, at one value of the second
     * (for example mu); units are those of the swept parameters.
     */
    struct UnstableRegion
    {
      double second;               ///< value of the second parameter
      double first_min, first_max; ///< the interval of the first parameter
      double f_min, f_max;         ///< Hz
      double max_re;               ///< 1/s
      int    track;
      int    partner_track = -1;    ///< the locking-in partner, -1 if none
      unsigned int point_of_max;    ///< sweep point index of max_re
      unsigned int first_point = 0; ///< sweep point index of its first point
      unsigned int last_point  = 0; ///< sweep point index of its last point
    };

    /**
     * The one-to-one assignment of rows to columns of an m x n @p cost
     * matrix (any sign, finite) that minimises the total cost over
     * min(m, n) pairs (the Hungarian method with potentials, O(k^3),
     * k = max(m, n)). Entries above @p reject count as forbidden: a row
     * whose best feasible assignment needs one is left unassigned.
     * @return the column of every row, -1 for an unassigned row
     */
    std::vector<int>
    optimal_assignment(const Eigen::MatrixXd &cost,
                       const double           reject = 1e300);

    /**
     * Unstable regions of one sweep of the first parameter at a fixed value
     * @p second of the second: maximal runs of consecutive points where a
     * track has Re lambda > tolerance [1/s]. The partner is the stable mode
     * nearest in frequency at the point of largest growth (the other member
     * of the lock-in).
     * @param first values of the first parameter per point (ascending or
     *   descending); @param point_index sweep point ids
     */
    std::vector<UnstableRegion>
    find_unstable_regions(
      const double                                          second,
      const std::vector<double>                            &first,
      const std::vector<unsigned int>                      &point_index,
      const std::vector<std::vector<std::complex<double>>> &lambdas,
      const std::vector<std::vector<int>>                  &tracks,
      const double                                          tolerance,
      const double relative_tolerance = 0.);
  } // namespace eigen
} // namespace squeal

#endif
