// Crack and exfoliation maps from SEM images of the pad surface.
//
// Everything here is made of OpenCV operators; what OpenCV lacks and is
// written here is the Frangi ridge filter (from Gaussian and Sobel
// operators), a robust polynomial background for uneven SEM brightness, and a
// chain-code length of skeletons. The synthetic surface generator draws what
// the tests measure against: its lengths and areas are exact by construction.

#include <squeal/tribology/surface_images.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/ximgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace squeal
{
  namespace tribology
  {
    cv::Mat
    load_grey_image(const std::string &filename)
    {
      if (!std::filesystem::exists(filename))
        throw std::runtime_error("image '" + filename + "': no such file");
      const cv::Mat raw =
        cv::imread(filename, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
      if (raw.empty())
        throw std::runtime_error(
          "image '" + filename +
          "': cannot be read as an image (PNG, TIFF or BMP expected)");
      cv::Mat out;
      switch (raw.depth())
        {
          case CV_8U:
            raw.convertTo(out, CV_32F, 1. / 255.);
            break;
          case CV_16U:
            raw.convertTo(out, CV_32F, 1. / 65535.);
            break;
          default:
            throw std::runtime_error("image '" + filename +
                                     "': only 8- and 16-bit images are read");
        }
      return out;
    }

    namespace
    {
      // Monomials x^i y^j, i + j <= degree, at normalised coordinates.
      void
      monomials(double x, double y, unsigned int degree, double *out)
      {
        unsigned int k = 0;
        for (unsigned int d = 0; d <= degree; ++d)
          for (unsigned int i = 0; i <= d; ++i)
            out[k++] = std::pow(x, i) * std::pow(y, d - i);
      }
    } // namespace

    cv::Mat
    flatten_background(const cv::Mat &image, const unsigned int degree)
    {
      if (degree > 4)
        throw std::invalid_argument(
          "background polynomial degree must lie in 0..4");
      CV_Assert(image.type() == CV_32F);
      const int    n_terms = (degree + 1) * (degree + 2) / 2;
      const int    step = std::max(1, std::min(image.rows, image.cols) / 160);
      const double sx   = 2. / std::max(1, image.cols - 1),
                   sy   = 2. / std::max(1, image.rows - 1);
      std::vector<cv::Point> samples;
      for (int r = 0; r < image.rows; r += step)
        for (int c = 0; c < image.cols; c += step)
          samples.emplace_back(c, r);
      cv::Mat A(samples.size(), n_terms, CV_64F), b(samples.size(), 1, CV_64F);
      for (std::size_t k = 0; k < samples.size(); ++k)
        {
          monomials(samples[k].x * sx - 1.,
                    samples[k].y * sy - 1.,
                    degree,
                    A.ptr<double>(k));
          b.at<double>(k) = image.at<float>(samples[k]);
        }
      cv::Mat           coef;
      std::vector<char> use(samples.size(), 1);
      for (int pass = 0; pass < 3; ++pass)
        {
          cv::Mat As, bs;
          for (std::size_t k = 0; k < samples.size(); ++k)
            if (use[k])
              {
                As.push_back(A.row(k));
                bs.push_back(b.row(k));
              }
          cv::solve(As, bs, coef, cv::DECOMP_QR);
          const cv::Mat res = b - A * coef;
          double        ss  = 0.;
          int           n   = 0;
          for (std::size_t k = 0; k < samples.size(); ++k)
            if (use[k])
              {
                ss += res.at<double>(k) * res.at<double>(k);
                ++n;
              }
          const double sd = std::sqrt(ss / std::max(1, n));
          for (std::size_t k = 0; k < samples.size(); ++k)
            use[k] = std::abs(res.at<double>(k)) <= 2.5 * sd;
        }
      cv::Mat             out(image.size(), CV_32F);
      std::vector<double> m(n_terms);
      double              mean_fit = 0.;
      for (int r = 0; r < image.rows; ++r)
        for (int c = 0; c < image.cols; ++c)
          {
            monomials(c * sx - 1., r * sy - 1., degree, m.data());
            double fit = 0.;
            for (int t = 0; t < n_terms; ++t)
              fit += m[t] * coef.at<double>(t);
            out.at<float>(r, c) = image.at<float>(r, c) - fit;
            mean_fit += fit;
          }
      mean_fit /= double(image.total());
      out += mean_fit;
      return out;
    }

    cv::Mat
    frangi_vesselness(const cv::Mat             &image,
                      const std::vector<double> &sigmas,
                      const double               beta,
                      const bool                 dark,
                      const double               noise_floor)
    {
      CV_Assert(image.type() == CV_32F);
      cv::Mat best = cv::Mat::zeros(image.size(), CV_32F);
      for (const double s : sigmas)
        {
          cv::Mat g, dxx, dyy, dxy;
          cv::GaussianBlur(image, g, cv::Size(0, 0), s, s, cv::BORDER_REFLECT);
          // 3x3 Sobel second derivatives carry a factor 4 of smoothing
          // weight; sigma^2 normalises across scales.
          const double f = s * s / 4.;
          cv::Sobel(g, dxx, CV_32F, 2, 0, 3, f, 0., cv::BORDER_REFLECT);
          cv::Sobel(g, dyy, CV_32F, 0, 2, 3, f, 0., cv::BORDER_REFLECT);
          cv::Sobel(g, dxy, CV_32F, 1, 1, 3, f, 0., cv::BORDER_REFLECT);
          cv::Mat            l1(image.size(), CV_32F), l2(image.size(), CV_32F);
          std::vector<float> norms;
          norms.reserve(image.total());
          for (int r = 0; r < image.rows; ++r)
            for (int c = 0; c < image.cols; ++c)
              {
                const float a = dxx.at<float>(r, c), d = dyy.at<float>(r, c),
                            b    = dxy.at<float>(r, c);
                const float root = std::sqrt((a - d) * (a - d) + 4.f * b * b);
                float m1 = 0.5f * (a + d + root), m2 = 0.5f * (a + d - root);
                if (std::abs(m1) > std::abs(m2))
                  std::swap(m1, m2);
                l1.at<float>(r, c) = m1;
                l2.at<float>(r, c) = m2;
                norms.push_back(std::sqrt(m1 * m1 + m2 * m2));
              }
          // Frangi's c is half the largest Hessian norm; a few strong edges
          // (grain boundaries, blobs) would then hide faint cracks, so the
          // 99th percentile stands in for the maximum. Where an image has
          // few cracks that percentile is noise, so structure below a noise
          // floor (a multiple of the median norm, which the background
          // sets) is no ridge at all.
          std::vector<float> sorted(norms);
          std::nth_element(sorted.begin(),
                           sorted.begin() + sorted.size() / 2,
                           sorted.end());
          const float floor =
            static_cast<float>(noise_floor) * sorted[sorted.size() / 2];
          std::nth_element(sorted.begin(),
                           sorted.begin() + sorted.size() * 99 / 100,
                           sorted.end());
          const float s_max = std::max(sorted[sorted.size() * 99 / 100], floor);
          if (s_max <= 0.f)
            continue;
          const double c2 = 2. * std::pow(0.5 * s_max, 2),
                       b2 = 2. * beta * beta;
          for (int r = 0; r < image.rows; ++r)
            for (int c = 0; c < image.cols; ++c)
              {
                const float m1 = l1.at<float>(r, c), m2 = l2.at<float>(r, c);
                // A dark ridge (valley) curves upwards across: lambda_2 > 0.
                if ((dark && m2 <= 0.f) || (!dark && m2 >= 0.f))
                  continue;
                const double rb = m1 / m2, ss = m1 * m1 + m2 * m2;
                if (ss < double(floor) * floor)
                  continue;
                const float v = static_cast<float>(std::exp(-rb * rb / b2) *
                                                   (1. - std::exp(-ss / c2)));
                best.at<float>(r, c) = std::max(best.at<float>(r, c), v);
              }
        }
      double vmax = 0.;
      cv::minMaxLoc(best, nullptr, &vmax);
      if (vmax > 0.)
        best /= vmax;
      return best;
    }

    namespace
    {
      bool
      on(const cv::Mat &m, int r, int c)
      {
        return r >= 0 && c >= 0 && r < m.rows && c < m.cols &&
               m.at<uchar>(r, c) != 0;
      }

      // Thinning leaves 4-connected staircases (an L of three pixels where
      // a diagonal step would do). A pixel is redundant when its neighbours
      // stay one 8-connected group without it; it is removed if it has three
      // neighbours or more, or exactly two at a right angle, so that line
      // ends are never eroded. Repeated until nothing changes.
      void
      remove_redundant_pixels(cv::Mat &skel)
      {
        const int ring_r[8] = {-1, -1, 0, 1, 1, 1, 0, -1},
                  ring_c[8] = {0, 1, 1, 1, 0, -1, -1, -1};
        for (bool changed = true; changed;)
          {
            changed = false;
            for (int r = 0; r < skel.rows; ++r)
              for (int c = 0; c < skel.cols; ++c)
                {
                  if (!on(skel, r, c))
                    continue;
                  bool nb[8];
                  int  n = 0;
                  for (int k = 0; k < 8; ++k)
                    n += (nb[k] = on(skel, r + ring_r[k], c + ring_c[k]));
                  if (n < 2)
                    continue;
                  if (n == 2)
                    {
                      // only an L: two orthogonal neighbours at a right angle
                      bool l_corner = false;
                      for (int k = 0; k < 8; k += 2)
                        l_corner |= nb[k] && nb[(k + 2) % 8];
                      if (!l_corner)
                        continue;
                    }
                  // Connected groups of the neighbours: ring pixels k and
                  // k+1 always touch; k and k+2 touch when k+1 is
                  // orthogonal (k odd... i.e. corners around an edge pixel).
                  int group[8], n_groups = 0;
                  for (int k = 0; k < 8; ++k)
                    group[k] = -1;
                  for (int k = 0; k < 8; ++k)
                    {
                      if (!nb[k] || group[k] >= 0)
                        continue;
                      group[k] = n_groups;
                      std::vector<int> todo{k};
                      while (!todo.empty())
                        {
                          const int a = todo.back();
                          todo.pop_back();
                          for (int b = 0; b < 8; ++b)
                            if (nb[b] && group[b] < 0 &&
                                std::abs(ring_r[a] - ring_r[b]) <= 1 &&
                                std::abs(ring_c[a] - ring_c[b]) <= 1)
                              {
                                group[b] = n_groups;
                                todo.push_back(b);
                              }
                        }
                      ++n_groups;
                    }
                  if (n_groups == 1)
                    {
                      skel.at<uchar>(r, c) = 0;
                      changed              = true;
                    }
                }
          }
      }
    } // namespace

    double
    skeleton_length(const cv::Mat &skel, cv::Mat *per_pixel)
    {
      CV_Assert(skel.type() == CV_8U);
      // Vossepoel & Smeulders (CGIP 1982): even (orthogonal) and odd
      // (diagonal) chain links and corners (changes of direction).
      const double w_e = 0.980, w_o = 1.406, w_c = -0.091;
      cv::Mat      share  = cv::Mat::zeros(skel.size(), CV_32F);
      double       total  = 0.;
      const auto   linked = [&](int r, int c, int dr, int dc) {
        if (!on(skel, r + dr, c + dc))
          return false;
        // a diagonal bridged by an orthogonal pixel is not a link
        return dr == 0 || dc == 0 ||
               (!on(skel, r + dr, c) && !on(skel, r, c + dc));
      };
      for (int r = 0; r < skel.rows; ++r)
        for (int c = 0; c < skel.cols; ++c)
          {
            if (!on(skel, r, c))
              continue;
            int    n_links = 0, dir[8][2];
            double own     = 0.;
            for (int dr = -1; dr <= 1; ++dr)
              for (int dc = -1; dc <= 1; ++dc)
                if ((dr || dc) && linked(r, c, dr, dc))
                  {
                    // half of each link belongs to each end
                    own += 0.5 * ((dr && dc) ? w_o : w_e);
                    dir[n_links][0] = dr;
                    dir[n_links][1] = dc;
                    ++n_links;
                  }
            if (n_links == 2 &&
                (dir[0][0] != -dir[1][0] || dir[0][1] != -dir[1][1]))
              own += w_c;
            share.at<float>(r, c) = static_cast<float>(own);
            total += own;
          }
      if (per_pixel)
        *per_pixel = share;
      return total;
    }

    namespace
    {
      // Otsu's threshold of a float image (through 8 bits over its range).
      double
      otsu_threshold(const cv::Mat &img, const cv::Mat &mask = cv::Mat())
      {
        double lo, hi;
        cv::minMaxLoc(img, &lo, &hi, nullptr, nullptr, mask);
        if (hi <= lo)
          return hi;
        cv::Mat u8;
        img.convertTo(u8, CV_8U, 255. / (hi - lo), -255. * lo / (hi - lo));
        cv::Mat      dummy;
        const double t =
          cv::threshold(u8, dummy, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
        return lo + t * (hi - lo) / 255.;
      }

      double
      median_where(const cv::Mat &img, const cv::Mat &mask, bool value)
      {
        std::vector<float> v;
        for (int r = 0; r < img.rows; ++r)
          for (int c = 0; c < img.cols; ++c)
            if ((mask.at<uchar>(r, c) != 0) == value)
              v.push_back(img.at<float>(r, c));
        if (v.empty())
          return 0.;
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
      }
    } // namespace

    CrackMap
    detect_cracks(const cv::Mat         &image,
                  const CrackParameters &par,
                  const cv::Mat         &exclude)
    {
      const cv::Mat flat = flatten_background(image, par.background_degree);
      const cv::Mat v    = frangi_vesselness(
        flat, par.scales, par.beta, par.dark, par.noise_floor);
      CrackMap out;
      cv::Mat  mask = v > otsu_threshold(v);
      if (!exclude.empty())
        mask.setTo(0, exclude);
      cv::Mat skel;
      cv::ximgproc::thinning(mask, skel, cv::ximgproc::THINNING_ZHANGSUEN);
      remove_redundant_pixels(skel);
      cv::Mat per_pixel;
      skeleton_length(skel, &per_pixel);
      cv::Mat   labels, stats, centroids;
      const int n = cv::connectedComponentsWithStats(
        skel, labels, stats, centroids, 8, CV_32S);
      std::vector<double> length(n, 0.);
      for (int r = 0; r < skel.rows; ++r)
        for (int c = 0; c < skel.cols; ++c)
          length[labels.at<int>(r, c)] += per_pixel.at<float>(r, c);
      std::vector<char> keep(n, 0);
      for (int l = 1; l < n; ++l)
        if (length[l] >= par.min_length)
          {
            keep[l] = 1;
            out.lengths.push_back(length[l]);
            out.total_length += length[l];
            out.centroids.emplace_back(centroids.at<double>(l, 0),
                                       centroids.at<double>(l, 1));
          }
      out.skeleton         = cv::Mat::zeros(skel.size(), CV_8U);
      out.length_per_pixel = cv::Mat::zeros(skel.size(), CV_32F);
      for (int r = 0; r < skel.rows; ++r)
        for (int c = 0; c < skel.cols; ++c)
          if (keep[labels.at<int>(r, c)])
            {
              out.skeleton.at<uchar>(r, c)         = 255;
              out.length_per_pixel.at<float>(r, c) = per_pixel.at<float>(r, c);
            }
      out.mask = mask;
      return out;
    }

    ExfoliationMap
    detect_exfoliations(const cv::Mat &image, const ExfoliationParameters &par)
    {
      cv::Mat f = flatten_background(image, par.background_degree);
      if (par.dark)
        f = -f;
      // Otsu separates surface from blobs; cut at the midpoint of the two
      // classes' medians so blurred edges are split at half contrast.
      const cv::Mat first = f > otsu_threshold(f);
      const double  t =
        0.5 * (median_where(f, first, true) + median_where(f, first, false));
      cv::Mat   mask = f > t;
      const int r    = static_cast<int>(par.opening_radius);
      if (r > 0)
        cv::morphologyEx(mask,
                         mask,
                         cv::MORPH_OPEN,
                         cv::getStructuringElement(
                           cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
      // Fill holes: everything not reachable from the border outside.
      std::vector<std::vector<cv::Point>> contours;
      cv::findContours(mask.clone(),
                       contours,
                       cv::RETR_EXTERNAL,
                       cv::CHAIN_APPROX_NONE);
      cv::Mat filled = cv::Mat::zeros(mask.size(), CV_8U);
      cv::drawContours(filled, contours, -1, 255, cv::FILLED);
      cv::Mat   labels, stats, centroids;
      const int n = cv::connectedComponentsWithStats(
        filled, labels, stats, centroids, 8, CV_32S);
      ExfoliationMap out;
      out.mask = cv::Mat::zeros(mask.size(), CV_8U);
      std::vector<char> keep(n, 0);
      for (int l = 1; l < n; ++l)
        if (stats.at<int>(l, cv::CC_STAT_AREA) >= par.min_area)
          {
            keep[l] = 1;
            out.areas.push_back(stats.at<int>(l, cv::CC_STAT_AREA));
            out.centroids.emplace_back(centroids.at<double>(l, 0),
                                       centroids.at<double>(l, 1));
          }
      double total = 0.;
      for (int rr = 0; rr < mask.rows; ++rr)
        for (int c = 0; c < mask.cols; ++c)
          if (keep[labels.at<int>(rr, c)])
            {
              out.mask.at<uchar>(rr, c) = 255;
              total += 1.;
            }
      out.area_fraction = total / double(mask.total());
      return out;
    }

    double
    detect_scale_bar(const cv::Mat &image, const double bar_length)
    {
      if (!(bar_length > 0.))
        throw std::invalid_argument("scale bar length must be positive");
      const int     top   = image.rows - std::max(1, image.rows * 15 / 100);
      const cv::Mat strip = image.rowRange(top, image.rows);
      double        best  = 0.;
      for (const bool bright : {true, false})
        {
          const cv::Mat sat = bright ? (strip > 0.95f) : (strip < 0.05f);
          cv::Mat       labels, stats, centroids;
          const int     n = cv::connectedComponentsWithStats(
            sat, labels, stats, centroids, 8, CV_32S);
          for (int l = 1; l < n; ++l)
            {
              const int w = stats.at<int>(l, cv::CC_STAT_WIDTH),
                        h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
              // a filled bar: wide, thin, and (nearly) a full rectangle
              if (w >= 8 * h &&
                  stats.at<int>(l, cv::CC_STAT_AREA) >= 0.8 * w * h)
                best = std::max(best, double(w));
            }
        }
      if (best <= 0.)
        throw std::runtime_error(
          "no scale bar found (a filled black or white bar, at least 8 times "
          "as wide as high, in the bottom 15 % of the image); give the pixel "
          "size instead");
      return bar_length / best;
    }

    cv::Matx23d
    affine_from_fiducials(const std::vector<cv::Point2d> &px,
                          const std::vector<cv::Point2d> &face)
    {
      if (px.size() != face.size())
        throw std::invalid_argument(
          "fiducials: as many pixel positions as face positions are needed");
      if (px.size() < 2)
        throw std::invalid_argument("fiducials: at least two are needed");
      if (px.size() == 2)
        {
          // Similarity of the displayed image (y flipped) onto the face:
          // as complex numbers, face = s * conj-free(x, -y) + t.
          const cv::Point2d dp(px[1].x - px[0].x, -(px[1].y - px[0].y));
          const cv::Point2d df = face[1] - face[0];
          const double      n2 = dp.dot(dp);
          if (n2 <= 0.)
            throw std::invalid_argument("fiducials: the two points coincide");
          const double a = (df.x * dp.x + df.y * dp.y) / n2,
                       b = (df.y * dp.x - df.x * dp.y) / n2;
          // face = [a -b; b a] (x, -y) + t = [a b; b -a] (x, y) + t
          const double tx = face[0].x - (a * px[0].x + b * px[0].y),
                       ty = face[0].y - (b * px[0].x - a * px[0].y);
          return cv::Matx23d(a, b, tx, b, -a, ty);
        }
      cv::Mat A(px.size(), 3, CV_64F), B(px.size(), 2, CV_64F), X;
      for (std::size_t i = 0; i < px.size(); ++i)
        {
          A.at<double>(i, 0) = px[i].x;
          A.at<double>(i, 1) = px[i].y;
          A.at<double>(i, 2) = 1.;
          B.at<double>(i, 0) = face[i].x;
          B.at<double>(i, 1) = face[i].y;
        }
      if (!cv::solve(A, B, X, cv::DECOMP_SVD) ||
          std::abs(cv::determinant(A.t() * A)) < 1e-30)
        throw std::invalid_argument("fiducials: the points are collinear");
      return cv::Matx23d(X.at<double>(0, 0),
                         X.at<double>(1, 0),
                         X.at<double>(2, 0),
                         X.at<double>(0, 1),
                         X.at<double>(1, 1),
                         X.at<double>(2, 1));
    }

    cv::Matx23d
    refine_registration(const cv::Mat     &image,
                        const cv::Mat     &reference,
                        const cv::Matx23d &initial,
                        const int          gauss_filter_size)
    {
      cv::Mat warp(initial, true);
      warp.convertTo(warp, CV_32F);
      try
        {
          cv::findTransformECC(reference,
                               image,
                               warp,
                               cv::MOTION_EUCLIDEAN,
                               cv::TermCriteria(cv::TermCriteria::COUNT +
                                                  cv::TermCriteria::EPS,
                                                200,
                                                1e-8),
                               cv::noArray(),
                               gauss_filter_size);
        }
      catch (const cv::Exception &e)
        {
          throw std::runtime_error(
            "image registration (ECC) did not converge: " + e.msg);
        }
      cv::Matx23d out;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 3; ++j)
          out(i, j) = warp.at<float>(i, j);
      return out;
    }

    SyntheticSurface
    draw_synthetic_surface(const cv::Size                     size,
                           const std::vector<SyntheticCrack> &cracks,
                           const std::vector<SyntheticBlob>  &blobs,
                           const double                       contrast,
                           const double                       gradient,
                           const double                       blur,
                           const double                       noise,
                           const unsigned int                 seed)
    {
      const int  ss = 4, shift = 4; // supersampling; sub-pixel drawing bits
      const auto fix = [&](const cv::Point2d &p) {
        return cv::Point(
          cvRound((p.x + 0.5) * ss * (1 << shift) - 0.5 * (1 << shift)),
          cvRound((p.y + 0.5) * ss * (1 << shift) - 0.5 * (1 << shift)));
      };
      SyntheticSurface out;
      cv::Mat          hi_cracks = cv::Mat::zeros(size * ss, CV_8U),
              hi_blobs           = cv::Mat::zeros(size * ss, CV_8U);
      out.centre_lines           = cv::Mat::zeros(size, CV_8U);
      for (const auto &c : cracks)
        {
          std::vector<cv::Point> hi, lo;
          for (std::size_t i = 0; i < c.points.size(); ++i)
            {
              hi.push_back(fix(c.points[i]));
              lo.emplace_back(cvRound(c.points[i].x), cvRound(c.points[i].y));
              if (i)
                out.crack_length += cv::norm(c.points[i] - c.points[i - 1]);
            }
          cv::polylines(hi_cracks,
                        hi,
                        false,
                        255,
                        std::max(1, cvRound(c.width * ss)),
                        cv::LINE_8,
                        shift);
          cv::polylines(out.centre_lines, lo, false, 255, 1, cv::LINE_8);
        }
      for (const auto &b : blobs)
        {
          cv::ellipse(hi_blobs,
                      cv::RotatedRect(cv::Point2f((b.centre.x + 0.5) * ss - 0.5,
                                                  (b.centre.y + 0.5) * ss -
                                                    0.5),
                                      cv::Size2f(2 * b.semi_axes.width * ss,
                                                 2 * b.semi_axes.height * ss),
                                      b.angle),
                      255,
                      cv::FILLED,
                      cv::LINE_8);
          out.blob_area += M_PI * b.semi_axes.width * b.semi_axes.height;
        }
      cv::Mat cov_c, cov_b;
      cv::resize(hi_cracks, cov_c, size, 0, 0, cv::INTER_AREA);
      cv::resize(hi_blobs, cov_b, size, 0, 0, cv::INTER_AREA);
      cov_c.convertTo(cov_c, CV_32F, 1. / 255.);
      cov_b.convertTo(cov_b, CV_32F, 1. / 255.);
      out.blob_mask = cov_b >= 0.5f;
      cv::Mat img(size, CV_32F);
      for (int r = 0; r < size.height; ++r)
        for (int c = 0; c < size.width; ++c)
          {
            const double u = double(c) / size.width - 0.5,
                         v = double(r) / size.height - 0.5;
            const double bg =
              0.5 + gradient * (0.5 * (u + v) + 0.5 * (u * u + v * v) - 0.083);
            img.at<float>(r, c) = static_cast<float>(
              bg - contrast *
                     std::max(cov_c.at<float>(r, c), cov_b.at<float>(r, c)));
          }
      if (blur > 0.)
        cv::GaussianBlur(
          img, img, cv::Size(0, 0), blur, blur, cv::BORDER_REFLECT);
      if (noise > 0.)
        {
          cv::RNG rng(seed);
          cv::Mat n(size, CV_32F);
          rng.fill(n, cv::RNG::NORMAL, 0., noise);
          img += n;
        }
      cv::min(cv::max(img, 0.), 1., out.image);
      return out;
    }

    double
    skeleton_f1(const cv::Mat &detected,
                const cv::Mat &truth,
                const double   tolerance)
    {
      const auto within = [&](const cv::Mat &from, const cv::Mat &to) {
        cv::Mat dist;
        cv::distanceTransform(to == 0,
                              dist,
                              cv::DIST_L2,
                              cv::DIST_MASK_PRECISE);
        double hit = 0., all = 0.;
        for (int r = 0; r < from.rows; ++r)
          for (int c = 0; c < from.cols; ++c)
            if (from.at<uchar>(r, c))
              {
                all += 1.;
                hit += dist.at<float>(r, c) <= tolerance;
              }
        return all > 0. ? hit / all : 0.;
      };
      const double precision = within(detected, truth),
                   recall    = within(truth, detected);
      return precision + recall > 0. ?
               2. * precision * recall / (precision + recall) :
               0.;
    }

    void
    write_overlay(const std::string    &filename,
                  const cv::Mat        &image,
                  const CrackMap       &cracks,
                  const ExfoliationMap &exfoliations)
    {
      cv::Mat grey, colour;
      image.convertTo(grey, CV_8U, 255.);
      cv::cvtColor(grey, colour, cv::COLOR_GRAY2BGR);
      if (!exfoliations.mask.empty())
        {
          std::vector<std::vector<cv::Point>> contours;
          cv::findContours(exfoliations.mask.clone(),
                           contours,
                           cv::RETR_EXTERNAL,
                           cv::CHAIN_APPROX_NONE);
          cv::drawContours(colour, contours, -1, cv::Scalar(255, 255, 0), 2);
        }
      if (!cracks.skeleton.empty())
        {
          cv::Mat thick;
          cv::dilate(cracks.skeleton, thick, cv::Mat());
          colour.setTo(cv::Scalar(0, 0, 255), thick);
        }
      if (!cv::imwrite(filename, colour))
        throw std::runtime_error("cannot write image '" + filename + "'");
    }
  } // namespace tribology
} // namespace squeal
