#ifndef squeal_updating_model_updating_h
#define squeal_updating_model_updating_h

/**
 * @file
 * Model updating against measured modes (experimental modal analysis):
 * the named parameters p of a model are fitted so that its natural
 * frequencies match measured ones, by a bounded Levenberg-Marquardt
 * iteration on the weighted relative frequency residuals
 *
 *   r_i(p) = sqrt(w_i) (f_i(p) - f_i,measured) / (sigma f_i,measured),
 *
 * sigma the relative standard deviation of a measured frequency of weight 1,
 * and, for a measured mode that has a damping ratio, a second residual
 *
 *   r_i'(p) = sqrt(w_i) (zeta_i(p) - zeta_i,measured)
 *             / (sigma_zeta zeta_i,measured),
 *
 * with the exact frequency sensitivities of the model (for a symmetric
 * pencil with M-orthonormal phi_k: d omega_k^2 / dp = phi_k^T (dK/dp -
 * omega_k^2 dM/dp) phi_k; R.L. Fox, M.P. Kapoor, AIAA J. 6 (1968)
 * 2426-2429, eq. 8). Each measured mode is paired with a model mode at every
 * evaluation: by the modal assurance criterion (MAC) where the measured
 * shape at the measurement points is given, by the mode's name otherwise,
 * by frequency when neither is given; the pairing is the optimal one-to-one
 * assignment (J.E. Mottershead, M.I. Friswell, Mech. Syst. Signal Process.
 * 7 (1993) 3-17, for the method; D. W. Marquardt, J. SIAM 11 (1963)
 * 431-441, for the iteration).
 *
 * A positive parameter is fitted on a log scale (x = ln p), so that the
 * step is relative; its uncertainty comes from the Jacobian J of the
 * residuals at the fitted point: Cov(x) = (J^T J)^+ (first-order, for
 * residuals of unit variance). The singular value decomposition of J names
 * the parameter combinations the data cannot determine (identifiability).
 */

#include <Eigen/Dense>

