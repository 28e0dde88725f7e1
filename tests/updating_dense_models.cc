// Model updating (updating/model_updating.h) on small spring-mass chains
// whose modes come from a dense generalised eigensolve (Eigen), the
// frequency derivatives from phi^T (K_p - omega^2 M_p) phi (mass-normalised
// phi), checked first against central differences of the eigensolve:
//  1. recovery: a 4-mass chain; "measured" frequencies and shapes at hidden
//     spring stiffnesses (x 1.3, 0.8, 1.15 of the start) with a fixed
//     pseudo-random noise of 0.1 % (sigma = 0.001): every fitted value lies
//     within 3 of its stated standard deviations of the hidden one, and the
//     deviations are small (< 2 %), the final cost is the noise's (chi^2
//     per degree of freedom < 5);
//  2. identifiability: the same chain with the four springs and a common
//     mass scale: frequencies depend on k / m only, so one direction
//     (1,1,1,1,1) / sqrt 5 is undetermined; all five are reported not
//     identifiable, the smallest singular value is below 1e-6 of the
//     largest and its vector is that direction (1e-6);
//  3. crossing modes: two oscillators (k_a / m, k_b / m) coupled weakly
//     swap their order between the start and the hidden point. Paired by
//     MAC the fit recovers k_a and k_b (1e-6); the control pairs by
//     frequency alone and lands on the swapped values, far from them.
//  4. two configurations of one model (a spring that is not fitted at two
//     values): every target paired with a mode of its own configuration,
//     the springs recovered within 3 deviations; a disc mode's name without
//     its sign matches both signs;
//  5. bad input: a target no mode pairs with is named in the error; bad
//     bounds are named; a damping target for a model that gives no damping
//     ratio, and a ratio outside [0, 1), are refused;
//  6. damping ratios as targets: the chain with Rayleigh damping (zeta_k =
//     alpha / 2 omega_k + beta omega_k / 2) recovers a spring, alpha and
//     beta within 3 deviations from frequencies (0.1 % noise) and ratios
//     (2 % noise).

#include <squeal/updating/model_updating.h>

#include <Eigen/Eigenvalues>

#include "check.h"

#include <cmath>

using test_tools::check;
using test_tools::check_true;
using namespace squeal;

namespace
{
  /** A chain of masses, each tied to the previous (the first to ground). */
  struct Chain
  {
    unsigned int n;
    // parameter j: 0..n-1 the springs' stiffness, n: a common mass scale
    Eigen::MatrixXd
    K(const std::vector<double> &k) const
    {
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
      for (unsigned int i = 0; i < n; ++i)
        {
          A(i, i) += k[i];
          if (i > 0)
            {
              A(i - 1, i - 1) += k[i];
              A(i - 1, i) -= k[i];
              A(i, i - 1) -= k[i];
            }
        }
      return A;
    }
  };

  /** Modes of (K, M) for K, M and their derivatives given by callables. */
  updating::ModelModes
  dense_modes(const Eigen::MatrixXd              &K,
              const Eigen::MatrixXd              &M,
              const std::vector<Eigen::MatrixXd> &dK,
              const std::vector<Eigen::MatrixXd> &dM)
  {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    updating::ModelModes                                      modes;
    for (int k = 0; k < K.rows(); ++k)
      {
        const double          w2  = es.eigenvalues()[k];
        const Eigen::VectorXd phi = es.eigenvectors().col(k); // M-normalised
        const double          f   = std::sqrt(w2) / (2 * M_PI);
        modes.frequency.push_back(f);
        std::vector<double> d;
        for (unsigned int j = 0; j < dK.size(); ++j)
          d.push_back(phi.dot((dK[j] - w2 * dM[j]) * phi) /
                      (8 * M_PI * M_PI * f));
        modes.derivative.push_back(d);
        modes.shape.emplace_back(phi.data(), phi.data() + phi.size());
        modes.name.push_back("");
      }
    return modes;
  }

  /** The chain's model with springs (and optionally a mass scale). */
  updating::ModalModel
  chain_model(const Chain &chain, const bool mass_scale)
  {
    return [chain, mass_scale](const std::vector<double> &p) {
      std::vector<double> k(p.begin(), p.begin() + chain.n);
      const double        m = mass_scale ? p[chain.n] : 1.;
      Eigen::MatrixXd     M = Eigen::MatrixXd::Identity(chain.n, chain.n);
      for (unsigned int i = 0; i < chain.n; ++i)
        M(i, i) = m * (1. + 0.25 * i);
      std::vector<Eigen::MatrixXd> dK, dM;
      for (unsigned int j = 0; j < p.size(); ++j)
        {
          std::vector<double> unit(chain.n, 0.);
          if (j < chain.n)
            unit[j] = 1.;
          dK.push_back(chain.K(unit));
          dM.push_back(j < chain.n ? Eigen::MatrixXd::Zero(chain.n, chain.n) :
                                     Eigen::MatrixXd(M / m));
        }
      return dense_modes(chain.K(k), M, dK, dM);
    };
  }

