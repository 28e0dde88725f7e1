#ifndef squeal_tribology_correlation_h
#define squeal_tribology_correlation_h

/**
 * @file
 * Maps on a regular grid of the pad face and the statistics that compare
 * them: Pearson and Spearman correlation, ROC AUC, Moran's I, and a
 * toroidal-shift permutation test. Smooth maps are spatially autocorrelated,
 * so the naive p-value of a correlation between two of them is badly
 * overconfident; shifting one map cyclically against the other keeps each
 * map's autocorrelation and breaks only their alignment, which gives honest
 * p-values (the "toroidal shift" test of Fortin & Jacquez, Geogr. Anal.
 * 2000; Upton & Fingleton 1985).
 */

#include <functional>
#include <string>
#include <vector>

namespace squeal
{
  namespace tribology
  {
    /**
     * A scalar field on nx x ny square cells of the pad face. Cell (i, j)
     * covers [x0 + i h, x0 + (i + 1) h] x [y0 + j h, y0 + (j + 1) h] in
     * face coordinates [m] (x along the sliding direction, y along the
     * radius). A cell without data holds NaN.
     */
    struct GridMap
    {
      unsigned int        nx = 0, ny = 0;
      double              x0 = 0., y0 = 0., h = 1.; ///< m
      std::vector<double> values;                   ///< nx * ny, i + nx j

      GridMap() = default;
      /** An all-NaN map. */
      GridMap(unsigned int nx, unsigned int ny, double x0, double y0, double h);

      /** Value of cell (i, j), i < nx along s, j < ny along r. */
      double &
      operator()(unsigned int i, unsigned int j)
      {
        return values[i + nx * j];
      }
      /** Value of cell (i, j). */
      double
      operator()(unsigned int i, unsigned int j) const
      {
        return values[i + nx * j];
      }
      /** Index of the cell holding face point (x, y) [m], or -1 if none. */
      long
      cell_of(double x, double y) const;
      /** Same grid, all NaN. */
      GridMap
      empty_like() const;
    };

    /** Pearson correlation of the pairs where both are finite; NaN if
     * fewer than 3 pairs or a constant side. */
    double
    pearson(const std::vector<double> &a, const std::vector<double> &b);

    /** Spearman rank correlation (average ranks for ties) of the finite
     * pairs; NaN if fewer than 3 pairs. */
    double
    spearman(const std::vector<double> &a, const std::vector<double> &b);

    /**
     * Area under the ROC curve of @p score predicting @p label (non-zero =
     * positive) over the finite pairs, by the Mann-Whitney U statistic
     * (ties count one half). NaN if either class is empty.
     */
    double
    roc_auc(const std::vector<double> &score, const std::vector<double> &label);

    /** ROC curve points (false-positive rate, true-positive rate), from
     * (0, 0) to (1, 1), thresholds at every distinct score. */
    std::vector<std::pair<double, double>>
    roc_curve(const std::vector<double> &score,
              const std::vector<double> &label);

    /**
     * Moran's I of a map with queen-contiguity weights (the 8 neighbours
     * with data, weight 1): +1 smooth, about -1/(n-1) random, -1 a
     * chequerboard. NaN if fewer than 3 cells with data.
     */
    double
    morans_i(const GridMap &map);

    /** Result of a toroidal-shift test. */
    struct ToroidalTest
    {
      double       observed = 0.; ///< statistic of the aligned maps
      double       p_value  = 1.; ///< one-sided, larger is more extreme
      unsigned int n_shifts = 0;  ///< shifts with a finite statistic
    };

    /**
     * Toroidal-shift permutation test of statistic(a, b) against every
     * cyclic shift (di, dj) of @p b on its grid (nx ny shifts, the aligned
     * one included): p = #{shifts with statistic >= observed} / #shifts.
     * Exact for maps that are stationary on the torus.
     * @throws std::invalid_argument if the grids differ.
     */
    ToroidalTest
    toroidal_test(
      const GridMap                                            &a,
      const GridMap                                            &b,
      const std::function<double(const std::vector<double> &,
                                 const std::vector<double> &)> &statistic);
  } // namespace tribology
} // namespace squeal

#endif
