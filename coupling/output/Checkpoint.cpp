#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Checkpoint.h"

#include <H5Cpp.h>
#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

#ifndef TMDEM_VERSION
#define TMDEM_VERSION "0.1.0"
#endif

namespace tmdem::coupling {
namespace {

constexpr const char* kFormat = "tmdem-checkpoint-1";

using ScopedSilence = Hdf5ErrorSilence;

// A checkpoint problem found by this file (not by HDF5).
struct Invalid : std::runtime_error {
  using std::runtime_error::runtime_error;
};

H5::StrType utf8_string_type() {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  return type;
}

H5::FileAccPropList file_access(bool lock) {
  H5::FileAccPropList access;
#if H5_VERSION_GE(1, 10, 7)
  // Writing: PATH.tmp is private, no lock needed. Reading: lock where the file system can.
  H5Pset_file_locking(access.getId(), lock, true);
#else
  (void)lock;
#endif
  return access;
}

void put_string(H5::H5Object& object, const char* name, const std::string& value) {
  H5::StrType type = utf8_string_type();
  H5::Attribute attribute = object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, value);
}

template <class T>
void put_scalar(H5::H5Object& object, const char* name, const T& value,
                const H5::PredType& file_type, const H5::PredType& memory_type) {
  H5::Attribute attribute = object.createAttribute(name, file_type, H5::DataSpace(H5S_SCALAR));
  attribute.write(memory_type, &value);
}

std::string get_string(const H5::H5Object& object, const char* name) {
  if (!object.attrExists(name)) throw Invalid(std::string("attribute '") + name + "' is missing");
  H5::Attribute attribute = object.openAttribute(name);
  std::string value;
  attribute.read(attribute.getStrType(), value);
  return value;
}

template <class T>
T get_scalar(const H5::H5Object& object, const char* name, const H5::PredType& memory_type) {
  if (!object.attrExists(name)) throw Invalid(std::string("attribute '") + name + "' is missing");
  T value{};
  object.openAttribute(name).read(memory_type, &value);
  return value;
}

// A [rows] (columns == 0) or [rows, columns] dataset with a "units" attribute.
template <class T>
void put_array(H5::Group& group, const char* name, const std::vector<T>& values,
               hsize_t columns, const H5::PredType& file_type, const H5::PredType& memory_type,
               const char* units) {
  const hsize_t rows = columns == 0 ? values.size() : values.size() / columns;
  const hsize_t dims[2] = {rows, columns};
  H5::DataSpace space(columns == 0 ? 1 : 2, dims);
  H5::DataSet dataset = group.createDataSet(name, file_type, space);
  if (!values.empty()) dataset.write(values.data(), memory_type);
  put_string(dataset, "units", units);
}

template <class T>
std::vector<T> get_array(const H5::Group& group, const char* name, hsize_t columns,
                         const H5::PredType& memory_type) {
  if (!group.nameExists(name)) throw Invalid(std::string("dataset '") + name + "' is missing");
  H5::DataSet dataset = group.openDataSet(name);
  H5::DataSpace space = dataset.getSpace();
  const int rank = space.getSimpleExtentNdims();
  hsize_t dims[2] = {0, 0};
  if (rank != (columns == 0 ? 1 : 2)) {
    throw Invalid(std::string("dataset '") + name + "' has the wrong rank");
  }
  space.getSimpleExtentDims(dims);
  if (columns != 0 && dims[1] != columns) {
    throw Invalid(std::string("dataset '") + name + "' must have " + std::to_string(columns) +
                  " columns");
  }
  std::vector<T> values(dims[0] * (columns == 0 ? 1 : columns));
  if (!values.empty()) dataset.read(values.data(), memory_type);
  return values;
}

// Makes the written bytes durable before the rename (best effort).
void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

std::string describe(const H5::Exception& e) {
  std::string text = e.getFuncName();
  if (!e.getDetailMsg().empty()) text += (text.empty() ? "" : ": ") + e.getDetailMsg();
  return text.empty() ? "HDF5 error" : text;
}

}  // namespace

