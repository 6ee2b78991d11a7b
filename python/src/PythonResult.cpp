#include "PythonResult.h"

#include <limits>
#include <vector>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Hdf5Io.h"
#include "coupling/output/OutputError.h"

namespace py = pybind11;
namespace hdf5 = tmdem::coupling::hdf5;

namespace tmdem::python {

namespace {

constexpr hsize_t kAllRows = std::numeric_limits<hsize_t>::max();

template <typename T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  else return H5T_NATIVE_INT64;
}

// The dataset's first min(rows, stored rows) rows, any rank, converted to T by HDF5.
template <typename T>
py::array_t<T> read_dataset(hid_t group, const char* name, hsize_t rows = kAllRows) {
  coupling::Hdf5Handle dataset = hdf5::open_dataset(group, name);
  std::vector<hsize_t> dims = hdf5::dataset_dims(dataset.get());
  if (dims.empty()) throw coupling::Hdf5Failure(std::string(name) + " is a scalar");
  if (rows < dims[0]) dims[0] = rows;
  std::vector<py::ssize_t> shape(dims.begin(), dims.end());
  py::array_t<T> values(shape);
  hdf5::read_rows(dataset.get(), 0, dims[0], values.mutable_data(), native_type<T>());
  return values;
}

std::string string_attribute(hid_t object, const char* name) {
  std::string value;
  if (!hdf5::read_string_attribute(object, name, value))
    throw coupling::Hdf5Failure(std::string("root attribute \"") + name + "\" is missing");
  return value;
}

}  // namespace

PythonResult::PythonResult(const std::string& file_path) : path(file_path) {
  coupling::Hdf5ErrorSilence silence;
  try {
    // No file lock: the writer of a running result holds the file open (ResultWriter.h).
    coupling::Hdf5Handle file = hdf5::open_file(path, false, false);
    format = string_attribute(file.get(), "format");
    status = string_attribute(file.get(), "status");
    scene = string_attribute(file.get(), "scene");

    coupling::Hdf5Handle particles = hdf5::open_group(file.get(), "particles");
    radius = read_dataset<double>(particles.get(), "radius");
    mass = read_dataset<double>(particles.get(), "mass");
    heat_capacity = read_dataset<double>(particles.get(), "heat_capacity");
    material = read_dataset<std::int64_t>(particles.get(), "material");

    coupling::Hdf5Handle frames_group = hdf5::open_group(file.get(), "frames");
    const hid_t g = frames_group.get();
    time = read_dataset<double>(g, "time");
    // contact_offset may be one frame ahead of time (time is written last in each frame).
    contact_offset = read_dataset<std::int64_t>(g, "contact_offset", time.shape(0) + 1);
    const hsize_t f = static_cast<hsize_t>(contact_offset.shape(0) - 1);
    if (f < static_cast<hsize_t>(time.shape(0))) time = read_dataset<double>(g, "time", f);
    position = read_dataset<double>(g, "position", f);
    velocity = read_dataset<double>(g, "velocity", f);
    temperature = read_dataset<double>(g, "temperature", f);
    thermal_energy = read_dataset<double>(g, "thermal_energy", f);
    boundary_heat = read_dataset<double>(g, "boundary_heat", f);
    if (temperature.shape(0) != static_cast<py::ssize_t>(f) ||
        position.shape(0) != static_cast<py::ssize_t>(f))
      throw coupling::Hdf5Failure("frames datasets are shorter than /frames/time");

    coupling::Hdf5Handle contacts_group = hdf5::open_group(file.get(), "contacts");
    const hid_t c = contacts_group.get();
    int stored = 1;
    hdf5::read_int_attribute(c, "stored", stored);
    contacts_stored = stored != 0;
    const hsize_t rows = static_cast<hsize_t>(contact_offset.at(f));
    pair = read_dataset<std::int64_t>(c, "pair", rows);
    normal_force = read_dataset<double>(c, "normal_force", rows);
    conductance = read_dataset<double>(c, "conductance", rows);
    if (hdf5::exists(c, "tangential_force")) {
      tangential_force = read_dataset<double>(c, "tangential_force", rows);
    } else {  // files written before the dataset existed
      tangential_force = py::array_t<double>(std::vector<py::ssize_t>{pair.shape(0), 3});
      std::fill_n(tangential_force.mutable_data(), tangential_force.size(), 0.0);
    }
    if (hdf5::exists(c, "heat_flow")) {
      heat_flow = read_dataset<double>(c, "heat_flow", rows);
    } else {  // files written before the dataset existed: not known
      heat_flow = py::array_t<double>(std::vector<py::ssize_t>{pair.shape(0)});
      std::fill_n(heat_flow.mutable_data(), heat_flow.size(),
                  std::numeric_limits<double>::quiet_NaN());
    }
  } catch (const coupling::Hdf5Failure& e) {
    throw coupling::OutputError("cannot read result file \"" + path + "\": " + e.what());
  }
}

py::dict PythonResult::contacts(long frame) const {
  const long count = frames();
  if (frame < 0) frame += count;
  if (frame < 0 || frame >= count)
    throw py::index_error("frame " + std::to_string(frame) + " out of range (" +
                          std::to_string(count) + " frames)");
  const py::ssize_t first = contact_offset.at(frame), end = contact_offset.at(frame + 1);
  const py::slice rows(first, end, 1);
  py::dict out;
  out["pair"] = py::object(pair)[rows];
  out["normal_force"] = py::object(normal_force)[rows];
  out["tangential_force"] = py::object(tangential_force)[rows];
  out["conductance"] = py::object(conductance)[rows];
  out["heat_flow"] = py::object(heat_flow)[rows];
  return out;
}

}  // namespace tmdem::python
