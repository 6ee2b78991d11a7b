#pragma once
// One CSV line per mechanics step of a run (`tmdem run --step-log FILE`; docs/step-log.md): what
// each step cost and how near the law it ended, where the run summary gives only the totals. A
// bed that takes hours shows here which steps take the sweeps (a landing, a compaction, one
// stalled configuration), without a development build.
//
// A line is written and flushed at the end of each step (NscdIntegrator::set_step_observer), so
// a run stopped or crashed keeps every step it finished. A restart appends to the file: the lines
// between its checkpoint and the stop come twice, and the later ones are the steps that stand.
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "mechanics/integrator/NscdIntegrator.h"
#include "mechanics/integrator/StepReport.h"

namespace tmdem::coupling {

class MechanicsStepLog {
 public:
  struct Column {
    std::string name;
    std::string unit;     // "-" when none
    std::string meaning;
  };
  // The columns in file order (the header line is their names), for the docs.
  static const std::vector<Column>& columns();
  // docs/step-log.md (`tmdem docs step-log`): the file described, every column listed.
  static std::string reference_markdown();

  // Creates `path` (replacing a file there), or appends to it with `append` (a restart: the
  // header is written only into an empty file). Throws OutputError naming the file.
  MechanicsStepLog(std::string path, bool append);

  // The steps that follow belong to `phase` ("settle", "run", "resettle", "settle at P Pa"), whose clock stands at
  // t_s (s): settle time within a settle, the run's simulated time in a run.
  void begin_phase(std::string phase, double t_s);
  // One line for a step of h_s seconds that ended with `report`, the fastest particle then at
  // max_speed_m_s. Throws OutputError when the line cannot be written.
  void write(double h_s, const mechanics::StepReport& report, double max_speed_m_s);

  // Every step of `nscd` from now on writes a line (NscdIntegrator::set_step_observer).
  void attach(mechanics::NscdIntegrator& nscd);

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::string phase_ = "settle";
  double t_s_ = 0.0;
};

}  // namespace tmdem::coupling
