// Spectra and envelopes of the transient results (see signal.h). FFTW does
// the transforms; the rest is bookkeeping of windows and scalings.

#include <squeal/transient/signal.h>

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <stdexcept>

namespace squeal
{
  namespace transient
  {
    namespace
    {
      constexpr double pi = 3.14159265358979323846;

      std::vector<double>
      hann(const unsigned int n)
      {
        std::vector<double> w(n);
        for (unsigned int i = 0; i < n; ++i)
          w[i] = 0.5 - 0.5 * std::cos(2. * pi * i / n); // periodic form
        return w;
      }

      // |FFT|^2 of a real sequence (n_fft >= x.size(), zero-padded), bins
      // 0 .. n_fft / 2.
      std::vector<double>
      power(const std::vector<double> &x, const unsigned int n_fft)
      {
        std::vector<double>               in(n_fft, 0.);
        std::vector<std::complex<double>> out(n_fft / 2 + 1);
        std::copy(x.begin(), x.end(), in.begin());
        fftw_plan plan =
          fftw_plan_dft_r2c_1d(n_fft,
                               in.data(),
                               reinterpret_cast<fftw_complex *>(out.data()),
                               FFTW_ESTIMATE);
        fftw_execute(plan);
        fftw_destroy_plan(plan);
        std::vector<double> p(out.size());
        for (unsigned int k = 0; k < out.size(); ++k)
          p[k] = std::norm(out[k]);
        return p;
      }

      // The growth fit of an envelope (g.time, g.envelope filled): final
      // amplitude, growing / limit-cycle flags, saturation time, the
      // log-linear fit from the smallest value to half the final amplitude.
      void
      fit_envelope(GrowthFit &g)
      {
        const unsigned int n_w  = g.envelope.size();
        const unsigned int last = std::max(1u, n_w / 5);
        for (unsigned int k = n_w - last; k < n_w; ++k)
          g.final_amplitude += g.envelope[k] / last;
        double lo = 1e300, hi = 0.;
        for (unsigned int k = n_w - last; k < n_w; ++k)
          {
            lo = std::min(lo, g.envelope[k]);
            hi = std::max(hi, g.envelope[k]);
          }
        const unsigned int k_min =
          std::min_element(g.envelope.begin(), g.envelope.end()) -
          g.envelope.begin();
        const double smallest = g.envelope[k_min];
        const auto   k_peak =
          std::max_element(g.envelope.begin() + k_min, g.envelope.end());
        const double peak = *k_peak;
        // Growth: the envelope rose fivefold from its smallest value (at its
        // peak: a limit cycle may settle below an overshoot) and never fell
        // below a third of that peak afterwards (a vibration that rose and
        // died away again, or the beat of two close modes, is not an
        // instability).
        g.growing = (smallest > 0. ? peak > 5. * smallest : peak > 0.) &&
                    *std::min_element(k_peak, g.envelope.end()) >= peak / 3.;
        // Saturated: the last 20 % flat within 20 %, or the final amplitude
        // reached before the last 20 % (an overshoot that settles).
        if (g.growing)
          {
            unsigned int k_sat = k_min;
            while (k_sat + 1 < n_w && g.envelope[k_sat] < g.final_amplitude)
              ++k_sat;
            g.saturation_time = g.time[k_sat];
            g.limit_cycle =
              hi - lo <= 0.2 * g.final_amplitude ||
              (k_sat < n_w - last && hi - lo <= 0.5 * g.final_amplitude);
          }
        // the fit window
        unsigned int a = 0, b = n_w - 1;
        if (g.growing)
          {
            a = k_min;
            b = a;
            while (b + 1 < n_w && g.envelope[b + 1] < 0.5 * g.final_amplitude)
              ++b;
          }
        if (b < a + 2)
          b = std::min(n_w - 1, a + 2);
        double       st = 0, sy = 0, stt = 0, sty = 0;
        unsigned int m = 0;
        for (unsigned int k = a; k <= b; ++k)
          if (g.envelope[k] > 0.)
            {
              const double t = g.time[k], y = std::log(g.envelope[k]);
              st += t;
              sy += y;
              stt += t * t;
              sty += t * y;
              ++m;
            }
        if (m >= 2)
          g.growth_rate = (m * sty - st * sy) / (m * stt - st * st);
        g.fit_start = g.time[a];
        g.fit_end   = g.time[b];
      }
    } // namespace

