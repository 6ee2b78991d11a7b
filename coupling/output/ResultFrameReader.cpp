#include "coupling/output/ResultFrameReader.h"

#include <algorithm>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Hdf5Io.h"
#include "coupling/output/OutputError.h"
#include "coupling/output/ResultMetadata.h"

namespace tmdem::coupling {

namespace {

// Row `row` of a dataset [F, N] or [F, N, 3], as `per_row` values.
std::vector<double> read_frame_row(hid_t group, const char* name, hsize_t row, hsize_t per_row) {
  Hdf5Handle dataset = hdf5::open_dataset(group, name);
  const auto dims = hdf5::dataset_dims(dataset.get());
  hsize_t size = 1;
  for (std::size_t d = 1; d < dims.size(); ++d) size *= dims[d];
  if (dims.empty() || dims[0] <= row || size != per_row)
    throw Hdf5Failure(std::string("/frames/") + name + " does not hold frame " +
                      std::to_string(row) + " of " + std::to_string(per_row) + " values");
  std::vector<double> values(per_row);
  hdf5::read_rows(dataset.get(), row, 1, values.data(), H5T_NATIVE_DOUBLE);
  return values;
}

}  // namespace

ResultFrame read_result_frame(const std::string& path, std::int64_t frame) {
  Hdf5ErrorSilence silence;
  const std::string where = "result file '" + path + "'";
  ResultFrame out;
  try {
    // No file lock: a running result is held open by its writer (ResultWriter.h).
    Hdf5Handle file = hdf5::open_file(path, false, false);
    std::string format;
    if (!hdf5::read_string_attribute(file.get(), "format", format) || format != kResultFormat)
      throw OutputError(where + " is not a tmdem result (root attribute format is not \"" +
                        std::string(kResultFormat) + "\")");
    if (!hdf5::read_string_attribute(file.get(), "scene", out.scene))
      throw OutputError(where + " has no root attribute scene");
    Hdf5Handle particles = hdf5::open_group(file.get(), "particles");
    out.radius_m = hdf5::read_double_array(particles.get(), "radius", 0);
    out.material = hdf5::read_int64_array(particles.get(), "material", 0);
    const hsize_t n = out.radius_m.size();
    if (out.material.size() != n)
      throw OutputError(where + ": /particles/material and /particles/radius differ in length");

    Hdf5Handle frames = hdf5::open_group(file.get(), "frames");
    Hdf5Handle time = hdf5::open_dataset(frames.get(), "time");
    Hdf5Handle offsets = hdf5::open_dataset(frames.get(), "contact_offset");
    const hsize_t times = hdf5::dataset_rows(time.get());
    const hsize_t offset_rows = hdf5::dataset_rows(offsets.get());
    out.frames = static_cast<std::int64_t>(std::min(times, offset_rows > 0 ? offset_rows - 1 : 0));
    if (out.frames == 0) throw OutputError(where + " holds no complete frame");
    out.index = frame < 0 ? out.frames + frame : frame;
    if (out.index < 0 || out.index >= out.frames)
      throw FrameOutOfRange(where + " has frames 0 to " + std::to_string(out.frames - 1) +
                        " (-1 = the last); frame " + std::to_string(frame) + " does not exist");
    const auto row = static_cast<hsize_t>(out.index);
    hdf5::read_rows(time.get(), row, 1, &out.time_s, H5T_NATIVE_DOUBLE);
    out.position_m = read_frame_row(frames.get(), "position", row, 3 * n);
    out.temperature_K = read_frame_row(frames.get(), "temperature", row, n);
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot read " + where + ": " + e.what());
  }
  return out;
}

}  // namespace tmdem::coupling
