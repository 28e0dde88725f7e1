// The tribology analysis: contact-stress histories -> fatigue-damage indices
// per pad node; SEM images -> crack and exfoliation maps; both on one grid
// of the pad face -> correlation with honest (toroidal-shift) significance.
//
// The parameters follow the rest of squeal: one struct per subsection, every
// entry with a default, a range and help with SI units. Results go into
// DIRECTORY.partial, renamed at the end, so an interrupted run never looks
// like a finished one and never replaces an earlier result.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <squeal/output/output_directory.h>
#include <squeal/tribology/tribology_analysis.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>

namespace squeal
{
  namespace tribology
  {
    namespace fs = std::filesystem;
    using dealii::Patterns::Anything;
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::List;
    using dealii::Patterns::Selection;

    namespace
    {
      const double nan = std::numeric_limits<double>::quiet_NaN();

      std::vector<double>
      parse_doubles(const std::string &text, const std::string &what)
      {
        std::vector<double> out;
        for (const std::string &s : dealii::Utilities::split_string_list(text))
          {
            try
              {
                std::size_t pos = 0;
                out.push_back(std::stod(s, &pos));
                if (pos != s.size())
                  throw std::invalid_argument(s);
              }
            catch (const std::exception &)
              {
                throw std::runtime_error(what + ": '" + s +
                                         "' is not a number");
              }
          }
        return out;
      }

      // "x,y; x,y; ..." -> points
      std::vector<cv::Point2d>
      parse_points(const std::string &text, const std::string &what)
      {
        std::vector<cv::Point2d> out;
        for (const std::string &p :
             dealii::Utilities::split_string_list(text, ';'))
          {
            const std::vector<double> v = parse_doubles(p, what);
            if (v.size() != 2)
              throw std::runtime_error(what + ": '" + p +
                                       "' is not a pair x, y");
            out.emplace_back(v[0], v[1]);
          }
        return out;
      }

      // Folds deal.II's multi-line exception text into one line.
      std::string
      one_line(const dealii::ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        std::istringstream words(info.str());
        std::string        folded, w;
        while (words >> w)
          folded += (folded.empty() ? "" : " ") + w;
        return folded;
      }

      void
      parse_file(ParameterHandler &prm, const std::string &filename)
      {
        if (!std::ifstream(filename))
          throw std::runtime_error("cannot open parameter file '" + filename +
                                   "'");
        try
          {
            prm.parse_input(filename, "", false, true);
          }
        catch (const dealii::ExceptionBase &e)
          {
            throw std::runtime_error("in parameter file '" + filename +
                                     "': " + one_line(e));
          }
      }

      std::string
      resolve(const std::string &base, const std::string &file)
      {
        return fs::path(file).is_absolute() ? file :
                                              (fs::path(base) / file).string();
      }
    } // namespace

    // ---------------------------------------------------------------------
    // Parameters

    void
    HistoryInput::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Contact history");
      prm.declare_entry(
        "File", file, Anything(),
        "HDF5 contact history (layout in doc/tribology.md), relative to this "
        "file's folder; 'synthetic' draws a squeal-like one (subsection "
        "Synthetic history); empty: no damage analysis, images only.");
      prm.declare_entry("Start time", std::to_string(start_time),
                        Double(0.),
                        "Samples before this time [s] are dropped (the load "
                        "ramp).");
      prm.leave_subsection();
    }

