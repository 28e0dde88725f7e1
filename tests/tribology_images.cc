// Verification C5 and the image pipeline: synthetic SEM-like surfaces drawn
// with known geometry (straight, curved and crossing cracks of known length
// and width; ellipses of known area; noise, blur, uneven brightness). The
// crack length is checked within 5 %, the exfoliated area fraction within 2 %
// relative, the skeleton F1 score at 2 px above 0.95; ECC registration
// recovers a known rotation and translation within 0.1 px; the scale bar
// and fiducial placements are exact.

#include <squeal/tribology/surface_images.h>
#include <squeal/tribology/tribology_analysis.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "check.h"

#include <cmath>
#include <random>

using namespace squeal::tribology;
using test_tools::check;

namespace
{
  // Cracks: straight at several angles, a curved one (an arc as a fine
  // polyline), and two that cross.
  std::vector<SyntheticCrack>
  cracks(const double width)
  {
    std::vector<SyntheticCrack> c;
    for (int k = 0; k < 6; ++k)
      {
        const double      a = k * M_PI / 6. + 0.13;
        const cv::Point2d m(120. + 150. * (k % 3), 110. + 170. * (k / 3));
        const cv::Point2d d(60. * std::cos(a), 60. * std::sin(a));
        c.push_back({{m - d, m + d}, width});
      }
    SyntheticCrack arc{{}, width};
    for (int k = 0; k <= 40; ++k)
      {
        const double t = -0.9 + 1.8 * k / 40.;
        arc.points.emplace_back(560. + 90. * std::cos(t),
                                300. + 90. * std::sin(t));
      }
    c.push_back(arc);
    c.push_back({{{330., 480.}, {480., 560.}}, width});
    c.push_back({{{340., 570.}, {470., 470.}}, width});
    return c;
  }

  std::vector<SyntheticBlob>
  blobs()
  {
    return {{{560., 90.}, {30., 18.}, 20.},
            {{110., 520.}, {22., 22.}, 0.},
            {{600., 520.}, {40., 25.}, -35.},
            {{250., 620.}, {16., 12.}, 70.}};
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const cv::Size                           size(680, 680);
  for (const double width : {3., 5.})
    {
      const std::string w = "width " + std::to_string(int(width)) + " px: ";
      const SyntheticSurface s = draw_synthetic_surface(
        size, cracks(width), blobs(), 0.3, 0.3, 1.0, 0.03, 7);
      ExfoliationParameters ep;
      ep.opening_radius       = width > 4. ? 4 : 3;
      const ExfoliationMap ex = detect_exfoliations(s.image, ep);
      cv::Mat              exclude;
      cv::dilate(ex.mask,
                 exclude,
                 cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                           cv::Size(11, 11)));
      CrackParameters cp;
      const CrackMap  cm = detect_cracks(s.image, cp, exclude);
      test_tools::verbose()
        << w << "crack length " << cm.total_length << " / " << s.crack_length
        << ", F1 " << skeleton_f1(cm.skeleton, s.centre_lines, 2.) << ", blobs "
        << ex.areas.size() << ", area fraction " << ex.area_fraction << " / "
        << s.blob_area / size.area() << std::endl;
      if (std::getenv("SQUEAL_VERBOSE"))
        {
          write_overlay("/tmp/overlay_" + std::to_string(int(width)) + ".png",
                        s.image,
                        cm,
                        ex);
          for (std::size_t k = 0; k < cm.lengths.size(); ++k)
            test_tools::verbose() << "  crack at " << cm.centroids[k] << ": "
                                  << cm.lengths[k] << " px" << std::endl;
          cv::imwrite("/tmp/skel_" + std::to_string(int(width)) + ".png",
                      cm.skeleton);
        }
      check(w + "crack length within 5 %",
            cm.total_length,
            s.crack_length,
            0.05);
      check(w + "skeleton F1 at 2 px > 0.95",
            std::min(skeleton_f1(cm.skeleton, s.centre_lines, 2.), 0.95),
            0.95,
            0.);
      check(w + "4 exfoliations found", ex.areas.size(), 4., 0.);
      check(w + "exfoliated area fraction within 2 %",
            ex.area_fraction,
            s.blob_area / size.area(),
            0.02);
    }

