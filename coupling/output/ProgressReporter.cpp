#include "coupling/output/ProgressReporter.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace tmdem::coupling {

std::string eta_text(double t_begin_s, double t_s, double t_end_s, double phase_wall_s) {
  const double done_s = t_s - t_begin_s;
  if (!(done_s > 0.0) || !(phase_wall_s >= 0.1)) return "";
  const double left_s = std::max(0.0, t_end_s - t_s) * phase_wall_s / done_s;
  char text[48];
  if (left_s < 120.0)
    std::snprintf(text, sizeof text, "ETA %.0f s", left_s);
  else if (left_s < 7200.0)
    std::snprintf(text, sizeof text, "ETA %.1f min", left_s / 60.0);
  else
    std::snprintf(text, sizeof text, "ETA %.1f h", left_s / 3600.0);
  return text;
}

ProgressReporter::ProgressReporter(std::ostream& out, bool quiet, bool terminal)
    : out_(out), quiet_(quiet), terminal_(terminal),
      start_(std::chrono::steady_clock::now()), last_(start_ - std::chrono::hours(1)),
      phase_start_(start_) {}

void ProgressReporter::update(const std::string& phase, double t_s, double t_end_s,
                              const std::string& extra) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (phase != phase_) {  // before the throttle: the phase's clock starts at its first update
    phase_ = phase;
    phase_start_ = now;
    phase_t_begin_s_ = t_s;
  }
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_last < (terminal_ ? 0.2 : 5.0)) return;
  last_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  std::ostringstream line;
  line << phase << ": t = " << std::setprecision(6) << t_s << " / " << t_end_s << " s ("
       << std::fixed << std::setprecision(1) << (t_end_s > 0 ? 100.0 * t_s / t_end_s : 100.0)
       << "%), wall " << wall << " s";
  const std::string eta = eta_text(phase_t_begin_s_, t_s, t_end_s,
                                   std::chrono::duration<double>(now - phase_start_).count());
  if (!eta.empty()) line << ", " << eta;
  if (!extra.empty()) line << ", " << extra;
  if (terminal_) {
    out_ << "\r\033[K" << line.str() << std::flush;
    line_open_ = true;
  } else {
    out_ << line.str() << std::endl;
  }
}

void ProgressReporter::done() {
  if (line_open_) out_ << std::endl;
  line_open_ = false;
}

void ProgressReporter::message(const std::string& text) {
  if (quiet_) return;
  done();
  out_ << text << std::endl;
}

}  // namespace tmdem::coupling
