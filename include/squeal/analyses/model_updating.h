#ifndef squeal_analyses_model_updating_h
#define squeal_analyses_model_updating_h

/**
 * @file
 * The model updating analysis (Scene/Analysis = model updating): the named
 * parameters of subsection Model updating fitted to the measured modes of
 * its Targets file (updating::update()), the model's modes being those of
 * the frictionless assembly (K_s + K_n, M), every one below the maximum
 * frequency counted by Sylvester inertia and found by the symmetric
 * eigensolver at each step, with the exact frequency sensitivities from the
 * affine matrix parts. Writes, into the output folder,
 * updated_parameters.csv, targets.csv, identifiability.csv, history.csv,
 * modes.csv (every model mode at the fitted point), mac.csv (with
 * measurement points) and updated_parameters.prm.
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <squeal/eigen/reduced_model.h>
#include <squeal/physics/structural_model.h>
#include <squeal/updating/model_updating.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace squeal
{
  namespace analyses
  {
    /** A point where a shape was measured, and the direction measured. */
    struct MeasurementPoint
    {
      std::string          label;     ///< its name in reports
      dealii::Point<3>     x;         ///< position [m]
      dealii::Tensor<1, 3> direction; ///< unit vector
    };

    /**
     * Reads Model updating/Measurement points: a header line, then
     * `label,x,y,z,dx,dy,dz` per point [m; the direction of any non-zero
     * length, normalised].
     * @throws std::runtime_error naming the file and line on a missing or
     *   non-numeric field, a zero direction, or a file without points.
     */
    std::vector<MeasurementPoint>
    read_measurement_points(const std::string &file);

    /** A model configuration: values of parameters that are not fitted. */
    struct Configuration
    {
      std::string name; ///< "" for the file's own values
      /// the parameters it changes and their values [their units]
      std::vector<std::pair<std::string, double>> values;
    };

    /**
     * Parses Model updating/Configurations (`name: p = v, p = v; ...`).
     * @throws std::runtime_error naming the item on a missing name, a
     *   value that is not a number, or a name given twice.
     */
    std::vector<Configuration>
    parse_configurations(const std::string &text);

    /**
     * Reads Model updating/Targets: a header naming the columns (label,
     * frequency_Hz; optional weight, name, configuration and the shape
     * columns, whose headers start with `shape`), then one measured mode per
     * line, fields with commas in double quotes. An empty weight is 1; a
     * mode's shape values are all empty (no shape) or all given; a
     * configuration is "" (index 0) or one of @p configurations (its index
     * + 1).
     * @throws std::runtime_error naming the file and line on a missing
     *   column, a frequency or weight that is not a number > 0, a number
     *   of shape columns other than @p n_points, an unknown configuration
     *   (listing them), a label given twice, or a file without modes.
     */
    std::vector<updating::Target>
    read_targets(const std::string                &file,
                 unsigned int                      n_points,
                 const std::vector<Configuration> &configurations = {});

    /**
     * Parses Model updating/Parameters (`name: lower, upper[, linear]; ...`).
     * @throws std::runtime_error naming the item on a missing bound, a
     *   non-numeric bound or an unknown keyword.
     */
    std::vector<updating::Parameter>
    parse_updating_parameters(const std::string &text);

    /**
     * The displacement of the model's FE field at the measurement points
     * along their directions: each point is located in the mesh (through
     * the model's mapping) and its value is a fixed combination of DoFs
     * (hanging-node constraints resolved, held DoFs dropped).
     */
    class PointObservation
    {
    public:
      /**
       * Locates @p points in @p model's mesh. Collective.
       * @throws std::runtime_error naming a point that lies outside the
       *   mesh (farther than 1e-6 of the mesh's size).
       */
      PointObservation(const physics::StructuralModel      &model,
                       const std::vector<MeasurementPoint> &points);

      /** The values u(x_i) . d_i [the unit of @p u], one per point.
       * Collective. */
      std::vector<double>
      operator()(const physics::PETScVector &u) const;

      /** Number of points. */
      unsigned int
      size() const
      {
        return rows.size();
      }

    private:
      /// per point: the owned DoFs and their weights
      std::vector<
        std::vector<std::pair<dealii::types::global_dof_index, double>>>
               rows;
      MPI_Comm comm;
    };

    /** The analysis: see the file's description. */
    class ModelUpdatingAnalysis
    {
    public:
      /** Stores the parameters; nothing runs yet. */
      ModelUpdatingAnalysis(const parameters::AllParameters &prm,
                            const dealii::ParameterHandler  &handler,
                            MPI_Comm                         comm);

      /**
       * Builds the model, reads the measured data, fits, writes the results.
       * @throws std::runtime_error on bad measured data, an unknown
       *   parameter (listing the scene's), a target that cannot be paired
       *   at the start, a failed eigensolve or write.
       */
      void
      run();

    private:
      /// the named modes of every configuration a target uses, with their
      /// frequency derivatives and shapes at the measurement points
      updating::ModelModes
      modes_at(const std::vector<double> &values);
      /// as modes_at(), on the reduced model (Method = reduced): the
      /// symmetric problem projected on the basis, its exact derivatives
      updating::ModelModes
      reduced_modes_at(const std::vector<double> &values);
      /// Method = reduced: rounds of Levenberg-Marquardt on the reduced
      /// model of the full modes at the round's point and the one before,
      /// each within a trust region about its point and confirmed by a
      /// full solve at its end (at most 20 rounds)
      updating::Result
      fit_reduced(const std::vector<double> &start,
                  const updating::Options   &options);
      /// appends one mode (frequency @p f [Hz], its derivatives @p d, the
      /// M-normalised shape @p phi) of configuration @p c at @p p to
      /// @p result, with its shape at the points and its name (collective)
      void
      append_mode(updating::ModelModes          &result,
                  const unsigned int             c,
                  const parameters::ScalarPoint &p,
                  const double                   f,
                  std::vector<double>          &&d,
                  const physics::PETScVector    &phi,
                  const physics::PETScVector    &zero) const;
      /// the point of configuration @p c at @p values, with the names of
      /// the parameters acting there and, per parameter, its index among
      /// them (-1: it does not act there)
      parameters::ScalarPoint
      configuration_point(const unsigned int         c,
                          const std::vector<double> &values,
                          std::vector<std::string>  &names,
                          std::vector<int>          &column) const;
      /// the log's summary, then write_files() on rank 0 (collective)
      void
      write_results(const updating::Result &result) const;
      /// the output files (rank 0)
      void
      write_files(const updating::Result &result) const;

      const parameters::AllParameters &prm;
      const dealii::ParameterHandler  &handler;
      MPI_Comm                         comm;
      dealii::ConditionalOStream       pcout;
      dealii::TimerOutput              timer;
      physics::StructuralModel         model;
      std::string                      work_dir;

      std::vector<updating::Parameter> parameters;
      /// the file's values first, then Model updating/Configurations
      std::vector<Configuration>        configurations;
      std::vector<bool>                 used; ///< per configuration
      std::vector<updating::Target>     targets;
      std::vector<MeasurementPoint>     points;
      std::unique_ptr<PointObservation> observation;
      double                            f_max    = 0.;
      unsigned int                      n_solves = 0;
      /// a target has a damping ratio: the modes carry theirs
      bool with_damping = false;
      /// the reduced model (Method = reduced) and the modes of the last
      /// full solve, up to basis_factor x the maximum frequency
      std::unique_ptr<eigen::ReducedModel> reduced;
      std::vector<physics::PETScVector>    basis_candidates;
      static constexpr double              basis_factor = 1.5;
      /// a reduced round moves a (log-scaled) parameter by this factor at
      /// most
      static constexpr double trust_factor = 4.;
      unsigned int            n_reduced    = 0;
    };
  } // namespace analyses
} // namespace squeal

#endif
