#ifndef squeal_parameters_parameters_h
#define squeal_parameters_parameters_h

/**
 * @file
 * Run parameters, one struct per subsection of the `.prm` file. Every struct
 * has static-like `declare_parameters` and `parse_parameters` members in the
 * style of the deal.II code-gallery; every entry has a default, a Patterns::
 * range and help text with SI units. All quantities are SI (m, kg, s, Pa, N).
 */

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace squeal
{
  namespace parameters
  {
    using dealii::ParameterHandler;

    /**
     * Which bodies the scene holds. `tribobrake`: disc, pad, support and
     * springs (thesis ch. 3); `disc`: the clamped disc alone (verification
     * A3).
     */
    struct Scene
    {
      std::string bodies = "tribobrake";
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** Dimensions of the TriboBrake (thesis § 3.2.1), in m. */
    struct Geometry
    {
      double disc_inner_radius = 0.05;   ///< m, clamped radius
      double disc_outer_radius = 0.12;   ///< m
      double disc_thickness    = 0.01;   ///< m, disc occupies -h <= z <= 0
      double pad_size          = 0.01;   ///< m, edge of the cubic pad
      double pad_radius        = 0.10;   ///< m, radius of the pad face centre
      double support_length    = 0.10;   ///< m, along the disc axis z
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** Mesh density per body and FE degree. */
    struct Mesh
    {
      unsigned int fe_degree             = 2;
      unsigned int disc_cells_circumference = 64;
      unsigned int disc_cells_radial     = 10;
      unsigned int disc_cells_thickness  = 2;
      unsigned int pad_cells_side        = 4; ///< across the pad face (x and y)
      unsigned int pad_cells_thickness   = 2;
      unsigned int support_cells_length  = 10; ///< along z; 10 divides 11 spring stations
      unsigned int disc_refinements_under_pad = 0;
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** Isotropic linear elastic material, SI units. */
    struct Material
    {
      double youngs_modulus = 210e9; ///< Pa
      double poisson_ratio  = 0.3;   ///< -
      double density        = 7800.; ///< kg/m^3
    };

    /** Materials per body (thesis § 3.2.2) and the model-updating switch. */
    struct Materials
    {
      Material disc;
      Material pad{25e9, 0.3, 2500.};
      Material support{210e9, 0.3, 7800.};
      /// `updated`: the calibrated support density; `steel`: 7800 kg/m^3.
      std::string support_density_model = "updated";
      double      support_updated_density = 76500.; ///< kg/m^3, calibrated value
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** The 4 x 11 tangential springs holding the support (thesis § 3.2.1). */
    struct Springs
    {
      unsigned int n_rows_per_side = 2;
      unsigned int n_per_row       = 11;
      double       stiffness       = 8.422e6; ///< N/m per spring
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** Rayleigh damping C = alpha M + beta K on the whole structure. */
    struct Damping
    {
      double alpha = 0.02; ///< 1/s
      double beta  = 1e-7; ///< s
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** Linear friction coupling of the CEA (thesis eq. 3-1). */
    struct Interface
    {
      double      normal_stiffness = 2.5895e12; ///< N/m^3 per unit area
      std::string sliding_direction = "rotation"; ///< `rotation` or "tx, ty"
      std::string rotation_sense    = "counterclockwise";
      std::string quadrature        = "mortar"; ///< `mortar` or `nodal`
      /// Unit sliding direction at the pad (z component 0), resolved from the
      /// above for a pad on the +x axis.
      dealii::Tensor<1, 3> sliding_tangent() const;
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** The eigensolvers and the frequency band. */
    struct Eigensolver
    {
      double       f_min = 900.;   ///< Hz
      double       f_max = 20000.; ///< Hz
      std::string  method = "reduced"; ///< `full` or `reduced`
      double       tolerance = 1e-10;
      double       target_frequency = 100.; ///< Hz, real shift -2 pi f
      double       unstable_tolerance = 1e-3; ///< 1/s on Re(lambda)
      std::vector<double> reduced_sample_moduli{1e9, 1e10, 1e11}; ///< Pa
      double       reduced_band_factor = 1.5;
      bool         reduced_enrichment = true;
      unsigned int n_check_points = 2;
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** The two swept parameters: pad modulus (log-spaced) and mu (a list). */
    struct Sweep
    {
      double              E_pad_min = 1e9;  ///< Pa
      double              E_pad_max = 1e11; ///< Pa
      unsigned int        n_E_pad   = 41;
      std::vector<double> mu{0.01, 0.1, 0.2, 0.3, 0.5, 0.7};
      /// Moduli of the sweep, log-spaced from min to max (Pa).
      std::vector<double> E_pad_values() const;
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** Where results go. */
    struct Output
    {
      std::string directory = "output/run";
      bool        overwrite = false;
      std::string mode_output = "unstable and first"; ///< or `none`, `all`
      void declare_parameters(ParameterHandler &prm) const;
      void parse_parameters(ParameterHandler &prm);
    };

    /** All parameters of a run. */
    struct AllParameters
    {
      Scene       scene;
      Geometry    geometry;
      Mesh        mesh;
      Materials   materials;
      Springs     springs;
      Damping     damping;
      Interface   interface;
      Eigensolver eigensolver;
      Sweep       sweep;
      Output      output;

      /** Declares every subsection with defaults, ranges and help. */
      void declare_parameters(ParameterHandler &prm) const;
      /**
       * Reads every subsection and checks cross-parameter consistency.
       * @throws std::runtime_error naming the parameter when a value is
       * outside what is allowed (for example f_min >= f_max).
       */
      void parse_parameters(ParameterHandler &prm);

      /**
       * Parses @p filename into @p prm and this object.
       * @throws std::runtime_error naming the file, the line and the entry on
       * a malformed file, an unknown entry, or a value outside its range.
       */
      void read(ParameterHandler &prm, const std::string &filename);
    };
  } // namespace parameters
} // namespace squeal

#endif