    Spectrum
    welch_psd(const std::vector<double> &x,
              const double               rate,
              unsigned int               segment)
    {
      if (x.size() < 16)
        throw std::runtime_error("a spectrum needs at least 16 samples (got " +
                                 std::to_string(x.size()) + ")");
      if (segment == 0)
        {
          segment = 16;
          while (2 * segment <= x.size() * 2 / 5) // at least 4 segments
            segment *= 2;
        }
      segment                     = std::min<unsigned int>(segment, x.size());
      const std::vector<double> w = hann(segment);
      const double w2 = std::inner_product(w.begin(), w.end(), w.begin(), 0.);
      const unsigned int step = segment / 2;
      Spectrum           s;
      s.psd.assign(segment / 2 + 1, 0.);
      unsigned int n_seg = 0;
      for (std::size_t start = 0; start + segment <= x.size(); start += step)
        {
          std::vector<double> seg(x.begin() + start,
                                  x.begin() + start + segment);
          const double        mean =
            std::accumulate(seg.begin(), seg.end(), 0.) / segment;
          for (unsigned int i = 0; i < segment; ++i)
            seg[i] = (seg[i] - mean) * w[i];
          const std::vector<double> p = power(seg, segment);
          for (unsigned int k = 0; k < p.size(); ++k)
            s.psd[k] += p[k];
          ++n_seg;
        }
      for (unsigned int k = 0; k < s.psd.size(); ++k)
        {
          // one-sided: double all bins but DC and (even length) Nyquist
          const bool edge = k == 0 || (segment % 2 == 0 && k == segment / 2);
          s.psd[k] *= (edge ? 1. : 2.) / (rate * w2 * n_seg);
          s.frequency.push_back(k * rate / segment);
        }
      return s;
    }

    double
    dominant_frequency(const std::vector<double> &x,
                       const double               rate,
                       const double               f_min)
    {
      if (x.size() < 16)
        throw std::runtime_error(
          "a dominant frequency needs at least 16 samples (got " +
          std::to_string(x.size()) + ")");
      const unsigned int n        = x.size();
      const double       mean     = std::accumulate(x.begin(), x.end(), 0.) / n;
      const std::vector<double> w = hann(n);
      std::vector<double>       y(n);
      for (unsigned int i = 0; i < n; ++i)
        y[i] = (x[i] - mean) * w[i];
      const unsigned int        n_fft = 8 * n;
      const std::vector<double> p     = power(y, n_fft);
      unsigned int              best  = 1;
      for (unsigned int k = 1; k + 1 < p.size(); ++k)
        if (k * rate / n_fft >= f_min && p[k] > p[best])
          best = k;
      double shift = 0.;
      if (best > 0 && best + 1 < p.size() && p[best - 1] > 0 && p[best + 1] > 0)
        {
          const double a = std::log(p[best - 1]), b = std::log(p[best]),
                       c = std::log(p[best + 1]);
          const double d = a - 2 * b + c;
          if (d < 0)
            shift = 0.5 * (a - c) / d;
        }
      return (best + shift) * rate / n_fft;
    }

    GrowthFit
    fit_growth(const std::vector<double> &x,
               const double               rate,
               const double               t0,
               const double               period)
    {
      GrowthFit          g;
      const unsigned int per = std::max(1., std::round(period * rate));
      const unsigned int n_w = x.size() / per;
      if (n_w < 3)
        throw std::runtime_error(
          "the record is too short for an envelope: fewer than 3 periods");
      for (unsigned int k = 0; k < n_w; ++k)
        {
          double m = 0.;
          for (unsigned int i = k * per; i < (k + 1) * per; ++i)
            m = std::max(m, std::abs(x[i]));
          g.time.push_back(t0 + (k + 0.5) * per / rate);
          g.envelope.push_back(m);
        }
      fit_envelope(g);
      return g;
    }

    GrowthFit
    fit_modal_growth(const std::vector<double> &x,
                     const double               rate,
                     const double               t0,
                     const double               frequency,
                     const unsigned int         periods)
    {
      if (!(frequency > 0. && frequency < rate / 2.))
        throw std::runtime_error("a modal growth rate needs a frequency "
                                 "between 0 and half the sampling rate");
      const unsigned int length =
        std::max(4., std::round(periods / frequency * rate));
      const unsigned int hop = std::max(1u, length / 4);
      if (x.size() < length + 2 * hop)
        throw std::runtime_error(
          "the record is too short for a modal growth rate: fewer than 3 "
          "windows of " +
          std::to_string(periods) + " periods");
      const std::vector<double> w     = hann(length);
      const double              w_sum = std::accumulate(w.begin(), w.end(), 0.);
      GrowthFit                 g;
      for (std::size_t start = 0; start + length <= x.size(); start += hop)
        {
          const double mean =
            std::accumulate(x.begin() + start, x.begin() + start + length, 0.) /
            length;
          std::complex<double> c = 0.;
          for (unsigned int i = 0; i < length; ++i)
            c += w[i] * (x[start + i] - mean) *
                 std::polar(1., -2. * pi * frequency * (start + i) / rate);
          g.time.push_back(t0 + (start + 0.5 * length) / rate);
          g.envelope.push_back(2. * std::abs(c) / w_sum);
        }
      fit_envelope(g);
      return g;
    }
  } // namespace transient
} // namespace squeal