  // Few cracks on a noisy surface: the ridge filter's scale is not set by
  // the noise (no false cracks), and the one crack is measured.
  {
    const SyntheticSurface none =
      draw_synthetic_surface(size, {}, {}, 0.3, 0.3, 1.0, 0.03, 11);
    const CrackMap cm0 = detect_cracks(none.image, CrackParameters());
    test_tools::verbose() << "no cracks: " << cm0.total_length << " px found"
                          << std::endl;
    check("noise alone: under 20 px of false cracks",
          std::min(cm0.total_length, 20.),
          cm0.total_length,
          0.);
    const SyntheticSurface one = draw_synthetic_surface(
      size, {{{{200., 300.}, {420., 380.}}, 3.}}, {}, 0.3, 0.3, 1.0, 0.03, 12);
    const CrackMap cm1 = detect_cracks(one.image, CrackParameters());
    test_tools::verbose() << "one crack: " << cm1.total_length << " / "
                          << one.crack_length << std::endl;
    check("one crack on noise: length within 5 %",
          cm1.total_length,
          one.crack_length,
          0.05);
  }

  // Skeleton length of digital straight lines at any angle (Kulpa weights).
  for (const double deg : {0., 10., 22.5, 30., 45., 60., 80.})
    {
      cv::Mat      line = cv::Mat::zeros(400, 400, CV_8U);
      const double a = deg * M_PI / 180., L = 300.;
      cv::line(line,
               cv::Point(50, 50),
               cv::Point(cvRound(50 + L * std::cos(a)),
                         cvRound(50 + L * std::sin(a))),
               255,
               1,
               cv::LINE_8);
      check("skeleton length at " + std::to_string(deg).substr(0, 4) +
              " deg within 2.5 %",
            skeleton_length(line),
            L,
            0.025);
    }

