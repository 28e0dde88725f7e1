#ifndef squeal_transient_signal_h
#define squeal_transient_signal_h

/**
 * @file
 * Signal processing of the transient results: the power spectral density of a
 * uniformly sampled signal by Welch's method (FFTW), the dominant frequency
 * of a window, and the envelope of a growing oscillation with its
 * exponential growth rate and limit cycle.
 */

#include <string>
#include <vector>

namespace squeal
{
  namespace transient
  {
    /** A one-sided power spectral density. */
    struct Spectrum
    {
      std::vector<double> frequency; ///< Hz, bins 0 .. rate / 2
      std::vector<double> psd;       ///< signal unit^2 / Hz
    };

    /**
     * Welch's PSD (P. D. Welch, IEEE Trans. Audio Electroacoust. 15, 1967):
     * Hann-windowed segments of @p segment samples overlapping by half, mean
     * removed per segment, periodograms averaged, one-sided and scaled so
     * that the integral over frequency equals the signal's mean square (the
     * same convention as scipy.signal.welch with scaling='density').
     * @param x samples; @param rate sampling rate [Hz]
     * @param segment samples per segment; 0: the largest power of two that
     * gives at least 4 segments (at least 16 samples)
     * @throws std::runtime_error if @p x has fewer than 16 samples
     */
    Spectrum
    welch_psd(const std::vector<double> &x,
              double                     rate,
              unsigned int               segment = 0);

    /**
     * The frequency [Hz] of the largest peak of the Hann-windowed,
     * zero-padded (8x) periodogram of the whole of @p x above @p f_min,
     * refined by a parabola through the log power of the three bins at the
     * peak: resolution far below 1 / duration for a clean tone.
     * @throws std::runtime_error if @p x has fewer than 16 samples
     */
    double
    dominant_frequency(const std::vector<double> &x,
                       double                     rate,
                       double                     f_min = 0.);

    /** The envelope of an oscillation and what it says. */
    struct GrowthFit
    {
      std::vector<double> time;             ///< s, window centres
      std::vector<double> envelope;         ///< max |x| per window
      double              growth_rate = 0.; ///< 1/s, fitted on the growing part
      double fit_start = 0., fit_end = 0.;  ///< s, the fitted window
      double final_amplitude = 0.; ///< mean envelope over the last 20 %
      /// the envelope's peak after its smallest value exceeds 5x that value
      /// and the envelope stays above a third of the peak after it
      bool growing = false;
      /// growing, and saturated: the last 20 % flat within 20 %, or the
      /// final amplitude reached before the last 20 % and the last 20 %
      /// flat within 50 %
      bool   limit_cycle     = false;
      double saturation_time = 0.; ///< s, first reaching the final amplitude
                                   ///< (growing records only)
    };

    /**
     * Splits @p x (sampled at @p rate from @p t0 [s]) into windows of
     * @p period [s] (e.g. one period of the dominant frequency), takes the
     * largest |x| in each as the envelope, and fits ln(envelope) by least
     * squares against time from the envelope's smallest value (after the
     * start) up to where it first reaches half of the final amplitude: the
     * exponential growth rate before saturation. Without growth, the fit
     * spans the whole record (a negative rate: decay). A record that grows
     * tenfold, overshoots and settles into a limit cycle is growing with
     * limit_cycle set, whatever the overshoot (GrowthFit).
     * @throws std::runtime_error if fewer than 3 windows fit in @p x
     */
    GrowthFit
    fit_growth(const std::vector<double> &x,
               double                     rate,
               double                     t0,
               double                     period);

    /**
     * The growth rate of one spectral component of @p x (sampled at
     * @p rate [Hz] from @p t0 [s]): its amplitude at @p frequency [Hz] in
     * Hann windows of @p periods periods, a quarter window apart (a
     * short-time Fourier transform evaluated at one frequency; amplitude
     * 2 |sum w_i x_i exp(-2 pi i f t_i)| / sum w_i, the window's mean
     * removed), fitted as in fit_growth(); GrowthFit::envelope holds these
     * amplitudes at the window centres. Where several unstable modes grow at
     * once the envelope of fit_growth() mixes them; this follows the one at
     * @p frequency alone, separated from components further away than
     * about 2 f / @p periods (the Hann main lobe).
     * @throws std::runtime_error if fewer than 3 windows fit in @p x or
     * @p frequency is not in (0, rate / 2)
     */
    GrowthFit
    fit_modal_growth(const std::vector<double> &x,
                     double                     rate,
                     double                     t0,
                     double                     frequency,
                     unsigned int               periods = 16);
  } // namespace transient
} // namespace squeal

#endif
