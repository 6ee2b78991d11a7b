#include "coupling/app/ProbesCommand.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "coupling/common/CsvField.h"
#include "coupling/common/ExitCode.h"
#include "coupling/common/ShortestNumber.h"
#include "coupling/output/OutputError.h"
#include "coupling/output/ResultProbes.h"

namespace tmdem::coupling {
int run_probes_command(const ProbesOptions& options, std::ostream& out, std::ostream& log) {
  std::error_code ec;
  if (!options.csv_path.empty() && std::filesystem::exists(options.csv_path, ec) &&
      std::filesystem::equivalent(options.csv_path, options.result_path, ec)) {
    log << "error: -o " << options.csv_path << " names the result file itself\n";
    return kExitInvalid;
  }
  if (!std::filesystem::is_regular_file(options.result_path, ec)) {
    log << "error: cannot read result file '" << options.result_path << "': no such file\n";
    return kExitIo;
  }
  ProbeSeries series;
  bool has_probes = false;
  try {
    series = read_probe_series(options.result_path, has_probes);
  } catch (const OutputError& e) {
    log << "error: " << e.what() << "\n";
    return kExitIo;
  }
  if (!has_probes) {
    log << "error: result file '" << options.result_path
        << "' has no probes (/probes): add [[probe]] tables to the scene and run it again\n";
    return kExitInvalid;
  }
  std::ostringstream csv;
  csv << "time_s,probe,count,mean_K,min_K,max_K\n";
  const std::size_t n = series.names.size();
  for (std::size_t f = 0; f < series.time_s.size(); ++f)
    for (std::size_t p = 0; p < n; ++p) {
      const std::size_t k = f * n + p;
      csv << shortest_number(series.time_s[f]) << ',' << csv_field(series.names[p]) << ','
          << series.count[k] << ',' << shortest_number(series.mean_K[k]) << ','
          << shortest_number(series.min_K[k]) << ',' << shortest_number(series.max_K[k]) << '\n';
    }
  if (options.csv_path.empty()) {
    out << csv.str();
    return kExitOk;
  }
  std::ofstream file(options.csv_path, std::ios::binary | std::ios::trunc);
  file << csv.str();
  file.close();
  if (!file) {
    log << "error: cannot write " << options.csv_path << "\n";
    return kExitIo;
  }
  log << "wrote " << series.time_s.size() << " frames of " << n << " probes of "
      << options.result_path << " to " << options.csv_path << "\n";
  return kExitOk;
}

}  // namespace tmdem::coupling
