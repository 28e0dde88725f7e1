#ifndef squeal_tribology_tribology_analysis_h
#define squeal_tribology_tribology_analysis_h

/**
 * @file
 * The tribology analysis that `build/squeal-tribology FILE.prm` runs: fatigue
 * damage per contact node from a contact-stress history, crack and
 * exfoliation maps from SEM images of the pad, both on one grid of the pad
 * face, and their correlation. Parameters are deal.II parameter files, one
 * struct per subsection, SI units.
 */

#include <deal.II/base/parameter_handler.h>

#include <squeal/io/contact_history.h>
#include <squeal/tribology/correlation.h>
#include <squeal/tribology/fatigue.h>
#include <squeal/tribology/surface_images.h>
#include <squeal/tribology/synthetic_history.h>

#include <string>
#include <vector>

namespace squeal
{
  namespace tribology
  {
    using dealii::ParameterHandler;

    /** Subsection `Contact history`: where the stress histories come from. */
    struct HistoryInput
    {
      /// HDF5 file (contact_history.h), relative to the .prm file's folder;
      /// `synthetic` draws one (subsection `Synthetic history`); empty: no
      /// damage analysis (images only).
      std::string file       = "synthetic";
      double      start_time = 0.; ///< s, earlier samples (the ramp) dropped
      /// the pad face (contact pair name) to analyse; empty: the history's
      /// only face
      std::string face;
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Synthetic history` (see synthetic_squeal_history()). */
    struct SyntheticHistory
    {
      unsigned int nodes_per_side       = 11;
      unsigned int samples              = 10000;
      double       sampling_rate        = 1e6;   ///< Hz
      double       frequency            = 3400.; ///< Hz
      double       mean_pressure        = 1e6;   ///< Pa (100 N on 1e-4 m^2)
      double       friction_coefficient = 0.4;
      double       pad_size             = 0.01; ///< m
      double       pad_radius           = 0.1;  ///< m
      double trailing_amplitude = 0.1; ///< oscillation at the trailing edge
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Damage`: the fatigue indices and their sensitivity. */
    struct DamageSettings
    {
      FindleyParameters   findley;
      double              crossland_alpha = 0.3; ///< -
      double              poisson_ratio   = 0.3; ///< pad, -
      std::vector<double> sensitivity_k{0.1, 0.2, 0.3, 0.4, 0.5};
      std::vector<double> sensitivity_m{5., 8., 10., 12., 15.};
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Images`: SEM images and their detectors. */
    struct ImageSettings
    {
      /// image files relative to the .prm file (each with a sidecar of the
      /// same name and the extension .prm), `synthetic`, or empty (none)
      std::vector<std::string> files{"synthetic"};
      /// folder of the sidecars, relative to the .prm file; empty: beside
      /// each image (for images in a read-only folder)
      std::string           sidecar_folder;
      CrackParameters       cracks;
      ExfoliationParameters exfoliations;
      double micro_max_area = 1e-10; ///< m^2: micro-exfoliations below
      double macro_min_area = 1e-6;  ///< m^2: macro-exfoliations above
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Synthetic images`: SEM-like fields whose crack density
     * follows the damage map, for demonstrations. */
    struct SyntheticImages
    {
      unsigned int fields_per_side = 2;   ///< fields of view per face side
      unsigned int image_size      = 800; ///< px per side of one field
      double       cracks_per_cell = 4.; ///< mean count where damage is largest
      double       blobs_per_cell = 0.3; ///< mean count where damage is largest
      unsigned int seed           = 1;
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Correlation`. */
    struct CorrelationSettings
    {
      double cell_size = 1e-3; ///< m, grid of the pad face
      /// mm/mm^2: cells with a larger crack length per area are "cracked";
      /// a negative value takes the median over the imaged cells
      double cracked_threshold = -1.;
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** Subsection `Output`. */
    struct TribologyOutput
    {
      std::string directory = "output/tribology";
      bool        overwrite = false;
      /** Declares the subsection's entries with defaults, ranges, help. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads them back. @throws std::runtime_error on inconsistent values. */
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** All subsections. */
    struct TribologyParameters
    {
      HistoryInput        history;
      SyntheticHistory    synthetic_history;
      DamageSettings      damage;
      ImageSettings       images;
      SyntheticImages     synthetic_images;
      CorrelationSettings correlation;
      TribologyOutput     output;
      std::string         base_directory = "."; ///< folder of the .prm file

      /** Declares every subsection. */
      void
      declare_parameters(ParameterHandler &prm) const;
      /** Reads every subsection. @throws std::runtime_error on
       * inconsistent values (naming the parameter). */
      void
      parse_parameters(ParameterHandler &prm);
      /**
       * Declares, parses @p filename and checks the values.
       * @throws std::runtime_error naming the file and the line or the
       * parameter and what is allowed.
       */
      void
      read(ParameterHandler &prm, const std::string &filename);
    };

    /**
     * Placement of one image on the pad face, from its sidecar `.prm`:
     * `Pixel size` [m/px] (0: read the scale bar of length `Scale bar
     * length` [m]), `Placement` = centre | fiducials | affine with
     * `Centre` [m], `Rotation` [deg], `Fiducial pixels` (x,y; x,y [px]),
     * `Fiducial face coordinates` (s,r; s,r [m]), `Affine` (a11,a12,a13;
     * a21,a22,a23: face [m] = A (x, y, 1)), and an optional `Reference image`
     * (with its own sidecar) to refine the placement by ECC registration.
     */
    struct ImagePlacement
    {
      cv::Matx23d pixel_to_face;   ///< face [m] = A (x, y, 1)
      double      pixel_size = 0.; ///< m/px (sqrt of |det A|)
      std::string reference_image; ///< empty: none
    };

    /**
     * Reads the placement of the image @p pixels from @p sidecar (a `.prm`).
     * @throws std::runtime_error naming the sidecar and the parameter.
     */
    ImagePlacement
    read_image_placement(const std::string &sidecar, const cv::Mat &pixels);

    /** The sidecar of @p image: its path with the extension `.prm`, or that
     * file name in @p folder if it is not empty. */
    std::string
    sidecar_of(const std::string &image, const std::string &folder);

    /**
     * Refines the placement of @p image on the pad face by ECC registration
     * against @p reference, whose placement is trusted: the first guess of
     * the reference-to-image pixel map comes from the two placements, ECC
     * refines it (refine_registration()), and the image's pixel-to-face map
     * becomes the reference's composed with its inverse.
     * @return the refined placement (pixel size unchanged).
     * @throws std::runtime_error if ECC does not converge.
     */
    ImagePlacement
    refine_placement(const cv::Mat        &image,
                     const ImagePlacement &placement,
                     const cv::Mat        &reference,
                     const ImagePlacement &reference_placement);

    /** What one image gave. */
    struct ImageResult
    {
      std::string    file;         ///< path of the image
      ImagePlacement placement;    ///< on the pad face
      CrackMap       cracks;       ///< see detect_cracks()
      ExfoliationMap exfoliations; ///< see detect_exfoliations()
      unsigned int   micro = 0, meso = 0, macro = 0; ///< blob counts by class
      double         micro_area = 0., meso_area = 0., macro_area = 0.; ///< m^2
    };

    /**
     * The tribology analysis (tutorial shape): `setup` (output folder,
     * inputs), `compute_damage`, `analyse_images`, `correlate`,
     * `output_results`, `run`.
     */
    class TribologyAnalysis
    {
    public:
      /** Keeps references to @p prm and to the @p handler it was read with
       * (echoed into the output folder as parameters.prm). */
      TribologyAnalysis(const TribologyParameters &prm,
                        const ParameterHandler    &handler);
      /** Runs everything; results in Output/Directory (written to
       * DIRECTORY.partial, renamed at the end).
       * @throws std::runtime_error on bad input or an existing output
       * directory without Output/Overwrite. */
      void
      run();

    private:
      void
      setup();
      void
      compute_damage();
      void
      make_synthetic_images();
      void
      analyse_images();
      void
      build_maps();
      void
      correlate();
      void
      output_results();

      const TribologyParameters &prm;
      const ParameterHandler    &handler;
      std::string                work_dir;

      io::ContactHistory          history;
      std::vector<FindleyDamage>  findley;
      std::vector<CrosslandIndex> crossland;
      std::vector<NodeStatistics> statistics;
      std::vector<std::string>    image_files;
      std::vector<ImageResult>    images;

      GridMap log_damage, crack_density, crack_count, exfoliated, coverage,
        p_oscillation, separated;
      std::vector<std::vector<std::string>>  correlation_rows;
      std::vector<std::pair<double, double>> roc;
      std::string                            verdict;
    };
  } // namespace tribology
} // namespace squeal

#endif
