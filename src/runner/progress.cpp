#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace mpm_sdem::runner {

Progress::Progress(Real end_time, bool enabled)
    : end_time_(end_time),
      enabled_(enabled),
      tty_(isatty(fileno(stderr)) != 0),
      start_(Clock::now()),
      last_(start_) {}

void Progress::update(long step, Real sim_time, Real dt, long particles) {
  if (!enabled_) return;
  const auto now = Clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (since < (tty_ ? 0.25 : 10.0)) return;
  last_ = now;
  print(step, sim_time, dt, particles, false);
}

void Progress::finish(long step, Real sim_time, long particles) {
  if (enabled_) print(step, sim_time, 0, particles, true);
}

void Progress::print(long step, Real sim_time, Real dt, long particles, bool final) {
  const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
  const double rtf = wall > 0 ? sim_time / wall : 0;
  const double eta = rtf > 0 ? (end_time_ - sim_time) / rtf : 0;
  const double rate = wall > 0 ? static_cast<double>(step) * particles / wall : 0;
  if (final) {
    std::fprintf(stderr,
                 "%sstep %ld  t = %.4g s  wall %.1f s  real-time factor %.3g  %.3g Mpart-steps/s\n",
                 tty_ ? "\r\033[K" : "", step, sim_time, wall, rtf, rate * 1e-6);
    return;
  }
  std::fprintf(stderr,
               "%sstep %ld  t = %.4g / %.4g s (%.0f%%)  dt %.3g s  real-time factor %.3g  "
               "ETA %.0f s%s",
               tty_ ? "\r\033[K" : "", step, sim_time, end_time_, 100 * sim_time / end_time_, dt,
               rtf, eta, tty_ ? "" : "\n");
  std::fflush(stderr);
}

}  // namespace mpm_sdem::runner
