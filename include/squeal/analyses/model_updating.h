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

    /**
     * Reads Model updating/Targets: a header line, then
     * `label,frequency_Hz,weight,name[,s_1,...,s_n]` per measured mode,
     * fields with commas in double quotes; an empty weight is 1; the shape
     * has no value or exactly @p n_points (one per measurement point).
     * @throws std::runtime_error naming the file and line on a frequency
     *   or weight that is not a number > 0, a shape of another length, a
     *   label given twice, or a file without modes.
     */
    std::vector<updating::Target>
    read_targets(const std::string &file, unsigned int n_points);

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
      updating::ModelModes
      modes_at(const std::vector<double> &values, bool with_names);
      void
      write_results(const updating::Result &result) const;

      const parameters::AllParameters &prm;
      const dealii::ParameterHandler  &handler;
      MPI_Comm                         comm;
      dealii::ConditionalOStream       pcout;
      dealii::TimerOutput              timer;
      physics::StructuralModel         model;
      std::string                      work_dir;

      std::vector<updating::Parameter>  parameters;
      std::vector<updating::Target>     targets;
      std::vector<MeasurementPoint>     points;
      std::unique_ptr<PointObservation> observation;
      double                            f_max        = 0.;
      bool                              names_needed = false;
      unsigned int                      n_solves     = 0;
      /// the full shapes of the last modes_at(), for the names
      std::vector<physics::PETScVector> last_shapes;
      parameters::ScalarPoint           last_point;
    };
  } // namespace analyses
} // namespace squeal

#endif
