// The tribology program's parameters: one struct per subsection, every
// entry with a default, a range and help with SI units; reading a file with
// one clear error.

#include <deal.II/base/exceptions.h>

#include <squeal/parameters/parameters.h>
#include <squeal/tribology/tribology_analysis.h>

#include "text_input.h"

#include <filesystem>
#include <stdexcept>
#include <string>

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
    using internal::parse_doubles;
    using parameters::parse_file;

    // ---------------------------------------------------------------------
    // Parameters

    void
    HistoryInput::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Contact history");
      prm.declare_entry(
        "File",
        file,
        Anything(),
        "HDF5 contact history (layout in doc/tribology.md), relative to this "
        "file's folder; 'synthetic' draws a squeal-like one (subsection "
        "Synthetic history); empty: no damage analysis, images only.");
      prm.declare_entry("Start time",
                        std::to_string(start_time),
                        Double(0.),
                        "Samples before this time [s] are dropped (the load "
                        "ramp).");
      prm.declare_entry(
        "Face",
        face,
        Anything(),
        "The pad face to analyse: the name of its contact pair in the scene "
        "(e.g. 'inner pad'); the history's other faces are dropped. Empty: "
        "the history's only face (a history of several faces needs a name).");
      prm.leave_subsection();
    }

    void
    HistoryInput::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact history");
      file       = prm.get("File");
      start_time = prm.get_double("Start time");
      face       = prm.get("Face");
      prm.leave_subsection();
    }

    void
    SyntheticHistory::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Synthetic history");
      prm.declare_entry("Nodes per side",
                        std::to_string(nodes_per_side),
                        Integer(2, 201),
                        "Pad-face nodes along each side.");
      prm.declare_entry("Samples",
                        std::to_string(samples),
                        Integer(2, 100000000),
                        "Samples per node.");
      prm.declare_entry("Sampling rate",
                        "1e6",
                        Double(1.),
                        "Sampling rate [Hz].");
      prm.declare_entry("Frequency",
                        "3400",
                        Double(1.),
                        "Squeal frequency [Hz] (the thesis' 3.4 kHz).");
      prm.declare_entry("Mean pressure",
                        "1e6",
                        Double(0.),
                        "Mean contact pressure [Pa] (100 N on the 1e-4 m^2 "
                        "face).");
      prm.declare_entry("Friction coefficient",
                        "0.4",
                        Double(0.),
                        "q = mu p [-].");
      prm.declare_entry("Pad size", "0.01", Double(1e-6), "Pad face edge [m].");
      prm.declare_entry("Pad radius",
                        "0.1",
                        Double(0.),
                        "Radius of the pad face centre [m].");
      prm.declare_entry("Trailing amplitude",
                        "0.1",
                        Double(0., 1.),
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
      prm.declare_entry("Findley k",
                        "0.3",
                        Double(0., 2.),
                        "Normal-stress sensitivity k of tau_eq = dq/2 - k "
                        "p_min [-] (0.2-0.3 for most materials).");
      prm.declare_entry("Basquin exponent",
                        "10",
                        Double(1., 50.),
                        "m = -1/b of the Basquin law N = 0.5 (tau_eq / "
                        "tau_f)^(-m) [-]. No S-N data of phenolic friction "
                        "materials is published: the indices are relative.");
      prm.declare_entry("Shear fatigue strength",
                        "20e6",
                        Double(1.),
                        "tau_f' of the Basquin law [Pa] (an assumed scale; "
                        "only the Palmgren-Miner D uses it).");
      prm.declare_entry("Rainflow residue",
                        "half cycles",
                        Selection("half cycles|repeating"),
                        "Residue of the rainflow count: 'half cycles' "
                        "(ASTM E1049-85, transient histories) or "
                        "'repeating' (the record is one period of a limit "
                        "cycle).");
      prm.declare_entry("Crossland alpha",
                        "0.3",
                        Double(0., 3.),
                        "Hydrostatic sensitivity of the Crossland index "
                        "sqrt(J2,a) + alpha sigma_H,max [-].");
      prm.declare_entry("Pad Poisson ratio",
                        "0.3",
                        Double(0., 0.4999),
                        "nu of the laterally constrained surface layer [-].");
      prm.declare_entry("Sensitivity k values",
                        "0.1, 0.2, 0.3, 0.4, 0.5",
                        List(Double(0., 2.)),
                        "k values of the sensitivity table (rank correlation "
                        "of the damage map to the default one).");
      prm.declare_entry("Sensitivity m values",
                        "5, 8, 10, 12, 15",
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
      sensitivity_k   = parse_doubles(prm.get("Sensitivity k values"),
                                    "Damage/Sensitivity k values");
      sensitivity_m   = parse_doubles(prm.get("Sensitivity m values"),
                                    "Damage/Sensitivity m values");
      prm.leave_subsection();
    }

    void
    ImageSettings::declare_parameters(ParameterHandler &prm) const
    {
      prm.enter_subsection("Images");
      prm.declare_entry(
        "Files",
        "synthetic",
        Anything(),
        "Comma-separated SEM images (8/16-bit PNG, TIFF, BMP) relative to "
        "this file's folder, each with a sidecar of the same name ending in "
        ".prm (pixel size and placement on the pad face); 'synthetic' draws "
        "fields whose crack density follows the damage map; empty: none.");
      prm.declare_entry("Sidecar folder",
                        "",
                        Anything(),
                        "Folder of the sidecars, relative to this file's "
                        "folder; empty: beside each image.");
      prm.declare_entry("Crack contrast",
                        "dark",
                        Selection("dark|bright"),
                        "Cracks are darker (or brighter) than the surface.");
      prm.declare_entry("Crack scales",
                        "1, 1.5, 2, 3",
                        List(Double(0.3, 50.)),
                        "Gaussian scales of the Frangi ridge filter [px], "
                        "about the crack half-widths.");
      prm.declare_entry("Frangi beta",
                        "0.5",
                        Double(0.05, 5.),
                        "Blob suppression of the Frangi filter [-].");
      prm.declare_entry("Ridge noise floor",
                        "3",
                        Double(0.),
                        "Ridges weaker than this many times the median "
                        "Hessian norm of the image are noise or texture "
                        "[-]: lower it for smooth images with faint cracks, "
                        "raise it for noisy ones.");
      prm.declare_entry("Background degree",
                        "2",
                        Integer(0, 4),
                        "Degree of the polynomial that flattens uneven "
                        "brightness.");
      prm.declare_entry("Minimum crack length",
                        "15",
                        Double(0.),
                        "Shorter cracks are dropped [px].");
      prm.declare_entry("Exfoliation contrast",
                        "dark",
                        Selection("dark|bright"),
                        "Exfoliations are darker (or brighter) than the "
                        "surface.");
      prm.declare_entry("Exfoliation opening radius",
                        "3",
                        Integer(0, 50),
                        "Radius of the opening that removes cracks from the "
                        "exfoliation mask [px]: above a crack's half-width.");
      prm.declare_entry("Minimum exfoliation area",
                        "20",
                        Double(0.),
                        "Smaller blobs are dropped [px^2].");
      prm.declare_entry("Micro exfoliation area",
                        "1e-10",
                        Double(0.),
                        "Blobs below this area are micro-exfoliations [m^2] "
                        "(the thesis: a few um^2).");
      prm.declare_entry("Macro exfoliation area",
                        "1e-6",
                        Double(0.),
                        "Blobs above this area are macro-exfoliations [m^2] "
                        "(the thesis: > 1 mm^2).");
      prm.leave_subsection();
    }

    void
    ImageSettings::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Images");
      files          = dealii::Utilities::split_string_list(prm.get("Files"));
      sidecar_folder = prm.get("Sidecar folder");
      cracks.dark    = prm.get("Crack contrast") == "dark";
      cracks.scales =
        parse_doubles(prm.get("Crack scales"), "Images/Crack scales");
      cracks.beta              = prm.get_double("Frangi beta");
      cracks.noise_floor       = prm.get_double("Ridge noise floor");
      cracks.background_degree = prm.get_integer("Background degree");
      cracks.min_length        = prm.get_double("Minimum crack length");
      exfoliations.dark        = prm.get("Exfoliation contrast") == "dark";
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
      prm.declare_entry("Fields per side",
                        "2",
                        Integer(1, 10),
                        "Fields of view along each side of the pad face.");
      prm.declare_entry("Image size",
                        "800",
                        Integer(64, 8000),
                        "Pixels per side of one field.");
      prm.declare_entry("Cracks per cell",
                        "4",
                        Double(0.),
                        "Mean crack count per map cell where damage is "
                        "largest (it falls with the damage rank).");
      prm.declare_entry("Exfoliations per cell",
                        "0.3",
                        Double(0.),
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
      prm.declare_entry("Cell size",
                        "1e-3",
                        Double(1e-7),
                        "Edge of the square cells of the pad-face grid [m]: "
                        "two to three times the registration error at least.");
      prm.declare_entry("Cracked threshold",
                        "-1",
                        Double(),
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
      prm.declare_entry("Directory",
                        directory,
                        Anything(),
                        "Output folder, relative to the working directory.");
      prm.declare_entry("Overwrite",
                        "false",
                        Bool(),
                        "Replace an existing output folder.");
      prm.leave_subsection();
    }

    void
    TribologyOutput::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory = prm.get("Directory");
      overwrite = prm.get_bool("Overwrite");
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
    TribologyParameters::read(ParameterHandler  &prm,
                              const std::string &filename)
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
      // an output folder must not hold what the run reads
      const auto input = [&](const std::string &file) {
        if (!file.empty() && file != "synthetic")
          parameters::register_input(
            (fs::path(base_directory) / fs::path(file)).string());
      };
      input(history.file);
      for (const std::string &image : images.files)
        input(image);
    }
  } // namespace tribology
} // namespace squeal
