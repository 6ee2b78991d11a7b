#pragma once
// `tmdem probes RESULT.h5 [-o OUT.csv]`: the probes' readings (/probes, ResultProbes.h) as CSV
//   time_s,probe,count,mean_K,min_K,max_K
// one row per complete frame and probe (frames in order, probes in scene order), to stdout or
// OUT.csv (replaced if it exists). A probe with count 0 holds no particle in that frame; its
// temperatures are then 0. Exit codes: 0; 2 for a result without probes or OUT.csv naming the
// result; 4 for a result that cannot be read or an OUT.csv that cannot be written.
#include <ostream>
#include <string>

namespace tmdem::coupling {

struct ProbesOptions {
  std::string result_path;
  std::string csv_path;  // empty: stdout
};

int run_probes_command(const ProbesOptions& options, std::ostream& out, std::ostream& log);

}  // namespace tmdem::coupling