void write_checkpoint(const std::string& path, const CheckpointState& s) {
  const std::size_t n = s.temperature_K.size();
  const std::size_t c = s.contact_pair.size() / 2;
  if (s.position_m.size() != 3 * n || s.velocity_m_per_s.size() != 3 * n ||
      s.angular_velocity_rad_per_s.size() != 3 * n) {
    throw std::invalid_argument(
        "CheckpointState: position_m, velocity_m_per_s and angular_velocity_rad_per_s need 3 N "
        "values (N = temperature_K.size() = " + std::to_string(n) + ")");
  }
  if (s.contact_pair.size() != 2 * c || s.contact_impulse_N_s.size() != 3 * c) {
    throw std::invalid_argument(
        "CheckpointState: contact_pair needs 2 C values and contact_impulse_N_s 3 C");
  }
  const std::string temporary = path + ".tmp";
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder, error)) {
    throw OutputError("cannot write checkpoint '" + path + "': folder '" + folder.string() +
                      "' does not exist");
  }
  std::string problem;
  bool created = false;  // PATH.tmp is ours to remove
  {
    ScopedSilence silence;
    try {
      H5::H5File file(temporary, H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT,
                      file_access(false));
      created = true;
      put_string(file, "format", kFormat);
      put_string(file, "version", TMDEM_VERSION);
      put_string(file, "scene", s.scene_toml);
      put_scalar(file, "time_s", s.time_s, H5::PredType::IEEE_F64LE, H5::PredType::NATIVE_DOUBLE);
      put_scalar(file, "boundary_heat_J", s.boundary_heat_J, H5::PredType::IEEE_F64LE,
                 H5::PredType::NATIVE_DOUBLE);
      put_scalar(file, "frames_written", s.frames_written, H5::PredType::STD_I64LE,
                 H5::PredType::NATIVE_INT64);
      const auto& f64 = H5::PredType::IEEE_F64LE;
      const auto& dbl = H5::PredType::NATIVE_DOUBLE;
      put_array(file, "position", s.position_m, 3, f64, dbl, "m");
      put_array(file, "velocity", s.velocity_m_per_s, 3, f64, dbl, "m/s");
      put_array(file, "angular_velocity", s.angular_velocity_rad_per_s, 3, f64, dbl, "rad/s");
      put_array(file, "temperature", s.temperature_K, 0, f64, dbl, "K");
      H5::Group contacts = file.createGroup("contacts");
      put_array(contacts, "pair", s.contact_pair, 2, H5::PredType::STD_I64LE,
                H5::PredType::NATIVE_INT64, "1");
      put_array(contacts, "impulse", s.contact_impulse_N_s, 3, f64, dbl, "N s");
      H5::Group extra = file.createGroup("extra");
      for (const auto& [name, value] : s.extra) {
        H5::DataSet d = extra.createDataSet(name, f64, H5::DataSpace(H5S_SCALAR));
        d.write(&value, dbl);
      }
      file.close();
    } catch (const H5::Exception& e) {
      problem = describe(e);
    }
  }
  if (problem.empty()) {
    sync_file(temporary);
    std::filesystem::rename(temporary, path, error);
    if (error) problem = "cannot rename '" + temporary + "': " + error.message();
  }
  if (!problem.empty()) {
    if (created) std::filesystem::remove(temporary, error);
    throw OutputError("cannot write checkpoint '" + path + "': " + problem);
  }
  if (!folder.empty()) sync_file(folder.string());
}

CheckpointState read_checkpoint(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw OutputError("cannot read checkpoint '" + path + "': no such file");
  }
  CheckpointState s;
  ScopedSilence silence;
  try {
    H5::H5File file(path, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, file_access(true));
    if (get_string(file, "format") != kFormat) {
      throw Invalid(std::string("not a ") + kFormat + " file");
    }
    s.scene_toml = get_string(file, "scene");
    s.time_s = get_scalar<double>(file, "time_s", H5::PredType::NATIVE_DOUBLE);
    s.boundary_heat_J = get_scalar<double>(file, "boundary_heat_J", H5::PredType::NATIVE_DOUBLE);
    s.frames_written =
        get_scalar<std::int64_t>(file, "frames_written", H5::PredType::NATIVE_INT64);
    const auto& dbl = H5::PredType::NATIVE_DOUBLE;
    s.position_m = get_array<double>(file, "position", 3, dbl);
    s.velocity_m_per_s = get_array<double>(file, "velocity", 3, dbl);
    s.angular_velocity_rad_per_s = get_array<double>(file, "angular_velocity", 3, dbl);
    s.temperature_K = get_array<double>(file, "temperature", 0, dbl);
    if (!file.nameExists("contacts")) throw Invalid("group 'contacts' is missing");
    H5::Group contacts = file.openGroup("contacts");
    s.contact_pair = get_array<std::int64_t>(contacts, "pair", 2, H5::PredType::NATIVE_INT64);
    s.contact_impulse_N_s = get_array<double>(contacts, "impulse", 3, dbl);
    if (file.nameExists("extra")) {
      H5::Group extra = file.openGroup("extra");
      for (hsize_t i = 0; i < extra.getNumObjs(); ++i) {
        const std::string name = extra.getObjnameByIdx(i);
        double value = 0.0;
        extra.openDataSet(name).read(&value, dbl);
        s.extra[name] = value;
      }
    }
  } catch (const Invalid& e) {
    throw OutputError("cannot read checkpoint '" + path + "': " + e.what());
  } catch (const H5::Exception& e) {
    throw OutputError("cannot read checkpoint '" + path + "': " + describe(e));
  }
  const std::size_t n = s.temperature_K.size();
  if (s.position_m.size() != 3 * n || s.velocity_m_per_s.size() != 3 * n ||
      s.angular_velocity_rad_per_s.size() != 3 * n ||
      s.contact_impulse_N_s.size() / 3 != s.contact_pair.size() / 2) {
    throw OutputError("cannot read checkpoint '" + path +
                      "': particle or contact counts of its datasets disagree");
  }
  return s;
}

}  // namespace tmdem::coupling
