#pragma once
// Progress of a long run on stderr: one updating line on a terminal, a plain line every few
// seconds otherwise (logs, CI), nothing with --quiet.
#include <chrono>
#include <ostream>
#include <string>

namespace tmdem::coupling {

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
};

}  // namespace tmdem::coupling