#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace squeal
{
  namespace updating
  {
    /** One fitted parameter. */
    struct Parameter
    {
      /// as given: a named parameter of the model (`pad.E`), or
      /// `<parameter>@<configuration>` for one fitted separately in one
      /// configuration (`pad on disc.k_n@225 N`: the interface at a load)
      std::string name;
      double      lower     = 0.;   ///< lower bound [the parameter's unit]
      double      upper     = 0.;   ///< upper bound, > lower [unit]
      bool        log_scale = true; ///< fit x = ln p (needs lower > 0)
      std::string scene_name;       ///< the model's parameter (`pad.E`)
      std::string configuration;    ///< "" all, else the one it applies to
    };

    /** One measured mode. */
    struct Target
    {
      std::string label;          ///< its name in reports
      double      frequency = 0.; ///< measured natural frequency [Hz], > 0
      /// > 0: the measured frequency's relative variance is sigma^2 / weight
      double weight = 1.;
      /// model mode name to pair with ("": none; see names_match(): a
      /// disc mode's name without its sign, alternatives split by `|`)
      std::string name;
      /// the model configuration it was measured in (ModelModes::
      /// configuration; 0: the model's nominal one)
      unsigned int configuration = 0;
      /// measured shape at the measurement points (any scale; empty: none)
      std::vector<double> shape;
      /// measured modal (viscous) damping ratio zeta [-] of the mode, in
      /// (0, 1); 0: not measured (no damping residual)
      double damping_ratio = 0.;
    };

    /** The modes of the model at one parameter point. */
    struct ModelModes
    {
      std::vector<double> frequency; ///< natural frequencies f_k [Hz]
      /// derivative[k][j] = d f_k / d p_j [Hz per unit of p_j]
      std::vector<std::vector<double>> derivative;
      std::vector<std::string>         name; ///< per mode ("" unnamed)
      /// per mode, its shape at the measurement points (empty: none)
      std::vector<std::vector<double>> shape;
      /// per mode, the configuration it belongs to (a model evaluated at
      /// several values of parameters that are not fitted, as a brake at
      /// two pad moduli); empty: every mode in configuration 0
      std::vector<unsigned int> configuration;
      /// per mode, its modal damping ratio zeta_k [-] (empty: the model
      /// gives none; needed when a target has a damping ratio)
      std::vector<double> damping_ratio;
      /// damping_derivative[k][j] = d zeta_k / d p_j [per unit of p_j]
      std::vector<std::vector<double>> damping_derivative;
    };

    /**
     * The model: its modes at the parameter values p (one per Parameter,
     * in their order, in their units). May throw std::runtime_error.
     */
    using ModalModel = std::function<ModelModes(const std::vector<double> &)>;

    /** Settings of update(). */
    struct Options
    {
      /// relative standard deviation sigma of a measured frequency of
      /// weight 1 [-]
      double measurement_error = 0.01;
      /// relative standard deviation of a measured damping ratio of weight
      /// 1 [-] (damping is measured far less precisely than frequency)
      double damping_error = 0.2;
      /// Levenberg-Marquardt iterations at most
      unsigned int max_iterations = 50;
      /// stop when an accepted step lowers the cost by less than this
      /// fraction, or the step is shorter than this (relative to x)
      double tolerance = 1e-10;
      /// least MAC of a pairing by shape, in (0, 1]
      double mac_threshold = 0.6;
      /// largest |f_model - f_measured| / f_measured of a pairing without
      /// shape
      double frequency_window = 0.5;
      /// singular values of J below this times the largest span the
      /// directions the data cannot determine
      double rank_tolerance = 1e-6;
      /// a parameter whose standard deviation exceeds this fraction of its
      /// value is reported as not identifiable
      double largest_relative_deviation = 1.;
    };

    /** The pairing of measured with model modes at one point. */
    struct Pairing
    {
      std::vector<int>    mode; ///< per target: its model mode
      std::vector<double> mac;  ///< per target: MAC with it (-1: no shape)
      /// MAC of every target (rows) with every model mode (columns); rows
      /// of targets without shape are -1; empty when no target has one
      Eigen::MatrixXd mac_matrix;
    };

    /**
     * Pairs every target with one model mode of its configuration, one to
     * one, by the optimal assignment: a target with a shape (and model shapes
     * of its length) by cost 1 - MAC, modes below Options::mac_threshold
     * forbidden (a mode whose frequency repeats to 1e-6, as a symmetric body's
     * doublet, by the MAC with the span of its group's shapes, since any
     * combination of them is a mode); a target with a name among the modes of
     * that name by relative frequency distance; any other by relative frequency
     * distance within Options::frequency_window.
     * @throws std::runtime_error naming the target that has no admissible
     *   mode (its best MAC, or that no mode has its name), and if a
     *   target's shape length differs from the model's.
     */
    /**
     * Whether a target's mode name @p wanted matches a model mode's name
     * @p name: equal, or @p wanted a disc mode's name without its sign,
     * `(n,m)`, and @p name `(n,m+)` or `(n,m-)`; @p wanted may list
     * alternatives separated by `|` (`(0,3+)|support y`: a disc mode that
     * the support's motion may dominate).
     */
    bool
    names_match(const std::string &wanted, const std::string &name);

    Pairing
    pair_targets(const std::vector<Target> &targets,
                 const ModelModes          &modes,
                 const Options             &options);

    /** One Levenberg-Marquardt trial. */
    struct Iteration
    {
      unsigned int        index    = 0; ///< 0: the start
      double              cost     = 0; ///< 1/2 sum r_i^2 at the trial point
      double              damping  = 0; ///< Marquardt's lambda of the step
      bool                accepted = false; ///< the cost went down
      std::vector<double> value;            ///< the trial parameters [units]
    };

    /** What update() found. */
    struct Result
    {
      std::vector<double> initial; ///< start values [units]
      std::vector<double> value;   ///< fitted values [units]
      /// first-order standard deviation of each fitted value [units];
      /// infinity when the data do not determine it
      std::vector<double> standard_deviation;
      std::vector<bool>   identifiable; ///< see Options
      std::vector<bool>   at_bound;     ///< the fit stopped on a bound
      /// singular values of J at the fitted point, descending
      Eigen::VectorXd singular_value;
      /// the right singular vectors (columns, in x = ln p or p / (upper -
      /// lower) per parameter), same order
      Eigen::MatrixXd singular_vector;
      ModelModes      initial_modes, modes; ///< at the start and fitted values
      Pairing         initial_pairing, pairing;     ///< ditto
      double          initial_cost = 0., cost = 0.; ///< 1/2 sum r_i^2
      unsigned int    iterations = 0;               ///< accepted steps
      bool            converged  = false; ///< false: iteration limit reached
      std::string     stop_reason;        ///< why it stopped
      std::vector<Iteration> history;     ///< every trial, the start first
    };

    /**
     * Fits @p parameters of @p model, starting at @p start (clipped into the
     * bounds), to @p targets (see the file's description). The parameters
     * must be determined by J only up to the null directions reported;
     * the step solves (J^T J + lambda D) dx = -J^T r with D the diagonal of
     * J^T J (Marquardt's scaling), clipped to the bounds.
     * @throws std::runtime_error on bad bounds (naming the parameter), no
     *   target, a target frequency or weight <= 0, a model without modes,
     *   a pairing that fails at the start (pair_targets()), or a model
     *   whose derivatives do not have one entry per parameter.
     */
    Result
    update(const ModalModel             &model,
           const std::vector<Parameter> &parameters,
           const std::vector<double>    &start,
           const std::vector<Target>    &targets,
           const Options                &options,
           std::ostream                 *log = nullptr);
  } // namespace updating
} // namespace squeal

#endif
