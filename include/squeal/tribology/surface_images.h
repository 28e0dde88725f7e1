#ifndef squeal_tribology_surface_images_h
#define squeal_tribology_surface_images_h

/**
 * @file
 * Crack and exfoliation maps from SEM images of the pad surface (thesis
 * ch. 5: superficial cracks, exfoliations of the third-body layer), built
 * from OpenCV 4.6 operators: background flattening, a multi-scale Hessian
 * ridge filter (Frangi et al., MICCAI 1998, eq. 13-15), Otsu thresholding,
 * Zhang-Suen thinning (cv::ximgproc::thinning), connected components, and
 * ECC image registration (Evangelidis & Psarakis, IEEE PAMI 2008).
 *
 * Images are single-channel `CV_32F` matrices with values in [0, 1]; pixel
 * (col, row) = (x, y) with the origin at the top-left corner. Lengths in
 * pixels unless a name says m.
 */

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace squeal
{
  namespace tribology
  {
    /**
     * Reads an 8- or 16-bit grey (or colour, converted to grey) PNG, TIFF
     * or BMP image into a CV_32F matrix in [0, 1].
     * @throws std::runtime_error naming the file if it is missing,
     * unreadable or empty.
     */
    cv::Mat
    load_grey_image(const std::string &filename);

    /**
     * Removes uneven brightness: fits a bivariate polynomial of degree
     * @p degree (0-4) to the image by least squares on a coarse sample,
     * twice re-fitted without the pixels more than 2.5 standard deviations
     * off (cracks and blobs), and returns image - fit + mean(fit).
     */
    cv::Mat
    flatten_background(const cv::Mat &image, unsigned int degree);

    /**
     * Frangi vesselness of dark (@p dark = true) or bright ridges, the
     * maximum over the Gaussian scales @p sigmas [px] of
     * V = exp(-R_B^2 / (2 beta^2)) (1 - exp(-S^2 / (2 c^2))),
     * R_B = lambda_1 / lambda_2, S = |lambda|, |lambda_1| <= |lambda_2| the
     * eigenvalues of the scale-normalised Hessian (sigma^2 times Sobel
     * second derivatives of the Gaussian-smoothed image), c half the 99th
     * percentile of S at each scale (Frangi et al. 1998, eq. 15, take the
     * maximum; a few strong edges would then hide faint cracks). Pixels
     * whose S lies below @p noise_floor times the median S of the image
     * (the background's noise or texture) get V = 0. Returns CV_32F in
     * [0, 1].
     */
    cv::Mat
    frangi_vesselness(const cv::Mat             &image,
                      const std::vector<double> &sigmas,
                      double                     beta,
                      bool                       dark,
                      double                     noise_floor);

    /**
     * Length of a one-pixel-wide skeleton (8-connected, non-zero pixels),
     * from its chain: L = 0.980 n_e + 1.406 n_o - 0.091 n_c with n_e
     * orthogonal links, n_o diagonal links (not bridged by an orthogonal
     * pixel) and n_c corners (pixels where the chain turns) (Vossepoel &
     * Smeulders, Comput. Graph. Image Process. 20, 1982; about 2 % at
     * most on straight lines of any direction). Also returns, if
     * @p per_pixel is given, each pixel's share of that length (CV_32F) so
     * that lengths can be summed over regions.
     */
    double
    skeleton_length(const cv::Mat &skeleton, cv::Mat *per_pixel = nullptr);

    /** Settings of the crack detector. */
    struct CrackParameters
    {
      std::vector<double> scales{1., 1.5, 2., 3.}; ///< Gaussian sigmas [px]
      double              beta = 0.5;  ///< Frangi's blob sensitivity [-]
      bool                dark = true; ///< cracks darker than the surface
      unsigned int        background_degree = 2; ///< see flatten_background()
      double min_length = 15.; ///< shorter skeleton parts dropped [px]
      /// ridges weaker than this many times the median Hessian norm are
      /// noise or texture (see frangi_vesselness())
      double noise_floor = 3.;
    };

    /** What the crack detector found in one image. */
    struct CrackMap
    {
      cv::Mat             mask;     ///< CV_8U, 255 on crack pixels
      cv::Mat             skeleton; ///< CV_8U, 255 on the kept centre lines
      cv::Mat             length_per_pixel; ///< CV_32F, see skeleton_length()
      std::vector<double> lengths;          ///< per kept crack (component) [px]
      double              total_length = 0.; ///< [px]
      std::vector<cv::Point2d> centroids;    ///< per kept crack [px]
    };

    /**
     * Cracks: flatten, Frangi filter, Otsu threshold of the vesselness,
     * thinning, 8-connected skeleton components shorter than
     * `min_length` dropped. Pixels where @p exclude (CV_8U, optional) is
     * non-zero are no crack: pass the exfoliation mask dilated by a few
     * pixels, or the ridge filter's response along blob edges counts as
     * cracks.
     */
    CrackMap
    detect_cracks(const cv::Mat         &image,
                  const CrackParameters &parameters,
                  const cv::Mat         &exclude = cv::Mat());

    /** Settings of the exfoliation (blob) detector. */
    struct ExfoliationParameters
    {
      bool         dark              = true; ///< exfoliations darker
      unsigned int background_degree = 2;    ///< see flatten_background()
      /// radius [px] of the disc of the morphological opening that removes
      /// cracks and noise: larger than a crack's half-width, smaller than
      /// the smallest blob's radius of curvature
      unsigned int opening_radius = 3;
      double       min_area       = 20.; ///< smaller components dropped [px^2]
    };

    /** What the exfoliation detector found in one image. */
    struct ExfoliationMap
    {
      cv::Mat                  mask;      ///< CV_8U, 255 on exfoliated pixels
      std::vector<double>      areas;     ///< per blob [px^2]
      std::vector<cv::Point2d> centroids; ///< per blob [px]
      double                   area_fraction = 0.; ///< exfoliated / image area
    };

    /**
     * Exfoliations: flatten; Otsu splits surface from blobs, then the
     * threshold moves to the midpoint of the two classes' medians (so that
     * blurred edges are cut at half contrast, unbiased by the classes'
     * sizes); opening by a disc removes cracks; holes filled; components
     * below `min_area` dropped.
     */
    ExfoliationMap
    detect_exfoliations(const cv::Mat               &image,
                        const ExfoliationParameters &parameters);

    /**
     * Reads a scale bar: the widest horizontal bar (at least 8 times as
     * wide as high) of saturated pixels (black or white) in the bottom 15 %
     * of the image, and returns @p bar_length [m] divided by its width in
     * pixels: the pixel size [m/px].
     * @throws std::runtime_error if no such bar is found.
     */
    double
    detect_scale_bar(const cv::Mat &image, double bar_length);

    /**
     * The affine map pixel (x, y) -> pad-face coordinates [m] through
     * fiducials. With two, the similarity (rotation, uniform scale,
     * translation) through both, for an image seen as displayed: pixel rows
     * grow downwards while the face's second axis points up, so the map
     * includes that reflection. With three or more, the least-squares affine
     * map (any orientation).
     * @throws std::invalid_argument with fewer than two points, different
     * counts, or coincident points.
     */
    cv::Matx23d
    affine_from_fiducials(const std::vector<cv::Point2d> &pixels,
                          const std::vector<cv::Point2d> &face);

    /**
     * Refines the Euclidean (rotation + translation) warp that maps
     * @p reference pixels to @p image pixels, x_image = W (x_ref, 1), by
     * maximising the enhanced correlation coefficient (cv::findTransformECC,
     * both images first smoothed by a Gaussian kernel of
     * @p gauss_filter_size px, an odd number). @p initial is the first
     * guess, within a few pixels. Sub-pixel accurate on textured images.
     * @throws std::runtime_error if ECC does not converge.
     */
    cv::Matx23d
    refine_registration(const cv::Mat     &image,
                        const cv::Mat     &reference,
                        const cv::Matx23d &initial,
                        int                gauss_filter_size = 5);

    /** A synthetic SEM-like image with known content, for tests and demos. */
    struct SyntheticSurface
    {
      cv::Mat image;             ///< CV_32F in [0, 1]
      cv::Mat centre_lines;      ///< CV_8U, the cracks' 1-px centre lines
      cv::Mat blob_mask;         ///< CV_8U, 255 inside the drawn ellipses
      double  crack_length = 0.; ///< exact drawn centre-line length [px]
      double  blob_area    = 0.; ///< exact area of the ellipses [px^2]
    };

    /** A crack: a polyline of width `width` [px]. */
    struct SyntheticCrack
    {
      std::vector<cv::Point2d> points;
      double                   width = 3.;
    };

    /** An exfoliation: an ellipse (centre, semi-axes [px], angle [deg]). */
    struct SyntheticBlob
    {
      cv::Point2d centre;
      cv::Size2d  semi_axes;
      double      angle = 0.;
    };

    /**
     * Draws a surface of @p size px: a brightness gradient (uneven SEM
     * illumination, from 0.5 - gradient / 2 to 0.5 + gradient / 2 across
     * the diagonal, plus a quadratic bowl), dark cracks and exfoliations of
     * contrast @p contrast, Gaussian blur of @p blur px and Gaussian noise of
     * standard deviation @p noise, from the random seed @p seed. Drawing is
     * 4x supersampled and anti-aliased, so areas and lengths are exact to
     * well below a pixel. Blobs must not overlap (their areas are summed).
     */
    SyntheticSurface
    draw_synthetic_surface(cv::Size                           size,
                           const std::vector<SyntheticCrack> &cracks,
                           const std::vector<SyntheticBlob>  &blobs,
                           double                             contrast,
                           double                             gradient,
                           double                             blur,
                           double                             noise,
                           unsigned int                       seed);

    /**
     * F1 score of a detected skeleton against true centre lines with a
     * matching tolerance of @p tolerance px (precision: detected pixels
     * within the tolerance of a true one; recall: the converse).
     */
    double
    skeleton_f1(const cv::Mat &detected,
                const cv::Mat &truth,
                double         tolerance);

    /**
     * Writes an 8-bit colour overlay of @p image with cracks (red) and
     * exfoliations (cyan) to @p filename (PNG).
     * @throws std::runtime_error if it cannot be written.
     */
    void
    write_overlay(const std::string    &filename,
                  const cv::Mat        &image,
                  const CrackMap       &cracks,
                  const ExfoliationMap &exfoliations);
  } // namespace tribology
} // namespace squeal

#endif