  /** Deterministic noise in [-1, 1] (a linear congruential sequence). */
  double
  noise(unsigned int &state)
  {
    state = 1664525u * state + 1013904223u;
    return 2. * (state / 4294967296.) - 1.;
  }

  std::vector<updating::Target>
  targets_of(const updating::ModelModes &modes,
             const double                relative_noise,
             const bool                  shapes)
  {
    std::vector<updating::Target> targets;
    unsigned int                  state = 12345;
    for (unsigned int k = 0; k < modes.frequency.size(); ++k)
      {
        updating::Target t;
        t.label     = "mode " + std::to_string(k + 1);
        t.frequency = modes.frequency[k] * (1. + relative_noise * noise(state));
        if (shapes)
          for (const double s : modes.shape[k])
            t.shape.push_back(s * (1. + 0.01 * noise(state)));
        targets.push_back(t);
      }
    return targets;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // the derivatives against central differences of the eigensolve
  const Chain               chain{4};
  const auto                model = chain_model(chain, true);
  const std::vector<double> p0{1e6, 2e6, 1.5e6, 1e6, 2.};
  {
    const auto base  = model(p0);
    double     worst = 0.;
    for (unsigned int j = 0; j < p0.size(); ++j)
      {
        const double        h  = 1e-5 * p0[j];
        std::vector<double> up = p0, down = p0;
        up[j] += h;
        down[j] -= h;
        const auto hi = model(up), lo = model(down);
        for (unsigned int k = 0; k < 4; ++k)
          worst =
            std::max(worst,
                     std::abs((hi.frequency[k] - lo.frequency[k]) / (2 * h) -
                              base.derivative[k][j]) *
                       p0[j] / base.frequency[k]);
      }
    check(
      "frequency derivatives against central differences", worst, 0., 1e-8, 1.);
  }

  // 1. recovery of hidden springs
  updating::Options options;
  options.measurement_error = 1e-3;
  {
    const std::vector<updating::Parameter> parameters{{"k1", 1e4, 1e8, true},
                                                      {"k2", 1e4, 1e8, true},
                                                      {"k3", 1e4, 1e8, true}};
    const std::vector<double>              hidden{1.3e6, 1.6e6, 1.725e6};
    const auto springs = [&](const std::vector<double> &k) {
      auto modes = model({k[0], k[1], k[2], 1e6, 2.});
      for (auto &d : modes.derivative)
        d.resize(3);
      return modes;
    };
    const auto targets = targets_of(springs(hidden), 1e-3, true);
    const auto result  = updating::update(
      springs, parameters, {1e6, 2e6, 1.5e6}, targets, options);
    check_true("recovery: converged", result.converged);
    for (unsigned int j = 0; j < 3; ++j)
      {
        const double sd = result.standard_deviation[j];
        check("recovery: " + parameters[j].name + " within 3 deviations",
              result.value[j],
              hidden[j],
              3 * sd,
              1.);
        check("recovery: " + parameters[j].name + " deviation below 2 %",
              sd / hidden[j],
              0.,
              0.02,
              1.);
        check_true("recovery: " + parameters[j].name + " identifiable",
                   result.identifiable[j]);
      }
    check("recovery: chi^2 per degree of freedom",
          2 * result.cost / (4 - 3),
          0.,
          5.,
          1.);
    check_true("recovery: the cost went down",
               result.cost < 1e-2 * result.initial_cost);
    for (unsigned int i = 0; i < 4; ++i)
      check("recovery: target " + std::to_string(i) + " paired by MAC",
            result.pairing.mac[i],
            1.,
            1e-3);
  }

  // 2. springs and a common mass scale: k / m is all the data see
  {
    std::vector<updating::Parameter> parameters;
    for (const char *name : {"k1", "k2", "k3", "k4"})
      parameters.push_back({name, 1e4, 1e8, true});
    parameters.push_back({"m", 0.1, 10., true});
    const auto targets =
      targets_of(model({1.3e6, 1.6e6, 1.725e6, 1.2e6, 3.}), 0., true);
    const auto result =
      updating::update(model, parameters, p0, targets, options);
    bool none = true;
    for (unsigned int j = 0; j < 5; ++j)
      none = none && !result.identifiable[j] &&
             std::isinf(result.standard_deviation[j]);
    check_true("k / m: all five reported not identifiable", none);
    check("k / m: smallest singular value",
          result.singular_value[4],
          0.,
          1e-6,
          result.singular_value[0]);
    double along = 0.;
    for (unsigned int j = 0; j < 5; ++j)
      along += result.singular_vector(j, 4) / std::sqrt(5.);
    check("k / m: the null direction is (1,1,1,1,1)/sqrt 5",
          std::abs(along),
          1.,
          1e-6);
    check("k / m: the frequencies are still fitted",
          result.cost,
          0.,
          1e-12,
          result.initial_cost);
  }

  // 3. two modes crossing between the start and the hidden point
  {
    const auto crossing = [](const std::vector<double> &p) {
      const double    kc = 2e4; // weak coupling
      Eigen::MatrixXd K(2, 2), M = Eigen::MatrixXd::Identity(2, 2);
      K << p[0] + kc, -kc, -kc, p[1] + kc;
      Eigen::MatrixXd dA = Eigen::MatrixXd::Zero(2, 2), dB = dA;
      dA(0, 0) = 1.;
      dB(1, 1) = 1.;
      return dense_modes(K,
                         M,
                         {dA, dB},
                         {Eigen::MatrixXd::Zero(2, 2),
                          Eigen::MatrixXd::Zero(2, 2)});
    };
    const std::vector<updating::Parameter> parameters{{"k_a", 1e4, 1e8, true},
                                                      {"k_b", 1e4, 1e8, true}};
    const std::vector<double>              hidden{3e6, 1.5e6}, start{1e6, 2e6};
    // measured: mode 1 is b's (lower), mode 2 is a's
    const auto targets = targets_of(crossing(hidden), 0., true);
    const auto by_mac =
      updating::update(crossing, parameters, start, targets, options);
    const auto before =
      updating::pair_targets(targets, crossing(start), options);
    check_true("crossing: at the start the measured lower mode pairs with the "
               "model's upper one",
               before.mode[0] == 1 && before.mode[1] == 0);
    for (unsigned int j = 0; j < 2; ++j)
      check("crossing, MAC pairing: " + parameters[j].name,
            by_mac.value[j],
            hidden[j],
            1e-6);
    auto frequency_only = targets;
    for (auto &t : frequency_only)
      t.shape.clear();
    const auto by_frequency =
      updating::update(crossing, parameters, start, frequency_only, options);
    check_true("crossing, control: frequency pairing lands on the swapped "
               "values (k_a low, k_b high)",
               by_frequency.value[0] < 0.6 * hidden[0] &&
                 by_frequency.value[1] > 1.5 * hidden[1]);
  }

  // 4. two configurations (the fourth spring at 1e6 and 3e6 N/m, not
  // fitted): the modes of both in one model, each target paired in its own
  {
    const auto two = [&](const std::vector<double> &k) {
      updating::ModelModes all;
      for (const unsigned int c : {0u, 1u})
        {
          auto modes = model({k[0], k[1], k[2], c == 0 ? 1e6 : 3e6, 2.});
          for (unsigned int m = 0; m < modes.frequency.size(); ++m)
            {
              all.frequency.push_back(modes.frequency[m]);
              modes.derivative[m].resize(3);
              all.derivative.push_back(modes.derivative[m]);
              all.shape.push_back(modes.shape[m]);
              all.name.push_back("");
              all.configuration.push_back(c);
            }
        }
      return all;
    };
    const std::vector<double> hidden{1.3e6, 1.6e6, 1.725e6};
    auto                      targets = targets_of(two(hidden), 1e-3, false);
    for (unsigned int i = 0; i < targets.size(); ++i)
      targets[i].configuration = i < 4 ? 0 : 1;
    const std::vector<updating::Parameter> parameters{{"k1", 1e4, 1e8, true},
                                                      {"k2", 1e4, 1e8, true},
                                                      {"k3", 1e4, 1e8, true}};
    const auto                             result =
      updating::update(two, parameters, {1e6, 2e6, 1.5e6}, targets, options);
    bool own = true;
    for (unsigned int i = 0; i < targets.size(); ++i)
      own = own && (result.pairing.mode[i] < 4) == (i < 4);
    check_true("configurations: every target paired in its own", own);
    for (unsigned int j = 0; j < 3; ++j)
      check("configurations: " + parameters[j].name + " within 3 deviations",
            result.value[j],
            hidden[j],
            3 * result.standard_deviation[j],
            1.);
  }
  check_true("names: (1,3) matches (1,3+) and (1,3-)",
             updating::names_match("(1,3)", "(1,3+)") &&
               updating::names_match("(1,3)", "(1,3-)"));
  check_true("names: (1,3+) does not match (1,3-), (1,3) not (1,30+)",
             !updating::names_match("(1,3+)", "(1,3-)") &&
               !updating::names_match("(1,3)", "(1,30+)") &&
               !updating::names_match("(1,3)", "(1,4+)"));
  check_true("names: alternatives (0,3+)|support y",
             updating::names_match("(0,3+)|support y", "support y") &&
               updating::names_match("(0,3+)|support y", "(0,3+)") &&
               !updating::names_match("(0,3+)|support y", "support x"));

  // 5. bad input
  {
    const auto one_spring = [&](const std::vector<double> &k) {
      auto modes = model({k[0], 2e6, 1.5e6, 1e6, 2.});
      for (auto &d : modes.derivative)
        d.resize(1);
      return modes;
    };
    auto targets    = targets_of(model(p0), 0., false);
    targets[0].name = "(0,2+)";
    test_tools::check_message(
      "bad input: unpaired named target",
      test_tools::error_of([&] {
        updating::update(
          one_spring, {{"k1", 1e4, 1e8, true}}, {1e6}, targets, options);
      }),
      {"target 'mode 1'", "no free mode of the model's 4 is named '(0,2+)'"});
    test_tools::check_message("bad input: bounds",
                              test_tools::error_of([&] {
                                updating::update(one_spring,
                                                 {{"k1", 0., 1e8, true}},
                                                 {1e6},
                                                 targets,
                                                 options);
                              }),
                              {"parameter k1 has bounds [0, 1e+08]",
                               "lower > 0 (log scale)"});
    targets[0].name          = "";
    targets[0].damping_ratio = 0.01;
    test_tools::check_message(
      "bad input: a damping target for a model without damping",
      test_tools::error_of([&] {
        updating::update(
          one_spring, {{"k1", 1e4, 1e8, true}}, {1e6}, targets, options);
      }),
      {"target 'mode 1' has a damping ratio, but the model gives none"});
    targets[0].damping_ratio = 1.5;
    test_tools::check_message("bad input: a damping ratio of 1.5",
                              test_tools::error_of([&] {
                                updating::update(one_spring,
                                                 {{"k1", 1e4, 1e8, true}},
                                                 {1e6},
                                                 targets,
                                                 options);
                              }),
                              {"target 'mode 1'", "a damping ratio in [0, 1)"});
  }

  // 6. damping ratios as targets: the chain with Rayleigh damping C =
  // alpha M + beta K, zeta_k = alpha / (2 omega_k) + beta omega_k / 2
  // (exact for proportional damping); k1, alpha and beta hidden, the
  // frequencies with 0.1 % and the ratios with 2 % noise
  {
    const auto damped = [&](const std::vector<double> &p) {
      auto modes = model({p[0], 2e6, 1.5e6, 1e6, 2.});
      for (unsigned int k = 0; k < modes.frequency.size(); ++k)
        {
          const double w  = 2 * M_PI * modes.frequency[k];
          const double dw = 2 * M_PI * modes.derivative[k][0];
          const double a = p[1], b = p[2];
          modes.derivative[k].assign({modes.derivative[k][0], 0., 0.});
          modes.damping_ratio.push_back(a / (2 * w) + b * w / 2);
          modes.damping_derivative.push_back(
            {(-a / (2 * w * w) + b / 2) * dw, 1. / (2 * w), w / 2});
        }
      return modes;
    };
    const std::vector<double> hidden{1.3e6, 20., 2e-5};
    auto                      targets = targets_of(damped(hidden), 1e-3, false);
    const auto                exact   = damped(hidden);
    unsigned int              state   = 777;
    for (unsigned int k = 0; k < targets.size(); ++k)
      targets[k].damping_ratio =
        exact.damping_ratio[k] * (1. + 0.02 * noise(state));
    updating::Options o = options;
    o.damping_error     = 0.02;
    const std::vector<updating::Parameter> parameters{
      {"k1", 1e4, 1e8, true},
      {"alpha", 1e-2, 1e4, true},
      {"beta", 1e-9, 1e-2, true}};
    const auto result =
      updating::update(damped, parameters, {1e6, 1., 1e-6}, targets, o);
    check_true("damping targets: converged", result.converged);
    for (unsigned int j = 0; j < 3; ++j)
      check("damping targets: " + parameters[j].name +
              " within 3 deviations, deviation below 10 %",
            std::abs(result.value[j] - hidden[j]) <=
                3 * result.standard_deviation[j] &&
              result.standard_deviation[j] < 0.1 * hidden[j],
            1.,
            0.);
    check("damping targets: cost down to the noise's (below 4 per target)",
          result.cost < 4. * targets.size(),
          1.,
          0.);
  }
  return test_tools::finish();
}
