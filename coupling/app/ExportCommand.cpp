#include "coupling/app/ExportCommand.h"

#include <filesystem>
#include <fstream>

#include "coupling/app/FrameOption.h"
#include "coupling/common/ExitCode.h"
#include "coupling/output/ResultFrameReader.h"
#include "coupling/scene/CsvPackingWriter.h"
#include "coupling/scene/ResultPackingReader.h"

namespace tmdem::coupling {

int run_export_command(const ExportOptions& options, std::ostream& out, std::ostream& log) {
  const std::optional<std::int64_t> parsed = parse_frame_option(options.frame);
  if (!parsed) {
    log << "error: --frame must be \"last\" or a frame number (got \"" << options.frame << "\")\n";
    return kExitInvalid;
  }
  const std::int64_t frame = *parsed;
  std::error_code ec;
  if (std::filesystem::exists(options.csv_path, ec) &&
      std::filesystem::equivalent(options.csv_path, options.result_path, ec)) {
    log << "error: -o " << options.csv_path << " names the result file itself\n";
    return kExitInvalid;
  }
  if (std::filesystem::exists(options.csv_path, ec) && !options.overwrite) {
    log << "error: " << options.csv_path << " exists; give --overwrite to replace it\n";
    return kExitInvalid;
  }
  Packing packing;
  try {
    packing = read_result_packing(options.result_path, frame);
  } catch (const FrameOutOfRange& e) {
    log << "error: " << e.what() << "\n";
    return kExitInvalid;
  } catch (const std::runtime_error& e) {  // OutputError, PackingFileError
    log << "error: " << e.what() << "\n";
    return kExitIo;
  }
  std::ofstream file(options.csv_path, std::ios::binary | std::ios::trunc);
  file << packing_csv(packing);
  file.close();
  if (!file) {
    log << "error: cannot write " << options.csv_path << "\n";
    return kExitIo;
  }
  out << "exported " << packing.rows.size() << " particles, " << packing.description << " of "
      << options.result_path << ", to " << options.csv_path << "\n";
  return kExitOk;
}

}  // namespace tmdem::coupling
