#pragma once
// Progress of a long run on stderr: one updating line on a terminal, a plain line every few
// seconds otherwise (logs, CI), nothing with --quiet. Each line ends with an estimate of the
// wall time left in its phase ("ETA 42 s"), from the phase's mean rate so far; for "settle" the
// phase ends at the longest settle time, so its estimate is an upper bound.
#include <chrono>
#include <ostream>
#include <string>

namespace tmdem::coupling {

// "ETA 42 s", "ETA 12.5 min", "ETA 3.1 h": the wall time left if simulated time keeps advancing
// at its mean rate since the phase began (at simulated time t_begin_s, phase_wall_s ago); ""
// while there is nothing to extrapolate from (no simulated time or under 0.1 s of wall time yet).
std::string eta_text(double t_begin_s, double t_s, double t_end_s, double phase_wall_s);

class ProgressReporter {
 public:
  ProgressReporter(std::ostream& out, bool quiet, bool terminal);
  // phase: "settle", "run"; t and t_end in s of simulated time; extra: a short status text.
  void update(const std::string& phase, double t_s, double t_end_s, const std::string& extra = "");
  // Ends an updating line so later messages start on a fresh line.
  void done();
  // Prints a message on its own line (warnings), keeping the progress line intact.
  void message(const std::string& text);

 private:
  std::ostream& out_;
  bool quiet_, terminal_;
  bool line_open_ = false;
  std::chrono::steady_clock::time_point start_, last_;
  // The current phase: its name, when it began (wall clock) and its simulated time then.
  std::string phase_;
  std::chrono::steady_clock::time_point phase_start_;
  double phase_t_begin_s_ = 0.0;
};

}  // namespace tmdem::coupling
