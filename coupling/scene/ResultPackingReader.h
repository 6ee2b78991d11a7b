#pragma once
// Particles from one frame of a tmdem result file ([[import]] format = "tmdem"): positions,
// radii and temperatures of the frame, and each particle's material by name (the result's
// stored scene names its [[material]] entries; the importing scene must define the same names).
// Held temperatures, sources and fixed flags are not in a result: set them on the [[import]]
// table or with [[assign]].
#include <cstdint>
#include <string>

#include "coupling/scene/PackingFile.h"

namespace tmdem::coupling {

// frame: 0-based, negative counts from the end (-1: the last complete frame). Throws the
// OutputError of read_result_frame (FrameOutOfRange for a frame the file does not hold), or
// PackingFileError for a material index its stored scene does not name.
Packing read_result_packing(const std::string& path, std::int64_t frame);

}  // namespace tmdem::coupling