    void
    HistoryInput::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact history");
      file       = prm.get("File");
      start_time = prm.get_double("Start time");
      prm.leave_subsection();
    }

    void
    SyntheticHistory::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Synthetic history");
      prm.declare_entry("Nodes per side", std::to_string(nodes_per_side),
                        Integer(2, 201), "Pad-face nodes along each side.");
      prm.declare_entry("Samples", std::to_string(samples),
                        Integer(2, 100000000), "Samples per node.");
      prm.declare_entry("Sampling rate", "1e6", Double(1.),
                        "Sampling rate [Hz].");
      prm.declare_entry("Frequency", "3400", Double(1.),
                        "Squeal frequency [Hz] (the thesis' 3.4 kHz).");
      prm.declare_entry("Mean pressure", "1e6", Double(0.),
                        "Mean contact pressure [Pa] (100 N on the 1e-4 m^2 "
                        "face).");
      prm.declare_entry("Friction coefficient", "0.4", Double(0.),
                        "q = mu p [-].");
      prm.declare_entry("Pad size", "0.01", Double(1e-6), "Pad face edge [m].");
      prm.declare_entry("Pad radius", "0.1", Double(0.),
                        "Radius of the pad face centre [m].");
      prm.declare_entry("Trailing amplitude", "0.1", Double(0., 1.),
                        "Oscillation amplitude at the trailing edge relative "
                        "to the leading edge [-].");
      prm.leave_subsection();
    }

    void
    SyntheticHistory::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Synthetic history");
      nodes_per_side       = prm.get_integer("Nodes per side");
      samples              = prm.get_integer("Samples");
      sampling_rate        = prm.get_double("Sampling rate");
      frequency            = prm.get_double("Frequency");
      mean_pressure        = prm.get_double("Mean pressure");
      friction_coefficient = prm.get_double("Friction coefficient");
      pad_size             = prm.get_double("Pad size");
      pad_radius           = prm.get_double("Pad radius");
      trailing_amplitude   = prm.get_double("Trailing amplitude");
      prm.leave_subsection();
    }

    void
    DamageSettings::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Damage");
      prm.declare_entry("Findley k", "0.3", Double(0., 2.),
                        "Normal-stress sensitivity k of tau_eq = dq/2 - k "
                        "p_min [-] (0.2-0.3 for most materials).");
      prm.declare_entry("Basquin exponent", "10", Double(1., 50.),
                        "m = -1/b of the Basquin law N = 0.5 (tau_eq / "
                        "tau_f)^(-m) [-]. No S-N data of phenolic friction "
                        "materials is published: the indices are relative.");
      prm.declare_entry("Shear fatigue strength", "20e6", Double(1.),
                        "tau_f' of the Basquin law [Pa] (an assumed scale; "
                        "only the Palmgren-Miner D uses it).");
      prm.declare_entry("Rainflow residue", "half cycles",
                        Selection("half cycles|repeating"),
                        "Residue of the rainflow count: 'half cycles' "
                        "(ASTM E1049-85, transient histories) or "
                        "'repeating' (the record is one period of a limit "
                        "cycle).");
      prm.declare_entry("Crossland alpha", "0.3", Double(0., 3.),
                        "Hydrostatic sensitivity of the Crossland index "
                        "sqrt(J2,a) + alpha sigma_H,max [-].");
      prm.declare_entry("Pad Poisson ratio", "0.3", Double(0., 0.4999),
                        "nu of the laterally constrained surface layer [-].");
      prm.declare_entry("Sensitivity k values", "0.1, 0.2, 0.3, 0.4, 0.5",
                        List(Double(0., 2.)),
                        "k values of the sensitivity table (rank correlation "
                        "of the damage map to the default one).");
      prm.declare_entry("Sensitivity m values", "5, 8, 10, 12, 15",
                        List(Double(1., 50.)),
                        "Basquin exponents of the sensitivity table.");
      prm.leave_subsection();
    }

    void
    DamageSettings::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Damage");
      findley.k       = prm.get_double("Findley k");
      findley.m       = prm.get_double("Basquin exponent");
      findley.tau_f   = prm.get_double("Shear fatigue strength");
      findley.residue = residue_from_string(prm.get("Rainflow residue"));
      crossland_alpha = prm.get_double("Crossland alpha");
      poisson_ratio   = prm.get_double("Pad Poisson ratio");
      sensitivity_k =
        parse_doubles(prm.get("Sensitivity k values"), "Damage/Sensitivity k values");
      sensitivity_m =
        parse_doubles(prm.get("Sensitivity m values"), "Damage/Sensitivity m values");
      prm.leave_subsection();
    }

    void
    ImageSettings::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Images");
      prm.declare_entry(
        "Files", "synthetic", Anything(),
        "Comma-separated SEM images (8/16-bit PNG, TIFF, BMP) relative to "
        "this file's folder, each with a sidecar of the same name ending in "
        ".prm (pixel size and placement on the pad face); 'synthetic' draws "
        "fields whose crack density follows the damage map; empty: none.");
      prm.declare_entry("Sidecar folder", "", Anything(),
                        "Folder of the sidecars, relative to this file's "
                        "folder; empty: beside each image.");
      prm.declare_entry("Crack contrast", "dark", Selection("dark|bright"),
                        "Cracks are darker (or brighter) than the surface.");
      prm.declare_entry("Crack scales", "1, 1.5, 2, 3", List(Double(0.3, 50.)),
                        "Gaussian scales of the Frangi ridge filter [px], "
                        "about the crack half-widths.");
      prm.declare_entry("Frangi beta", "0.5", Double(0.05, 5.),
                        "Blob suppression of the Frangi filter [-].");
      prm.declare_entry("Ridge noise floor", "3", Double(0.),
                        "Ridges weaker than this many times the median "
                        "Hessian norm of the image are noise or texture "
                        "[-]: lower it for smooth images with faint cracks, "
                        "raise it for noisy ones.");
      prm.declare_entry("Background degree", "2", Integer(0, 4),
                        "Degree of the polynomial that flattens uneven "
                        "brightness.");
      prm.declare_entry("Minimum crack length", "15", Double(0.),
                        "Shorter cracks are dropped [px].");
      prm.declare_entry("Exfoliation contrast", "dark",
                        Selection("dark|bright"),
                        "Exfoliations are darker (or brighter) than the "
                        "surface.");
      prm.declare_entry("Exfoliation opening radius", "3", Integer(0, 50),
                        "Radius of the opening that removes cracks from the "
                        "exfoliation mask [px]: above a crack's half-width.");
      prm.declare_entry("Minimum exfoliation area", "20", Double(0.),
                        "Smaller blobs are dropped [px^2].");
      prm.declare_entry("Micro exfoliation area", "1e-10", Double(0.),
                        "Blobs below this area are micro-exfoliations [m^2] "
                        "(the thesis: a few um^2).");
      prm.declare_entry("Macro exfoliation area", "1e-6", Double(0.),
                        "Blobs above this area are macro-exfoliations [m^2] "
                        "(the thesis: > 1 mm^2).");
      prm.leave_subsection();
    }

    void
    ImageSettings::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Images");
      files = dealii::Utilities::split_string_list(prm.get("Files"));
      sidecar_folder = prm.get("Sidecar folder");
      cracks.dark   = prm.get("Crack contrast") == "dark";
      cracks.scales = parse_doubles(prm.get("Crack scales"), "Images/Crack scales");
      cracks.beta   = prm.get_double("Frangi beta");
      cracks.noise_floor = prm.get_double("Ridge noise floor");
      cracks.background_degree = prm.get_integer("Background degree");
      cracks.min_length        = prm.get_double("Minimum crack length");
      exfoliations.dark = prm.get("Exfoliation contrast") == "dark";
      exfoliations.background_degree = cracks.background_degree;
      exfoliations.opening_radius =
        prm.get_integer("Exfoliation opening radius");
      exfoliations.min_area = prm.get_double("Minimum exfoliation area");
      micro_max_area        = prm.get_double("Micro exfoliation area");
      macro_min_area        = prm.get_double("Macro exfoliation area");
      if (micro_max_area > macro_min_area)
        throw std::runtime_error(
          "Images/Micro exfoliation area must not exceed Images/Macro "
          "exfoliation area");
      prm.leave_subsection();
    }

    void
    SyntheticImages::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Synthetic images");
      prm.declare_entry("Fields per side", "2", Integer(1, 10),
                        "Fields of view along each side of the pad face.");
      prm.declare_entry("Image size", "800", Integer(64, 8000),
                        "Pixels per side of one field.");
      prm.declare_entry("Cracks per cell", "4", Double(0.),
                        "Mean crack count per map cell where damage is "
                        "largest (it falls with the damage rank).");
      prm.declare_entry("Exfoliations per cell", "0.3", Double(0.),
                        "Mean exfoliation count per map cell where damage is "
                        "largest.");
      prm.declare_entry("Seed", "1", Integer(0), "Random seed.");
      prm.leave_subsection();
    }

    void
    SyntheticImages::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Synthetic images");
      fields_per_side = prm.get_integer("Fields per side");
      image_size      = prm.get_integer("Image size");
      cracks_per_cell = prm.get_double("Cracks per cell");
      blobs_per_cell  = prm.get_double("Exfoliations per cell");
      seed            = prm.get_integer("Seed");
      prm.leave_subsection();
    }

    void
    CorrelationSettings::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Correlation");
      prm.declare_entry("Cell size", "1e-3", Double(1e-7),
                        "Edge of the square cells of the pad-face grid [m]: "
                        "two to three times the registration error at least.");
      prm.declare_entry("Cracked threshold", "-1", Double(),
                        "Crack length per area [mm/mm^2] above which a cell "
                        "counts as cracked (ROC AUC); negative: the median "
                        "over the imaged cells.");
      prm.leave_subsection();
    }

    void
    CorrelationSettings::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Correlation");
      cell_size         = prm.get_double("Cell size");
      cracked_threshold = prm.get_double("Cracked threshold");
      prm.leave_subsection();
    }

    void
    TribologyOutput::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Directory", directory, Anything(),
                        "Output folder, relative to the working directory.");
      prm.declare_entry("Overwrite", "false", Bool(),
                        "Replace an existing output folder.");
      prm.declare_entry("Plots", "true", Bool(),
                        "Write PNG maps and the correlation report "
                        "(scripts/plot_tribology.py, matplotlib).");
      prm.leave_subsection();
    }

    void
    TribologyOutput::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory = prm.get("Directory");
      overwrite = prm.get_bool("Overwrite");
      plots     = prm.get_bool("Plots");
      if (directory.empty())
        throw std::runtime_error("Output/Directory must not be empty");
      prm.leave_subsection();
    }

    void
    TribologyParameters::declare_parameters(ParameterHandler &prm) const
    {
      history.declare_parameters(prm);
      synthetic_history.declare_parameters(prm);
      damage.declare_parameters(prm);
      images.declare_parameters(prm);
      synthetic_images.declare_parameters(prm);
      correlation.declare_parameters(prm);
      output.declare_parameters(prm);
    }

    void
    TribologyParameters::parse_parameters(ParameterHandler &prm)
    {
      history.parse_parameters(prm);
      synthetic_history.parse_parameters(prm);
      damage.parse_parameters(prm);
      images.parse_parameters(prm);
      synthetic_images.parse_parameters(prm);
      correlation.parse_parameters(prm);
      output.parse_parameters(prm);
      if (images.files.size() == 1 && images.files[0] == "synthetic" &&
          history.file.empty())
        throw std::runtime_error(
          "Images/Files = synthetic draws cracks from the damage map: it "
          "needs a Contact history/File");
    }

    void
    TribologyParameters::read(ParameterHandler &prm, const std::string &filename)
    {
      declare_parameters(prm);
      parse_file(prm, filename);
      base_directory = fs::path(filename).parent_path().string();
      if (base_directory.empty())
        base_directory = ".";
      try
        {
          parse_parameters(prm);
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error("in parameter file '" + filename +
                                   "': " + e.what());
        }
    }

    std::string
    sidecar_of(const std::string &image, const std::string &folder)
    {
      const fs::path beside = fs::path(image).replace_extension(".prm");
      return folder.empty() ? beside.string() :
                              (fs::path(folder) / beside.filename()).string();
    }

    ImagePlacement
    read_image_placement(const std::string &sidecar, const cv::Mat &pixels)
    {
      ParameterHandler p;
      p.declare_entry("Pixel size", "0", Double(0.),
                      "m/px; 0: read the scale bar");
      p.declare_entry("Scale bar length", "0", Double(0.), "m");
      p.declare_entry("Placement", "centre",
                      Selection("centre|fiducials|affine"), "");
      p.declare_entry("Centre", "0, 0", Anything(), "face point [m]");
      p.declare_entry("Rotation", "0", Double(-360., 360.), "deg");
      p.declare_entry("Fiducial pixels", "", Anything(), "x,y; x,y [px]");
      p.declare_entry("Fiducial face coordinates", "", Anything(),
                      "s,r; s,r [m]");
      p.declare_entry("Affine", "", Anything(), "a11,a12,a13; a21,a22,a23");
      p.declare_entry("Reference image", "", Anything(), "");
      parse_file(p, sidecar);
      const std::string where = "sidecar '" + sidecar + "': ";
      try
        {
          ImagePlacement out;
          double         pixel = p.get_double("Pixel size");
          if (pixel == 0. && p.get("Placement") == "centre")
            {
              const double bar = p.get_double("Scale bar length");
              if (bar <= 0.)
                throw std::runtime_error(
                  "give Pixel size > 0 or a Scale bar length > 0 to detect");
              pixel = detect_scale_bar(pixels, bar);
            }
          const std::string placement = p.get("Placement");
          if (placement == "centre")
            {
              const std::vector<double> c =
                parse_doubles(p.get("Centre"), "Centre");
              if (c.size() != 2)
                throw std::runtime_error("Centre must be two numbers s, r [m]");
              const double a = p.get_double("Rotation") * M_PI / 180.;
              // displayed image: x right, rows down; face: s right, r up
              const double ca = pixel * std::cos(a), sa = pixel * std::sin(a);
              const double cx = 0.5 * (pixels.cols - 1),
                           cy = 0.5 * (pixels.rows - 1);
              out.pixel_to_face =
                cv::Matx23d(ca, sa, c[0] - ca * cx - sa * cy, sa, -ca,
                            c[1] - sa * cx + ca * cy);
            }
          else if (placement == "fiducials")
            out.pixel_to_face = affine_from_fiducials(
              parse_points(p.get("Fiducial pixels"), "Fiducial pixels"),
              parse_points(p.get("Fiducial face coordinates"),
                           "Fiducial face coordinates"));
          else
            {
              const std::vector<std::string> rows =
                dealii::Utilities::split_string_list(p.get("Affine"), ';');
              if (rows.size() != 2)
                throw std::runtime_error(
                  "Affine must be two rows a11,a12,a13; a21,a22,a23");
              cv::Matx23d A;
              for (int i = 0; i < 2; ++i)
                {
                  const std::vector<double> r = parse_doubles(rows[i], "Affine");
                  if (r.size() != 3)
                    throw std::runtime_error("Affine: each row has 3 numbers");
                  for (int j = 0; j < 3; ++j)
                    A(i, j) = r[j];
                }
              out.pixel_to_face = A;
            }
          const cv::Matx23d &A = out.pixel_to_face;
          const double det = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
          if (!(std::abs(det) > 0.))
            throw std::runtime_error("the placement is singular");
          out.pixel_size = std::sqrt(std::abs(det));
          if (pixel > 0. && std::abs(out.pixel_size / pixel - 1.) > 0.05)
            throw std::runtime_error(
              "Pixel size " + std::to_string(pixel) +
              " m disagrees with the placement's scale " +
              std::to_string(out.pixel_size) + " m/px by more than 5 %");
          const std::string ref = p.get("Reference image");
          if (!ref.empty())
            out.reference_image =
              resolve(fs::path(sidecar).parent_path().string(), ref);
          return out;
        }
      catch (const std::exception &e)
        {
          throw std::runtime_error(where + e.what());
        }
    }

    ImagePlacement
    refine_placement(const cv::Mat        &image,
                     const ImagePlacement &placement,
                     const cv::Mat        &reference,
                     const ImagePlacement &reference_placement)
    {
      const auto square = [](const cv::Matx23d &A) {
        cv::Matx33d M = cv::Matx33d::eye();
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 3; ++j)
            M(i, j) = A(i, j);
        return M;
      };
      const cv::Matx33d Ai = square(placement.pixel_to_face),
                        Ar = square(reference_placement.pixel_to_face);
      // reference pixel -> face -> image pixel
      const cv::Matx33d W0 = Ai.inv() * Ar;
      const cv::Matx23d W =
        refine_registration(image, reference, cv::Matx23d(W0.val), 5);
      const cv::Matx33d refined = Ar * square(W).inv();
      ImagePlacement    out     = placement;
      out.pixel_to_face         = cv::Matx23d(refined.val);
      return out;
    }

    // ---------------------------------------------------------------------
    // The analysis

    TribologyAnalysis::TribologyAnalysis(const TribologyParameters &prm,
                                         const ParameterHandler    &handler)
      : prm(prm)
      , handler(handler)
    {}

    void
    TribologyAnalysis::setup()
    {
      work_dir =
        output::partial_directory(prm.output.directory, prm.output.overwrite);
      output::fresh_directory(work_dir, "images");
      std::ofstream out(fs::path(work_dir) / "parameters.prm");
      handler.print_parameters(out, ParameterHandler::PRM);

      if (prm.history.file == "synthetic")
        {
          const SyntheticHistory &s = prm.synthetic_history;
          history = synthetic_squeal_history(
            s.nodes_per_side, s.samples, s.sampling_rate, s.frequency,
            s.mean_pressure, s.friction_coefficient, s.pad_size,
            s.pad_radius, s.trailing_amplitude);
          write_contact_history((fs::path(work_dir) / "contact_history.h5")
                                  .string(),
                                history);
          std::cout << "Synthetic contact history: " << history.n_nodes()
                    << " nodes x " << history.n_samples() << " samples at "
                    << history.sampling_rate << " Hz (written to "
                    << "contact_history.h5)" << std::endl;
        }
      else if (!prm.history.file.empty())
        {
          history = read_contact_history(
            resolve(prm.base_directory, prm.history.file));
          std::cout << "Contact history " << prm.history.file << ": "
                    << history.n_nodes() << " nodes x "
                    << history.n_samples() << " samples at "
                    << history.sampling_rate << " Hz" << std::endl;
        }
      if (history.n_nodes() > 0 && prm.history.start_time > 0.)
        {
          const std::size_t first =
            std::lower_bound(history.time.begin(), history.time.end(),
                             prm.history.start_time) -
            history.time.begin();
          if (first + 2 > history.n_samples())
            throw std::runtime_error(
              "Contact history/Start time leaves fewer than 2 samples");
          const auto cut = [first](auto &rows) {
            for (auto &r : rows)
              r.erase(r.begin(), r.begin() + first);
          };
          history.time.erase(history.time.begin(),
                             history.time.begin() + first);
          cut(history.p_N);
          cut(history.t_T1);
          cut(history.t_T2);
          cut(history.slip_velocity);
          cut(history.status);
        }

      // The grid of the pad face: the nodes' bounding box.
      if (history.n_nodes() > 0)
        {
          double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
          for (std::size_t i = 0; i < history.n_nodes(); ++i)
            {
              const auto uv = history.face_coordinates(i);
              for (int d = 0; d < 2; ++d)
                {
                  lo[d] = std::min(lo[d], uv[d]);
                  hi[d] = std::max(hi[d], uv[d]);
                }
            }
          const double h = prm.correlation.cell_size;
          const double eps = 1e-9 * h;
          const auto   n = [&](int d) {
            return std::max(1u, static_cast<unsigned int>(
                                  std::ceil((hi[d] - lo[d]) / h - 1e-6)));
          };
          // Centre the grid on the face.
          const unsigned int nx = n(0), ny = n(1);
          log_damage = GridMap(nx, ny,
                               0.5 * (lo[0] + hi[0]) - 0.5 * nx * h - eps,
                               0.5 * (lo[1] + hi[1]) - 0.5 * ny * h - eps,
                               h + 2. * eps / std::max(nx, ny));
        }
    }

    void
    TribologyAnalysis::compute_damage()
    {
      if (history.n_nodes() == 0)
        return;
      const std::size_t n = history.n_nodes();
      findley.resize(n);
      crossland.resize(n);
      statistics.resize(n);
      std::size_t next_report = n / 10;
      for (std::size_t i = 0; i < n; ++i)
        {
          findley[i] =
            findley_damage(history.p_N[i], history.t_T1[i], prm.damage.findley);
          crossland[i] =
            crossland_index(history.p_N[i], history.t_T1[i],
                            prm.damage.poisson_ratio,
                            prm.damage.crossland_alpha);
          statistics[i] = node_statistics(history.p_N[i], history.status[i],
                                          history.sampling_rate);
          if (n >= 1000 && i + 1 >= next_report)
            {
              std::cout << "  damage: " << (100 * (i + 1)) / n << " % of "
                        << n << " nodes" << std::endl;
              next_report += n / 10;
            }
        }
      // Node values onto the grid: the mean over the nodes in a cell; a
      // cell without a node takes its nearest node's value if that lies
      // within 1.5 node spacings (a grid finer than the contact mesh).
      const std::size_t n_cells = log_damage.values.size();
      std::vector<double> sum(n_cells, 0.), osc(n_cells, 0.), sep(n_cells, 0.),
        count(n_cells, 0.);
      const auto node_log_damage = [&](std::size_t i) {
        return std::log10(std::max(findley[i].relative, 1e-300));
      };
      for (std::size_t i = 0; i < n; ++i)
        {
          const auto uv = history.face_coordinates(i);
          const long c  = log_damage.cell_of(uv[0], uv[1]);
          if (c < 0)
            continue;
          sum[c] += node_log_damage(i);
          osc[c] += statistics[i].relative_oscillation;
          sep[c] += statistics[i].separated_fraction;
          count[c] += 1.;
        }
      const GridMap &g = log_damage;
      const double spacing = std::sqrt(g.nx * g.ny * g.h * g.h / n);
      for (unsigned int j = 0; j < g.ny; ++j)
        for (unsigned int i = 0; i < g.nx; ++i)
          {
            const std::size_t c = i + g.nx * j;
            if (count[c] > 0.)
              continue;
            const double x = g.x0 + (i + 0.5) * g.h, y = g.y0 + (j + 0.5) * g.h;
            double       best = 1e300;
            std::size_t  k    = 0;
            for (std::size_t m = 0; m < n; ++m)
              {
                const auto   uv = history.face_coordinates(m);
                const double d2 = (uv[0] - x) * (uv[0] - x) +
                                  (uv[1] - y) * (uv[1] - y);
                if (d2 < best)
                  {
                    best = d2;
                    k    = m;
                  }
              }
            if (std::sqrt(best) <= 1.5 * spacing)
              {
                sum[c]   = node_log_damage(k);
                osc[c]   = statistics[k].relative_oscillation;
                sep[c]   = statistics[k].separated_fraction;
                count[c] = 1.;
              }
          }
      p_oscillation = separated = log_damage.empty_like();
      for (std::size_t c = 0; c < n_cells; ++c)
        if (count[c] > 0.)
          {
            log_damage.values[c]    = sum[c] / count[c];
            p_oscillation.values[c] = osc[c] / count[c];
            separated.values[c]     = sep[c] / count[c];
          }
      double d_max = 0., d_min = 1e300;
      std::size_t i_max = 0;
      for (std::size_t i = 0; i < n; ++i)
        {
          if (findley[i].relative > d_max)
            {
              d_max = findley[i].relative;
              i_max = i;
            }
          d_min = std::min(d_min, findley[i].relative);
        }
      const auto uv = history.face_coordinates(i_max);
      std::cout << "Findley damage D* over " << n << " nodes: max "
                << std::setprecision(4) << d_max << " Pa^m at (s, r) = ("
                << uv[0] * 1e3 << ", " << uv[1] * 1e3 << ") mm, min " << d_min
                << ", max/min " << (d_min > 0. ? d_max / d_min : INFINITY)
                << std::endl;
    }

    void
    TribologyAnalysis::make_synthetic_images()
    {
      // Fields of view tiling the grid; cracks and exfoliations drawn with a
      // density that follows the rank of the cell's damage.
      const SyntheticImages &s  = prm.synthetic_images;
      const GridMap         &g  = log_damage;
      const double           wx = g.nx * g.h / s.fields_per_side,
                   wy = g.ny * g.h / s.fields_per_side;
      const double pixel = std::max(wx, wy) / s.image_size;
      std::vector<double> finite;
      for (double v : g.values)
        if (std::isfinite(v))
          finite.push_back(v);
      std::sort(finite.begin(), finite.end());
      const auto rank = [&](double v) {
        if (!std::isfinite(v) || finite.size() < 2)
          return 0.;
        return double(std::lower_bound(finite.begin(), finite.end(), v) -
                      finite.begin()) /
               (finite.size() - 1);
      };
      std::mt19937 rng(s.seed);
      std::uniform_real_distribution<double> U(0., 1.);
      for (unsigned int fy = 0; fy < s.fields_per_side; ++fy)
        for (unsigned int fx = 0; fx < s.fields_per_side; ++fx)
          {
            const double s0 = g.x0 + fx * wx, r1 = g.y0 + (fy + 1) * wy;
            // pixel (x, y) -> face (s0 + x p, r1 - y p): displayed upright
            const cv::Matx23d A(pixel, 0., s0 + 0.5 * pixel, 0., -pixel,
                                r1 - 0.5 * pixel);
            const cv::Size size(cvRound(wx / pixel), cvRound(wy / pixel));
            std::vector<SyntheticCrack> cracks;
            std::vector<SyntheticBlob>  blobs;
            const double cell_px = g.h / pixel;
            for (unsigned int j = 0; j < g.ny; ++j)
              for (unsigned int i = 0; i < g.nx; ++i)
                {
                  const double cx = (g.x0 + (i + 0.5) * g.h - s0) / pixel - 0.5,
                               cy = (r1 - (g.y0 + (j + 0.5) * g.h)) / pixel - 0.5;
                  if (cx < 0 || cy < 0 || cx >= size.width || cy >= size.height)
                    continue;
                  const double q = rank(g(i, j));
                  std::poisson_distribution<int> nc(
                    std::max(1e-9, s.cracks_per_cell * q * q)),
                    nb(std::max(1e-9, s.blobs_per_cell * q));
                  for (int k = nc(rng); k > 0; --k)
                    {
                      const double len = (0.3 + 0.4 * U(rng)) * cell_px,
                                   ang = M_PI * U(rng);
                      const cv::Point2d mid(cx + (U(rng) - 0.5) * 0.5 * cell_px,
                                            cy + (U(rng) - 0.5) * 0.5 * cell_px);
                      const cv::Point2d d(0.5 * len * std::cos(ang),
                                          0.5 * len * std::sin(ang));
                      cracks.push_back({{mid - d, mid, mid + d + cv::Point2d(0.1 * len * std::sin(ang), 0.)},
                                        2. + U(rng)});
                    }
                  for (int k = nb(rng); k > 0; --k)
                    blobs.push_back({cv::Point2d(cx + (U(rng) - 0.5) * 0.4 * cell_px,
                                                 cy + (U(rng) - 0.5) * 0.4 * cell_px),
                                     cv::Size2d((0.15 + 0.1 * U(rng)) * cell_px,
                                                (0.12 + 0.05 * U(rng)) * cell_px),
                                     180. * U(rng)});
                }
            const SyntheticSurface surf = draw_synthetic_surface(
              size, cracks, blobs, 0.3, 0.2, 1.0, 0.02,
              s.seed + fx + s.fields_per_side * fy);
            const std::string name = "field_" + std::to_string(fx) + "_" +
                                     std::to_string(fy);
            const fs::path png = fs::path(work_dir) / "images" / (name + ".png");
            cv::Mat u8;
            surf.image.convertTo(u8, CV_8U, 255.);
            if (!cv::imwrite(png.string(), u8))
              throw std::runtime_error("cannot write " + png.string());
            std::ofstream side(fs::path(png).replace_extension(".prm"));
            side << std::setprecision(17) << "# synthetic field of view\n"
                 << "set Pixel size = " << pixel << "\n"
                 << "set Placement = affine\n"
                 << "set Affine = " << A(0, 0) << ", " << A(0, 1) << ", "
                 << A(0, 2) << "; " << A(1, 0) << ", " << A(1, 1) << ", "
                 << A(1, 2) << "\n";
            image_files.push_back(png.string());
          }
      std::cout << "Synthetic SEM fields: " << image_files.size() << " of "
                << cvRound(wx / pixel) << " x " << cvRound(wy / pixel)
                << " px at " << pixel * 1e6 << " um/px" << std::endl;
    }

    void
    TribologyAnalysis::analyse_images()
    {
      if (prm.images.files.size() == 1 && prm.images.files[0] == "synthetic")
        make_synthetic_images();
      else
        for (const auto &f : prm.images.files)
          image_files.push_back(resolve(prm.base_directory, f));

      const std::string folder =
        prm.images.sidecar_folder.empty() ?
          "" :
          resolve(prm.base_directory, prm.images.sidecar_folder);
      for (const std::string &file : image_files)
        {
          ImageResult r;
          r.file                    = file;
          const std::string sidecar = sidecar_of(file, folder);
          if (!fs::exists(sidecar))
            throw std::runtime_error(
              "image '" + file + "' has no sidecar '" + sidecar +
              "' (pixel size and placement on the pad face)");
          const cv::Mat img = load_grey_image(file);
          r.placement       = read_image_placement(sidecar, img);
          if (!r.placement.reference_image.empty())
            {
              // Refine: reference pixels -> image pixels by ECC, starting
              // from the two sidecars' placements.
              const cv::Mat ref = load_grey_image(r.placement.reference_image);
              const ImagePlacement rp = read_image_placement(
                sidecar_of(r.placement.reference_image, folder), ref);
              r.placement = refine_placement(img, r.placement, ref, rp);
              std::cout << "  " << fs::path(file).filename().string()
                        << ": placement refined by ECC against "
                        << fs::path(r.placement.reference_image)
                             .filename()
                             .string()
                        << std::endl;
            }
          r.exfoliations = detect_exfoliations(img, prm.images.exfoliations);
          cv::Mat exclude;
          // the ridge filter answers up to about its largest scale outside
          // a blob's edge
          const int grow = cvCeil(*std::max_element(
                             prm.images.cracks.scales.begin(),
                             prm.images.cracks.scales.end())) + 2;
          cv::dilate(r.exfoliations.mask, exclude,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                               cv::Size(2 * grow + 1,
                                                        2 * grow + 1)));
          r.cracks = detect_cracks(img, prm.images.cracks, exclude);
          const double px2 = r.placement.pixel_size * r.placement.pixel_size;
          for (double a : r.exfoliations.areas)
            {
              const double m2 = a * px2;
              if (m2 < prm.images.micro_max_area)
                {
                  ++r.micro;
                  r.micro_area += m2;
                }
              else if (m2 > prm.images.macro_min_area)
                {
                  ++r.macro;
                  r.macro_area += m2;
                }
              else
                {
                  ++r.meso;
                  r.meso_area += m2;
                }
            }
          const double area_mm2 = img.total() * px2 * 1e6;
          std::cout << "  " << fs::path(file).filename().string() << ": "
                    << img.cols << " x " << img.rows << " px at "
                    << r.placement.pixel_size * 1e6 << " um/px; "
                    << r.cracks.lengths.size() << " cracks, "
                    << r.cracks.total_length * r.placement.pixel_size * 1e3
                    << " mm, L_A = "
                    << r.cracks.total_length * r.placement.pixel_size * 1e3 /
                         area_mm2
                    << " mm/mm^2; exfoliated " << std::setprecision(3)
                    << 100. * r.exfoliations.area_fraction << " % ("
                    << r.micro << " micro, " << r.meso << " meso, " << r.macro
                    << " macro)" << std::setprecision(6) << std::endl;
          write_overlay((fs::path(work_dir) / "images" /
                         (fs::path(file).stem().string() + "_overlay.png"))
                          .string(),
                        img, r.cracks, r.exfoliations);
          images.push_back(std::move(r));
        }
    }

    void
    TribologyAnalysis::build_maps()
    {
      if (images.empty())
        return;
      if (log_damage.nx == 0)
        {
          // No history: the grid covers the images' footprints.
          double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
          for (const auto &r : images)
            {
              const cv::Mat &m = r.cracks.mask;
              for (const cv::Point2d p :
                   {cv::Point2d(0, 0), cv::Point2d(m.cols, 0),
                    cv::Point2d(0, m.rows), cv::Point2d(m.cols, m.rows)})
                {
                  const cv::Matx23d &A = r.placement.pixel_to_face;
                  const double s = A(0, 0) * p.x + A(0, 1) * p.y + A(0, 2),
                               t = A(1, 0) * p.x + A(1, 1) * p.y + A(1, 2);
                  lo[0] = std::min(lo[0], s);
                  hi[0] = std::max(hi[0], s);
                  lo[1] = std::min(lo[1], t);
                  hi[1] = std::max(hi[1], t);
                }
            }
          const double h = prm.correlation.cell_size;
          log_damage = GridMap(
            std::max(1u, unsigned(std::ceil((hi[0] - lo[0]) / h - 1e-6))),
            std::max(1u, unsigned(std::ceil((hi[1] - lo[1]) / h - 1e-6))),
            lo[0], lo[1], h);
          p_oscillation = separated = log_damage.empty_like();
        }
      GridMap length = log_damage.empty_like(), count = length,
              blob   = length, covered = length;
      for (GridMap *m : {&length, &count, &blob, &covered})
        std::fill(m->values.begin(), m->values.end(), 0.);
      for (const auto &r : images)
        {
          const cv::Matx23d &A  = r.placement.pixel_to_face;
          const double       px = r.placement.pixel_size;
          const cv::Mat     &L  = r.cracks.length_per_pixel;
          for (int y = 0; y < L.rows; ++y)
            for (int x = 0; x < L.cols; ++x)
              {
                const long c =
                  log_damage.cell_of(A(0, 0) * x + A(0, 1) * y + A(0, 2),
                                     A(1, 0) * x + A(1, 1) * y + A(1, 2));
                if (c < 0)
                  continue;
                covered.values[c] += px * px;
                length.values[c] += L.at<float>(y, x) * px;
                blob.values[c] +=
                  r.exfoliations.mask.at<uchar>(y, x) ? px * px : 0.;
              }
          for (const cv::Point2d &p : r.cracks.centroids)
            {
              const long c = log_damage.cell_of(
                A(0, 0) * p.x + A(0, 1) * p.y + A(0, 2),
                A(1, 0) * p.x + A(1, 1) * p.y + A(1, 2));
              if (c >= 0)
                count.values[c] += 1.;
            }
        }
      crack_density = crack_count = exfoliated = coverage =
        log_damage.empty_like();
      const double cell_area = log_damage.h * log_damage.h;
      for (std::size_t c = 0; c < covered.values.size(); ++c)
        {
          coverage.values[c] = std::min(1., covered.values[c] / cell_area);
          // a cell counts when at least half of it was imaged
          if (covered.values[c] < 0.5 * cell_area)
            continue;
          const double mm2 = covered.values[c] * 1e6;
          crack_density.values[c] = length.values[c] * 1e3 / mm2;
          crack_count.values[c]   = count.values[c] / mm2;
          exfoliated.values[c]    = blob.values[c] / covered.values[c];
        }
    }

    void
    TribologyAnalysis::correlate()
    {
      if (images.empty() || history.n_nodes() == 0)
        return;
      std::vector<double> imaged;
      for (double v : crack_density.values)
        if (std::isfinite(v))
          imaged.push_back(v);
      if (imaged.size() < 4)
        throw std::runtime_error(
          "fewer than 4 grid cells are both imaged and in contact: no "
          "correlation (check the images' placement or Correlation/Cell "
          "size)");
      double threshold = prm.correlation.cracked_threshold;
      if (threshold < 0.)
        {
          std::nth_element(imaged.begin(), imaged.begin() + imaged.size() / 2,
                           imaged.end());
          threshold = imaged[imaged.size() / 2];
        }
      GridMap cracked = crack_density.empty_like();
      for (std::size_t c = 0; c < cracked.values.size(); ++c)
        if (std::isfinite(crack_density.values[c]))
          cracked.values[c] = crack_density.values[c] > threshold ? 1. : 0.;

      const auto sp = [](const std::vector<double> &a,
                         const std::vector<double> &b) { return spearman(a, b); };
      const auto pe = [](const std::vector<double> &a,
                         const std::vector<double> &b) { return pearson(a, b); };
      const auto au = [](const std::vector<double> &a,
                         const std::vector<double> &b) { return roc_auc(a, b); };
      const ToroidalTest ts = toroidal_test(log_damage, crack_density, sp);
      const ToroidalTest tp = toroidal_test(log_damage, crack_density, pe);
      const ToroidalTest ta = toroidal_test(log_damage, cracked, au);
      const ToroidalTest te = toroidal_test(log_damage, exfoliated, sp);
      const double moran_d = morans_i(log_damage),
                   moran_c = morans_i(crack_density);
      std::size_t n_pairs = 0;
      for (std::size_t c = 0; c < cracked.values.size(); ++c)
        n_pairs += std::isfinite(cracked.values[c]) &&
                   std::isfinite(log_damage.values[c]);
      const auto row = [&](const std::string &name, double v, double p,
                           unsigned int shifts) {
        std::ostringstream a, b;
        a << std::setprecision(6) << v;
        b << std::setprecision(6) << p;
        correlation_rows.push_back({name, a.str(), b.str(),
                                    std::to_string(n_pairs),
                                    std::to_string(shifts)});
      };
      row("spearman_log_damage_vs_crack_density", ts.observed, ts.p_value,
          ts.n_shifts);
      row("pearson_log_damage_vs_crack_density", tp.observed, tp.p_value,
          tp.n_shifts);
      row("roc_auc_log_damage_predicts_cracked", ta.observed, ta.p_value,
          ta.n_shifts);
      row("spearman_log_damage_vs_exfoliated_fraction", te.observed,
          te.p_value, te.n_shifts);
      row("morans_i_log_damage", moran_d, nan, 0);
      row("morans_i_crack_density", moran_c, nan, 0);
      row("cracked_threshold_mm_per_mm2", threshold, nan, 0);
      roc = roc_curve(log_damage.values, cracked.values);

      std::ostringstream v;
      v << std::setprecision(2) << std::fixed;
      const bool significant = ts.p_value < 0.05 && ts.observed > 0.;
      v << "Verdict: over " << n_pairs << " cells of "
        << prm.correlation.cell_size * 1e3 << " mm that are both in contact "
        << "and imaged, the fatigue-damage map "
        << (significant ? "does" : "does not")
        << " predict where the cracks are: Spearman rho = " << ts.observed
        << " (toroidal-shift p = " << std::setprecision(3) << ts.p_value
        << " over " << ts.n_shifts << " shifts), ROC AUC = "
        << std::setprecision(2) << ta.observed << " for cells above "
        << threshold << " mm/mm^2 of cracks (p = " << std::setprecision(3)
        << ta.p_value << ")." << std::setprecision(2)
        << " Both maps are spatially smooth (Moran's I " << moran_d
        << " for damage, " << moran_c
        << " for cracks), so these p-values come from shifting one map "
           "against the other rather than from formulas that assume "
           "independent cells, which would overstate the evidence. "
        << (significant ?
              "The cracks concentrate where the simulated stress "
              "oscillations are largest, as a fatigue reading predicts." :
              "The data do not support a fatigue link at this grid size; "
              "more images, a finer registration or another damage "
              "parameter set (see damage_sensitivity.csv) may change this.");
      verdict = v.str();
    }

    void
    TribologyAnalysis::output_results()
    {
      const fs::path dir(work_dir);
      const auto write_csv = [&](const std::string &name,
                                 const std::string &header,
                                 const std::function<void(std::ostream &)> &body) {
        std::ofstream out(dir / name);
        out << std::setprecision(10) << header << '\n';
        body(out);
        if (!out)
          throw std::runtime_error("cannot write " + (dir / name).string());
      };
      if (history.n_nodes() > 0)
        {
          write_csv(
            "damage.csv",
            "node,x_m,y_m,z_m,s_m,r_m,D_star_Pa_pow_m,D_miner,max_tau_eq_Pa,"
            "n_cycles,crossland_Pa,sqrt_J2a_Pa,sigma_H_max_Pa,mean_p_Pa,"
            "max_p_Pa,p_range_rel,separated_fraction,stick_fraction,"
            "slip_fraction,cycles_per_s",
            [&](std::ostream &o) {
              for (std::size_t i = 0; i < history.n_nodes(); ++i)
                {
                  const auto &x = history.coordinates[i];
                  const auto  uv = history.face_coordinates(i);
                  const auto &s = statistics[i];
                  o << i << ',' << x[0] << ',' << x[1] << ',' << x[2] << ','
                    << uv[0] << ',' << uv[1] << ',' << findley[i].relative
                    << ',' << findley[i].miner << ',' << findley[i].max_tau_eq
                    << ',' << findley[i].n_cycles << ','
                    << crossland[i].index << ','
                    << crossland[i].sqrt_j2_amplitude << ','
                    << crossland[i].hydrostatic_max << ',' << s.mean_pressure
                    << ',' << s.max_pressure << ',' << s.relative_oscillation
                    << ',' << s.separated_fraction << ',' << s.stick_fraction
                    << ',' << s.slip_fraction << ',' << s.cycles_per_second
                    << '\n';
                }
            });
          // Sensitivity of the damage map's ranking to k and m.
          std::vector<double> reference(history.n_nodes());
          for (std::size_t i = 0; i < history.n_nodes(); ++i)
            reference[i] = findley[i].relative;
          write_csv("damage_sensitivity.csv",
                    "k,m,spearman_to_default,max_over_min",
                    [&](std::ostream &o) {
                      FindleyParameters f = prm.damage.findley;
                      std::vector<std::pair<double, double>> cases;
                      for (double k : prm.damage.sensitivity_k)
                        cases.emplace_back(k, f.m);
                      for (double m : prm.damage.sensitivity_m)
                        cases.emplace_back(f.k, m);
                      for (const auto &[k, m] : cases)
                        {
                          f.k = k;
                          f.m = m;
                          std::vector<double> d(history.n_nodes());
                          for (std::size_t i = 0; i < d.size(); ++i)
                            d[i] = findley_damage(history.p_N[i],
                                                  history.t_T1[i], f)
                                     .relative;
                          const auto [lo, hi] =
                            std::minmax_element(d.begin(), d.end());
                          o << k << ',' << m << ',' << spearman(reference, d)
                            << ',' << (*lo > 0. ? *hi / *lo : INFINITY)
                            << '\n';
                        }
                    });
        }
      if (!images.empty())
        write_csv("images.csv",
                  "file,pixel_size_m,width_px,height_px,cracks,"
                  "crack_length_mm,crack_length_per_area_mm_per_mm2,"
                  "cracks_per_mm2,exfoliated_fraction,micro,meso,macro,"
                  "micro_area_mm2,meso_area_mm2,macro_area_mm2",
                  [&](std::ostream &o) {
                    for (const auto &r : images)
                      {
                        const double px = r.placement.pixel_size;
                        const double mm2 = r.cracks.mask.total() * px * px * 1e6;
                        o << fs::path(r.file).filename().string() << ','
                          << px << ',' << r.cracks.mask.cols << ','
                          << r.cracks.mask.rows << ','
                          << r.cracks.lengths.size() << ','
                          << r.cracks.total_length * px * 1e3 << ','
                          << r.cracks.total_length * px * 1e3 / mm2 << ','
                          << r.cracks.lengths.size() / mm2 << ','
                          << r.exfoliations.area_fraction << ',' << r.micro
                          << ',' << r.meso << ',' << r.macro << ','
                          << r.micro_area * 1e6 << ',' << r.meso_area * 1e6
                          << ',' << r.macro_area * 1e6 << '\n';
                      }
                  });
      const GridMap &g = log_damage;
      const auto value = [](const GridMap &m, std::size_t c) {
        return m.values.empty() ? nan : m.values[c];
      };
      write_csv("maps.csv",
                "i,j,s_m,r_m,log10_damage,p_range_rel,separated_fraction,"
                "crack_length_per_area_mm_per_mm2,cracks_per_mm2,"
                "exfoliated_fraction,coverage",
                [&](std::ostream &o) {
                  for (unsigned int j = 0; j < g.ny; ++j)
                    for (unsigned int i = 0; i < g.nx; ++i)
                      {
                        const std::size_t c = i + g.nx * j;
                        o << i << ',' << j << ',' << g.x0 + (i + 0.5) * g.h
                          << ',' << g.y0 + (j + 0.5) * g.h << ','
                          << value(g, c) << ',' << value(p_oscillation, c)
                          << ',' << value(separated, c) << ','
                          << value(crack_density, c) << ','
                          << value(crack_count, c) << ','
                          << value(exfoliated, c) << ','
                          << value(coverage, c) << '\n';
                      }
                });
      if (!correlation_rows.empty())
        {
          write_csv("correlation.csv", "statistic,value,p_value,cells,shifts",
                    [&](std::ostream &o) {
                      for (const auto &r : correlation_rows)
                        o << r[0] << ',' << r[1] << ',' << r[2] << ','
                          << r[3] << ',' << r[4] << '\n';
                    });
          write_csv("roc.csv", "false_positive_rate,true_positive_rate",
                    [&](std::ostream &o) {
                      for (const auto &[f, t] : roc)
                        o << f << ',' << t << '\n';
                    });
          std::ofstream(dir / "verdict.txt") << verdict << '\n';
        }

      // ParaView: the maps as cell data on the pad-face grid.
      {
        dealii::Triangulation<2> tria;
        dealii::GridGenerator::subdivided_hyper_rectangle(
          tria, {g.nx, g.ny}, dealii::Point<2>(g.x0, g.y0),
          dealii::Point<2>(g.x0 + g.nx * g.h, g.y0 + g.ny * g.h));
        dealii::DataOut<2> data_out;
        data_out.attach_triangulation(tria);
        std::vector<dealii::Vector<double>> fields;
        const std::vector<std::pair<const GridMap *, std::string>> named = {
          {&log_damage, "log10_damage_Findley"},
          {&p_oscillation, "pressure_range_relative"},
          {&separated, "separated_fraction"},
          {&crack_density, "crack_length_per_area_mm_per_mm2"},
          {&crack_count, "cracks_per_mm2"},
          {&exfoliated, "exfoliated_fraction"}};
        fields.reserve(named.size());
        for (const auto &[m, name] : named)
          {
            fields.emplace_back(tria.n_active_cells());
            for (const auto &cell : tria.active_cell_iterators())
              {
                const auto        c = cell->center();
                const long        k = g.cell_of(c[0], c[1]);
                fields.back()[cell->active_cell_index()] =
                  (k >= 0 && !m->values.empty()) ? m->values[k] : nan;
              }
            data_out.add_data_vector(fields.back(), name,
                                     dealii::DataOut<2>::type_cell_data);
          }
        data_out.build_patches();
        std::ofstream vtu(dir / "pad_face_maps.vtu");
        data_out.write_vtu(vtu);
      }

      if (prm.output.plots)
        {
          const std::string cmd = "/usr/bin/python3 '" +
                                  std::string(SQUEAL_SOURCE_DIR) +
                                  "/scripts/plot_tribology.py' '" + work_dir +
                                  "'";
          if (std::system(cmd.c_str()) != 0)
            throw std::runtime_error(
              "the plots failed (" + cmd +
              "); set Output/Plots = false to run without matplotlib");
        }
      output::publish_directory(work_dir, prm.output.directory);
      std::cout << "Results in " << prm.output.directory << std::endl;
    }

    void
    TribologyAnalysis::run()
    {
      // Errors are caught inside the timer's scope and rethrown after it, so
      // that the timer is not destroyed while an exception is in flight.
      std::string failure;
      {
        dealii::TimerOutput timer(std::cout, dealii::TimerOutput::summary,
                                  dealii::TimerOutput::wall_times);
        const auto phase = [&](const char *name, auto &&work) {
          if (!failure.empty())
            return;
          dealii::TimerOutput::Scope t(timer, name);
          try
            {
              work();
            }
          catch (const std::exception &e)
            {
              failure = e.what();
            }
        };
        phase("read inputs", [&] { setup(); });
        phase("damage (rainflow, Findley, Crossland)",
              [&] { compute_damage(); });
        phase("images (cracks, exfoliations)", [&] {
          analyse_images();
          build_maps();
        });
        phase("correlation", [&] { correlate(); });
        if (failure.empty() && !verdict.empty())
          std::cout << '\n' << verdict << "\n\n";
        phase("output", [&] { output_results(); });
      }
      if (!failure.empty())
        throw std::runtime_error(failure);
    }
  } // namespace tribology
} // namespace squeal
