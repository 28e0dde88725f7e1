// Where an SEM image lies on the pad face (tribology_analysis.h): its
// sidecar .prm (pixel size or scale bar; centre, fiducials or an affine
// map) and the ECC refinement against a reference image.
#include <deal.II/base/parameter_handler.h>

#include <squeal/parameters/parameters.h>
#include <squeal/tribology/tribology_analysis.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "text_input.h"

#include <cmath>
#include <filesystem>
#include <sstream>

namespace squeal
{
  namespace tribology
  {
    namespace fs = std::filesystem;
    using dealii::Patterns::Anything;
    using dealii::Patterns::Double;
    using dealii::Patterns::Selection;

    using internal::parse_doubles;
    using internal::parse_points;
    using internal::resolve;
    using parameters::parse_file;

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
      p.declare_entry("Pixel size",
                      "0",
                      Double(0.),
                      "m/px; 0: read the scale bar");
      p.declare_entry("Scale bar length", "0", Double(0.), "m");
      p.declare_entry("Placement",
                      "centre",
                      Selection("centre|fiducials|affine"),
                      "");
      p.declare_entry("Centre", "0, 0", Anything(), "face point [m]");
      p.declare_entry("Rotation", "0", Double(-360., 360.), "deg");
      p.declare_entry("Fiducial pixels", "", Anything(), "x,y; x,y [px]");
      p.declare_entry("Fiducial face coordinates",
                      "",
                      Anything(),
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
              const double cx   = 0.5 * (pixels.cols - 1),
                           cy   = 0.5 * (pixels.rows - 1);
              out.pixel_to_face = cv::Matx23d(ca,
                                              sa,
                                              c[0] - ca * cx - sa * cy,
                                              sa,
                                              -ca,
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
                  const std::vector<double> r =
                    parse_doubles(rows[i], "Affine");
                  if (r.size() != 3)
                    throw std::runtime_error("Affine: each row has 3 numbers");
                  for (int j = 0; j < 3; ++j)
                    A(i, j) = r[j];
                }
              out.pixel_to_face = A;
            }
          const cv::Matx23d &A   = out.pixel_to_face;
          const double       det = A(0, 0) * A(1, 1) - A(0, 1) * A(1, 0);
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
  } // namespace tribology
} // namespace squeal