  // Registration: a textured surface, seen through two windows related by
  // a known rotation and translation (cropped, so that no border enters);
  // ECC from a guess 2 px off recovers the map within 0.1 px.
  {
    cv::Mat big(640, 640, CV_32F);
    cv::RNG rng(3);
    rng.fill(big, cv::RNG::UNIFORM, 0., 1.);
    cv::GaussianBlur(big, big, cv::Size(0, 0), 3.);
    cv::normalize(big, big, 0., 1., cv::NORM_MINMAX);
    const double      a = 1.7 * M_PI / 180.;
    const cv::Matx23d W(
      std::cos(a), -std::sin(a), 6.3, std::sin(a), std::cos(a), -4.6);
    cv::Mat warped; // warped(W x) = big(x)
    cv::warpAffine(big, warped, cv::Mat(W), big.size(), cv::INTER_CUBIC);
    const cv::Rect window(120, 120, 400, 400);
    const cv::Mat  ref = big(window).clone(), image = warped(window).clone();
    // in window coordinates: x_image = R x + R o + t - o
    const double      o = 120.;
    const cv::Matx23d Wc(W(0, 0),
                         W(0, 1),
                         W(0, 2) + (W(0, 0) + W(0, 1)) * o - o,
                         W(1, 0),
                         W(1, 1),
                         W(1, 2) + (W(1, 0) + W(1, 1)) * o - o);
    const cv::Matx23d guess(1., 0., Wc(0, 2) - 1.5, 0., 1., Wc(1, 2) + 2.);
    const cv::Matx23d found = refine_registration(image, ref, guess, 1);
    double            worst = 0.;
    for (const cv::Point2d p : {cv::Point2d(0, 0),
                                cv::Point2d(399, 0),
                                cv::Point2d(0, 399),
                                cv::Point2d(399, 399)})
      {
        const cv::Point2d t(Wc(0, 0) * p.x + Wc(0, 1) * p.y + Wc(0, 2),
                            Wc(1, 0) * p.x + Wc(1, 1) * p.y + Wc(1, 2));
        const cv::Point2d f(found(0, 0) * p.x + found(0, 1) * p.y + found(0, 2),
                            found(1, 0) * p.x + found(1, 1) * p.y +
                              found(1, 2));
        worst = std::max(worst, cv::norm(t - f));
      }
    test_tools::verbose() << "registration error " << worst << " px"
                          << std::endl;
    check("registration error (window corners) below 0.1 px",
          std::max(worst, 0.1),
          0.1,
          0.);

    // The same through the placements on the pad face: the reference at
    // 5 um/px is trusted, the image's sidecar is 2.5 px off; the refined
    // placement maps the image's corners within 0.1 px of the truth.
    ImagePlacement rp;
    rp.pixel_size    = 5e-6;
    rp.pixel_to_face = cv::Matx23d(5e-6, 0., -1e-3, 0., -5e-6, 2e-3);
    // truth: face = A_r W^-1 (x, 1)
    cv::Matx33d Ar = cv::Matx33d::eye(), Wm = cv::Matx33d::eye();
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j)
        {
          Ar(i, j) = rp.pixel_to_face(i, j);
          Wm(i, j) = Wc(i, j);
        }
    const cv::Matx33d truth           = Ar * Wm.inv();
    ImagePlacement    guess_placement = rp;
    guess_placement.pixel_to_face     = cv::Matx23d(truth.val);
    guess_placement.pixel_to_face(0, 2) += 2.5 * 5e-6;
    guess_placement.pixel_to_face(1, 2) -= 1.0 * 5e-6;
    const ImagePlacement refined =
      refine_placement(image, guess_placement, ref, rp);
    double face_error = 0.;
    for (const cv::Point2d p : {cv::Point2d(0, 0),
                                cv::Point2d(399, 0),
                                cv::Point2d(0, 399),
                                cv::Point2d(399, 399)})
      {
        const cv::Matx23d &A  = refined.pixel_to_face;
        const double       ds = A(0, 0) * p.x + A(0, 1) * p.y + A(0, 2) -
                          (truth(0, 0) * p.x + truth(0, 1) * p.y + truth(0, 2)),
                     dr = A(1, 0) * p.x + A(1, 1) * p.y + A(1, 2) -
                          (truth(1, 0) * p.x + truth(1, 1) * p.y + truth(1, 2));
        face_error = std::max(face_error, std::hypot(ds, dr) / 5e-6);
      }
    test_tools::verbose() << "placement error " << face_error << " px"
                          << std::endl;
    check("refined placement on the pad face within 0.1 px",
          std::max(face_error, 0.1),
          0.1,
          0.);
  }

  // Scale bar: a 240 px white bar of 50 um -> 50e-6 / 240 m/px.
  {
    cv::Mat img(600, 800, CV_32F, cv::Scalar(0.4));
    cv::rectangle(img, cv::Rect(500, 560, 240, 12), cv::Scalar(1.), cv::FILLED);
    check("scale bar pixel size",
          detect_scale_bar(img, 50e-6),
          50e-6 / 240.,
          1e-12);
  }

  // Fiducials: the similarity of two points maps both exactly, with the
  // displayed image's y axis flipped; three points give the affine map.
  {
    const std::vector<cv::Point2d> px{{10., 20.}, {810., 20.}},
      face{{-0.004, 0.003}, {0.0, 0.003}};
    const cv::Matx23d A = affine_from_fiducials(px, face);
    for (int k = 0; k < 2; ++k)
      {
        check("fiducial " + std::to_string(k) + " s",
              A(0, 0) * px[k].x + A(0, 1) * px[k].y + A(0, 2),
              face[k].x,
              1e-12,
              1e-3);
        check("fiducial " + std::to_string(k) + " r",
              A(1, 0) * px[k].x + A(1, 1) * px[k].y + A(1, 2),
              face[k].y,
              1e-12,
              1e-3);
      }
    // a point below in the image lies at smaller r on the face
    check("image rows grow towards smaller r", A(1, 1), -5e-6, 1e-9);
    const cv::Matx23d        B(2e-6, 1e-6, 0.001, -0.5e-6, -2e-6, 0.002);
    std::vector<cv::Point2d> p3{{0., 0.}, {100., 0.}, {0., 50.}, {70., 90.}},
      f3;
    for (const auto &p : p3)
      f3.emplace_back(B(0, 0) * p.x + B(0, 1) * p.y + B(0, 2),
                      B(1, 0) * p.x + B(1, 1) * p.y + B(1, 2));
    const cv::Matx23d C = affine_from_fiducials(p3, f3);
    double            e = 0.;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j)
        e = std::max(e, std::abs(C(i, j) - B(i, j)) / (j == 2 ? 1e-3 : 1e-6));
    check("affine from 4 fiducials", e, 0., 1e-9, 1.);
  }
  return test_tools::finish();
}
