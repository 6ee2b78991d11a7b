#pragma once
// `tmdem export RESULT.h5 [--frame last|N] -o OUT.csv [--overwrite]`: one frame of a result
// (default: the last complete one) as CSV in the columns [[import]] reads
// (coupling/scene/CsvPackingWriter.h), so a packing settled by tmdem can be imported into
// another scene. Exit codes: 0; 2 for a frame the file does not hold, an existing OUT.csv
// without --overwrite, or OUT.csv naming the result; 4 for a result that cannot be read or an
// OUT.csv that cannot be written.
#include <ostream>
#include <string>

namespace tmdem::coupling {

struct ExportOptions {
  std::string result_path;
  std::string frame = "last";  // "last", or a frame number (negative counts from the end)
  std::string csv_path;
  bool overwrite = false;
};

int run_export_command(const ExportOptions& options, std::ostream& out, std::ostream& log);

}  // namespace tmdem::coupling
