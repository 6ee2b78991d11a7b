#include "coupling/output/ProgressReporter.h"

#include <cstdio>
#include <iomanip>
#include <sstream>

namespace tmdem::coupling {

ProgressReporter::ProgressReporter(std::ostream& out, bool quiet, bool terminal)
    : out_(out), quiet_(quiet), terminal_(terminal),
      start_(std::chrono::steady_clock::now()), last_(start_ - std::chrono::hours(1)) {}

void ProgressReporter::update(const std::string& phase, double t_s, double t_end_s,
                              const std::string& extra) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_last < (terminal_ ? 0.2 : 5.0)) return;
  last_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  std::ostringstream line;
  line << phase << ": t = " << std::setprecision(6) << t_s << " / " << t_end_s << " s ("
       << std::fixed << std::setprecision(1) << (t_end_s > 0 ? 100.0 * t_s / t_end_s : 100.0)
       << "%), wall " << wall << " s";
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
