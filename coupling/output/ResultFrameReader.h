#pragma once
// One frame of a result file (contract section 3) read back: what `tmdem export` writes as CSV
// and what [[import]] format = "tmdem" turns into particles. Only complete frames count: a file
// of a run still going (or stopped by a crash) has F = min(len(/frames/time),
// len(/frames/contact_offset) - 1) of them.
#include <cstdint>
#include <string>
#include <vector>

#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

// The file is readable but has no such frame (an invalid argument rather than an I/O error).
struct FrameOutOfRange : OutputError {
  using OutputError::OutputError;
};

struct ResultFrame {
  std::string scene;            // root attribute "scene": the resolved scene as TOML text
  std::int64_t index = 0;       // frame number, 0-based
  std::int64_t frames = 0;      // complete frames in the file
  double time_s = 0.0;
  std::vector<double> radius_m;            // [N]
  std::vector<std::int64_t> material;      // [N] index into the scene's [[material]] entries
  std::vector<double> position_m;          // [N * 3]
  std::vector<double> temperature_K;       // [N]
};

// frame: 0-based, or negative counting from the end (-1: the last complete frame). Throws
// OutputError naming the file for a missing file, another format or no frame, FrameOutOfRange
// for a frame it does not hold.
ResultFrame read_result_frame(const std::string& path, std::int64_t frame = -1);

}  // namespace tmdem::coupling
