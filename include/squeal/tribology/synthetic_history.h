#ifndef squeal_tribology_synthetic_history_h
#define squeal_tribology_synthetic_history_h

/**
 * @file
 * A synthetic squeal-like contact history (verification C3, scaled) for
 * tests and demonstrations of the tribology module.
 */

#include <squeal/io/contact_history.h>

#include <cstddef>

namespace squeal
{
  namespace tribology
  {
    /**
     * A squeal-like history for tests and demonstrations (verification C3
     * scaled): on an n x n grid of nodes over a square pad face of edge
     * @p pad_size [m] centred at (@p pad_radius, 0, 0), with sliding along
     * +y and the leading edge (where the disc enters) at y = -pad_size / 2,
     * p(t) = p_mean max(0, 1 + A (15 sin(2 pi f t) + 3 sin(6 pi f t + 0.7)))
     * with A = 1 at the leading edge on the inner radius falling linearly to
     * @p trailing_amplitude at the trailing edge (and by a factor 0.6 from
     * the inner to the outer radius), q = t_T1 = mu p (slip), t_T2 = 0,
     * status 0 where p = 0, else 2 (slip at 10 rpm times the pad radius).
     * With A = 1 and p_mean = 1 this is
     * exactly the C3 history.
     *
     * @param n nodes per side, >= 2
     * @param samples number of samples; @param sampling_rate Hz
     * @param frequency squeal frequency f [Hz]
     * @param p_mean [Pa]; @param mu friction coefficient
     * @param pad_size edge of the square pad face [m]
     * @param pad_radius radius of the pad's centre [m]
     * @param trailing_amplitude A at the trailing edge [-]
     * @throws std::invalid_argument for n < 2, fewer than 2 samples or a
     * sampling rate that is not positive.
     */
    io::ContactHistory
    synthetic_squeal_history(unsigned int n,
                             std::size_t  samples,
                             double       sampling_rate,
                             double       frequency,
                             double       p_mean,
                             double       mu,
                             double       pad_size,
                             double       pad_radius,
                             double       trailing_amplitude);
  } // namespace tribology
} // namespace squeal

#endif
