#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/ResultWriter.h"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "coupling/output/XdmfWriter.h"

#ifndef TMDEM_VERSION
#define TMDEM_VERSION "0.1.0"
#endif

namespace tmdem::coupling {
namespace {

constexpr const char* kFormat = "tmdem-result-1";

// An HDF5 call failed; the public functions turn it into an OutputError naming the file.
struct Hdf5Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

herr_t keep_innermost(unsigned n, const H5E_error2_t* error, void* data) {
  if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
  return 0;
}

// The most specific message on the HDF5 error stack, e.g. "unable to open file: name = ...".
std::string hdf5_detail() {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &detail);
  return detail;
}

[[noreturn]] void fail(const std::string& what) {
  const std::string detail = hdf5_detail();
  throw Hdf5Failure(detail.empty() ? what : what + ": " + detail);
}

hid_t check_id(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check_ok(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

using ScopedSilence = Hdf5ErrorSilence;

// Owns one HDF5 identifier.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes; returns false if closing failed (for files: the last flush failed).
  bool reset() noexcept {
    bool ok = true;
    if (id_ >= 0 && closer_ != nullptr) ok = closer_(id_) >= 0;
    id_ = H5I_INVALID_HID;
    return ok;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

Handle utf8_string_type() {
  Handle type(check_id(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  check_ok(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  check_ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  return type;
}

// Scalar variable-length UTF-8 string attribute (h5py reads it as str); overwritten if present.
void write_string_attribute(hid_t object, const char* name, const std::string& value) {
  const std::string what = std::string("attribute '") + name + "'";
  Handle type = utf8_string_type();
  Handle attribute;
  const htri_t exists = H5Aexists(object, name);
  check_ok(exists < 0 ? -1 : 0, what);
  if (exists > 0) {
    attribute = Handle(check_id(H5Aopen(object, name, H5P_DEFAULT), what), H5Aclose);
  } else {
    Handle space(check_id(H5Screate(H5S_SCALAR), what), H5Sclose);
    attribute = Handle(
        check_id(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 what),
        H5Aclose);
  }
  const char* text = value.c_str();
  check_ok(H5Awrite(attribute.get(), type.get(), &text), what);
}

void write_string_array_attribute(hid_t object, const char* name,
                                  const std::vector<std::string>& values) {
  const std::string what = std::string("attribute '") + name + "'";
  Handle type = utf8_string_type();
  const hsize_t count = values.size();
  Handle space(check_id(H5Screate_simple(1, &count, nullptr), what), H5Sclose);
  Handle attribute(
      check_id(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), what),
      H5Aclose);
  std::vector<const char*> texts;
  for (const std::string& value : values) texts.push_back(value.c_str());
  check_ok(H5Awrite(attribute.get(), type.get(), texts.data()), what);
}

void write_int_attribute(hid_t object, const char* name, int value) {
  const std::string what = std::string("attribute '") + name + "'";
  Handle space(check_id(H5Screate(H5S_SCALAR), what), H5Sclose);
  Handle attribute(check_id(H5Acreate2(object, name, H5T_STD_I32LE, space.get(), H5P_DEFAULT,
                                       H5P_DEFAULT),
                            what),
                   H5Aclose);
  check_ok(H5Awrite(attribute.get(), H5T_NATIVE_INT, &value), what);
}

// Reads a scalar string attribute, variable- or fixed-length; nullopt-like "" plus false if absent.
bool read_string_attribute(hid_t object, const char* name, std::string& value) {
  const htri_t exists = H5Aexists(object, name);
  if (exists <= 0) return false;
  const std::string what = std::string("attribute '") + name + "'";
  Handle attribute(check_id(H5Aopen(object, name, H5P_DEFAULT), what), H5Aclose);
  Handle file_type(check_id(H5Aget_type(attribute.get()), what), H5Tclose);
  if (H5Tget_class(file_type.get()) != H5T_STRING) return false;
  if (H5Tis_variable_str(file_type.get()) > 0) {
    Handle type = utf8_string_type();
    char* text = nullptr;
    check_ok(H5Aread(attribute.get(), type.get(), &text), what);
    value = text != nullptr ? text : "";
    H5free_memory(text);
  } else {
    const std::size_t size = H5Tget_size(file_type.get());
    std::string buffer(size, '\0');
    Handle type(check_id(H5Tcopy(file_type.get()), what), H5Tclose);
    check_ok(H5Aread(attribute.get(), type.get(), buffer.data()), what);
    value = buffer.substr(0, buffer.find('\0'));
  }
  return true;
}

Handle create_group(hid_t file, const char* name) {
  return Handle(check_id(H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                         std::string("group ") + name),
                H5Gclose);
}

// Dataset with a "units" attribute. Extendible (chunked, first dimension unlimited) when
// chunk_rows > 0, else fixed size.
Handle create_dataset(hid_t location, const char* name, hid_t file_type,
                      const std::vector<hsize_t>& dims, hsize_t chunk_rows, const char* units) {
  const std::string what = std::string("dataset ") + name;
  std::vector<hsize_t> max_dims = dims;
  Handle properties(check_id(H5Pcreate(H5P_DATASET_CREATE), what), H5Pclose);
  if (chunk_rows > 0) {
    max_dims[0] = H5S_UNLIMITED;
    std::vector<hsize_t> chunk = dims;
    chunk[0] = chunk_rows;
    for (hsize_t& c : chunk) c = std::max<hsize_t>(c, 1);
    check_ok(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()), what);
  }
  Handle space(check_id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(),
                                         max_dims.data()),
                        what),
               H5Sclose);
  Handle dataset(check_id(H5Dcreate2(location, name, file_type, space.get(), H5P_DEFAULT,
                                     properties.get(), H5P_DEFAULT),
                          what),
                 H5Dclose);
  write_string_attribute(dataset.get(), "units", units);
  return dataset;
}

Handle open_dataset(hid_t file, const char* name) {
  return Handle(check_id(H5Dopen2(file, name, H5P_DEFAULT), std::string("dataset ") + name),
                H5Dclose);
}

std::vector<hsize_t> dataset_dims(hid_t dataset) {
  Handle space(check_id(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  check_ok(rank, "H5Sget_simple_extent_ndims");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  check_ok(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr),
           "H5Sget_simple_extent_dims");
  return dims;
}

hsize_t dataset_rows(hid_t dataset) {
  const std::vector<hsize_t> dims = dataset_dims(dataset);
  return dims.empty() ? 0 : dims[0];
}

void set_rows(hid_t dataset, hsize_t rows) {
  std::vector<hsize_t> dims = dataset_dims(dataset);
  dims[0] = rows;
  check_ok(H5Dset_extent(dataset, dims.data()), "H5Dset_extent");
}

// Writes `count` rows at row `first` of a dataset, growing it to first + count rows.
void write_rows(hid_t dataset, hsize_t first, hsize_t count, const void* data, hid_t memory_type,
                bool grow = true) {
  std::vector<hsize_t> dims = dataset_dims(dataset);
  if (grow) {
    dims[0] = first + count;
    check_ok(H5Dset_extent(dataset, dims.data()), "H5Dset_extent");
  }
  std::vector<hsize_t> start(dims.size(), 0);
  std::vector<hsize_t> block = dims;
  start[0] = first;
  block[0] = count;
  hsize_t elements = 1;
  for (hsize_t b : block) elements *= b;
  if (elements == 0) return;
  Handle file_space(check_id(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  check_ok(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                               block.data(), nullptr),
           "H5Sselect_hyperslab");
  Handle memory_space(
      check_id(H5Screate_simple(static_cast<int>(block.size()), block.data(), nullptr),
               "H5Screate_simple"),
      H5Sclose);
  check_ok(H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT,
                    data),
           "H5Dwrite");
}

void read_rows(hid_t dataset, hsize_t first, hsize_t count, void* data, hid_t memory_type) {
  if (count == 0) return;
  Handle file_space(check_id(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  const hsize_t start[1] = {first};
  const hsize_t block[1] = {count};
  check_ok(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, block, nullptr),
           "H5Sselect_hyperslab");
  Handle memory_space(check_id(H5Screate_simple(1, block, nullptr), "H5Screate_simple"),
                      H5Sclose);
  check_ok(H5Dread(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data),
           "H5Dread");
}

// No HDF5 file lock: readers may open the file while the run writes it (see the header).
Handle file_access_properties() {
  Handle properties(check_id(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
#if H5_VERSION_GE(1, 10, 7)
  check_ok(H5Pset_file_locking(properties.get(), false, true), "H5Pset_file_locking");
#endif
  return properties;
}

// Rows of a contact chunk: about one frame's contacts, within [256, 65536].
hsize_t contact_chunk_rows(std::size_t particles) {
  hsize_t rows = 256;
  while (rows < 3 * particles && rows < 65536) rows *= 2;
  return rows;
}

std::string folder_problem(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!parent.empty() && !std::filesystem::is_directory(parent, error)) {
    return "folder '" + parent.string() + "' does not exist";
  }
  return {};
}

constexpr hsize_t kFrameChunk = 1024;  // rows per chunk of the [F] datasets

}  // namespace

struct ResultWriter::Impl {
  std::string path;
  Handle file;
  Handle time, position, velocity, temperature, thermal_energy, boundary_heat, contact_offset;
  Handle pair, normal_force, conductance;
  std::size_t particles = 0;
  bool store_contacts = true;
  std::vector<double> times;      // of the frames written, for the XDMF
  std::int64_t contacts = 0;      // rows in /contacts/*
  std::size_t xdmf_frames = 0;    // frames in the last XDMF written
  bool finished = true;           // false once the file is complete and open

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  ~Impl() {
    if (finished) return;
    try {
      close_with_status("failed");
    } catch (...) {
      // Best effort only: a destructor never throws.
    }
  }

  void open_datasets() {
    const hid_t f = file.get();
    time = open_dataset(f, "/frames/time");
    position = open_dataset(f, "/frames/position");
    velocity = open_dataset(f, "/frames/velocity");
    temperature = open_dataset(f, "/frames/temperature");
    thermal_energy = open_dataset(f, "/frames/thermal_energy");
    boundary_heat = open_dataset(f, "/frames/boundary_heat");
    contact_offset = open_dataset(f, "/frames/contact_offset");
    pair = open_dataset(f, "/contacts/pair");
    normal_force = open_dataset(f, "/contacts/normal_force");
    conductance = open_dataset(f, "/contacts/conductance");
  }

  // Sets every dataset back to `frames` frames and `contact_rows` contacts.
  void cut_back(std::size_t frames, std::int64_t contact_rows) {
    for (const Handle* d : {&time, &position, &velocity, &temperature, &thermal_energy,
                            &boundary_heat}) {
      set_rows(d->get(), frames);
    }
    set_rows(contact_offset.get(), frames + 1);
    for (const Handle* d : {&pair, &normal_force, &conductance}) {
      set_rows(d->get(), static_cast<hsize_t>(contact_rows));
    }
  }

  void rewrite_xdmf_if_due() {
    const std::size_t frames = times.size();
    if (frames <= 1024 || (frames - xdmf_frames) * 32 >= frames) {
      write_xdmf(path, particles, times);
      xdmf_frames = frames;
    }
  }

  // Sets the status, closes the file and writes the XDMF; all steps are tried, the first error
  // is thrown as OutputError afterwards.
  void close_with_status(std::string_view status) {
    finished = true;
    std::string error;
    {
      ScopedSilence silence;
      try {
        write_string_attribute(file.get(), "status", std::string(status));
        check_ok(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
      } catch (const Hdf5Failure& e) {
        error = "cannot set status of result file '" + path + "': " + e.what();
      }
      for (Handle* d : {&time, &position, &velocity, &temperature, &thermal_energy,
                        &boundary_heat, &contact_offset, &pair, &normal_force, &conductance}) {
        d->reset();
      }
      if (!file.reset() && error.empty()) {
        error = "cannot close result file '" + path + "': " + hdf5_detail();
      }
    }
    try {
      write_xdmf(path, particles, times);
      xdmf_frames = times.size();
    } catch (const OutputError& e) {
      if (error.empty()) error = e.what();
    }
    if (!error.empty()) throw OutputError(error);
  }
};

ResultWriter::ResultWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ResultWriter::ResultWriter(const std::string& path, const ResultHeader& header,
                           bool store_contacts)
    : impl_(std::make_unique<Impl>()) {
  const std::size_t n = header.radius_m.size();
  if (header.mass_kg.size() != n || header.heat_capacity_J_per_K.size() != n ||
      header.material.size() != n) {
    throw std::invalid_argument(
        "ResultHeader: radius_m, mass_kg, heat_capacity_J_per_K and material must all have N "
        "entries");
  }
  Impl& w = *impl_;
  w.path = path;
  w.particles = n;
  w.store_contacts = store_contacts;
  if (const std::string problem = folder_problem(path); !problem.empty()) {
    throw OutputError("cannot create result file '" + path + "': " + problem);
  }
  ScopedSilence silence;
  try {
    Handle access = file_access_properties();
    w.file = Handle(check_id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
                             "H5Fcreate"),
                    H5Fclose);
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot create result file '" + path + "': " + e.what());
  }
  try {
    const hid_t f = w.file.get();
    write_string_attribute(f, "format", kFormat);
    write_string_attribute(f, "version", TMDEM_VERSION);
    write_string_attribute(f, "scene", header.scene_toml);
    write_string_attribute(f, "status", "running");

    const hsize_t nn = n;
    Handle particles = create_group(f, "particles");
    const hid_t p = particles.get();
    struct Column {
      const char* name;
      const std::vector<double>& values;
      const char* units;
    };
    for (const Column& c : {Column{"radius", header.radius_m, "m"},
                            Column{"mass", header.mass_kg, "kg"},
                            Column{"heat_capacity", header.heat_capacity_J_per_K, "J/K"}}) {
      Handle d = create_dataset(p, c.name, H5T_IEEE_F64LE, {nn}, 0, c.units);
      write_rows(d.get(), 0, nn, c.values.data(), H5T_NATIVE_DOUBLE, false);
    }
    Handle material = create_dataset(p, "material", H5T_STD_I32LE, {nn}, 0, "1");
    write_rows(material.get(), 0, nn, header.material.data(), H5T_NATIVE_INT, false);
    if (!header.material_names.empty()) {
      write_string_array_attribute(material.get(), "names", header.material_names);
    }

    Handle frames = create_group(f, "frames");
    const hid_t fr = frames.get();
    w.time = create_dataset(fr, "time", H5T_IEEE_F64LE, {0}, kFrameChunk, "s");
    w.position = create_dataset(fr, "position", H5T_IEEE_F64LE, {0, nn, 3}, 1, "m");
    w.velocity = create_dataset(fr, "velocity", H5T_IEEE_F64LE, {0, nn, 3}, 1, "m/s");
    w.temperature = create_dataset(fr, "temperature", H5T_IEEE_F64LE, {0, nn}, 1, "K");
    w.thermal_energy = create_dataset(fr, "thermal_energy", H5T_IEEE_F64LE, {0}, kFrameChunk, "J");
    w.boundary_heat = create_dataset(fr, "boundary_heat", H5T_IEEE_F64LE, {0}, kFrameChunk, "J");
    w.contact_offset = create_dataset(fr, "contact_offset", H5T_STD_I64LE, {0}, kFrameChunk, "1");
    const std::int64_t zero = 0;
    write_rows(w.contact_offset.get(), 0, 1, &zero, H5T_NATIVE_INT64);

    Handle contacts = create_group(f, "contacts");
    const hid_t c = contacts.get();
    write_int_attribute(c, "stored", store_contacts ? 1 : 0);
    const hsize_t chunk = contact_chunk_rows(n);
    w.pair = create_dataset(c, "pair", H5T_STD_I64LE, {0, 2}, chunk, "1");
    w.normal_force = create_dataset(c, "normal_force", H5T_IEEE_F64LE, {0}, chunk, "N");
    w.conductance = create_dataset(c, "conductance", H5T_IEEE_F64LE, {0}, chunk, "W/K");
    check_ok(H5Fflush(f, H5F_SCOPE_LOCAL), "H5Fflush");
  } catch (const Hdf5Failure& e) {
    impl_.reset();  // finished is still true: closes without touching the file further
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw OutputError("cannot create result file '" + path + "': " + e.what());
  }
  w.finished = false;
}

ResultWriter ResultWriter::reopen(const std::string& path, std::size_t keep_frames) {
  auto impl = std::make_unique<Impl>();
  Impl& w = *impl;
  w.path = path;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw OutputError("cannot reopen result file '" + path + "': no such file");
  }
  ScopedSilence silence;
  try {
    Handle access = file_access_properties();
    w.file = Handle(check_id(H5Fopen(path.c_str(), H5F_ACC_RDWR, access.get()), "H5Fopen"),
                    H5Fclose);
    std::string format;
    if (!read_string_attribute(w.file.get(), "format", format) || format != kFormat) {
      throw OutputError("cannot reopen result file '" + path + "': not a " + kFormat + " file");
    }
    w.open_datasets();
    Handle radius = open_dataset(w.file.get(), "/particles/radius");
    w.particles = dataset_rows(radius.get());

    hsize_t complete = dataset_rows(w.contact_offset.get());
    complete = complete == 0 ? 0 : complete - 1;
    for (const Handle* d : {&w.time, &w.position, &w.velocity, &w.temperature,
                            &w.thermal_energy, &w.boundary_heat}) {
      complete = std::min(complete, dataset_rows(d->get()));
    }
    if (keep_frames > complete) {
      throw OutputError("cannot reopen result file '" + path + "': it holds " +
                        std::to_string(complete) + " complete frames, " +
                        std::to_string(keep_frames) + " are needed");
    }
    read_rows(w.contact_offset.get(), keep_frames, 1, &w.contacts, H5T_NATIVE_INT64);
    hsize_t contact_rows = dataset_rows(w.pair.get());
    for (const Handle* d : {&w.normal_force, &w.conductance}) {
      contact_rows = std::min(contact_rows, dataset_rows(d->get()));
    }
    if (w.contacts < 0 || static_cast<hsize_t>(w.contacts) > contact_rows) {
      throw OutputError("cannot reopen result file '" + path + "': contact_offset[" +
                        std::to_string(keep_frames) + "] = " + std::to_string(w.contacts) +
                        " exceeds the " + std::to_string(contact_rows) + " stored contacts");
    }
    w.times.resize(keep_frames);
    read_rows(w.time.get(), 0, keep_frames, w.times.data(), H5T_NATIVE_DOUBLE);

    Handle contacts(check_id(H5Gopen2(w.file.get(), "/contacts", H5P_DEFAULT), "/contacts"),
                    H5Gclose);
    if (H5Aexists(contacts.get(), "stored") > 0) {
      Handle stored(check_id(H5Aopen(contacts.get(), "stored", H5P_DEFAULT), "stored"),
                    H5Aclose);
      int value = 1;
      check_ok(H5Aread(stored.get(), H5T_NATIVE_INT, &value), "stored");
      w.store_contacts = value != 0;
    }
    w.cut_back(keep_frames, w.contacts);
    write_string_attribute(w.file.get(), "status", "running");
    check_ok(H5Fflush(w.file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot reopen result file '" + path + "': " + e.what());
  }
  w.finished = false;
  return ResultWriter(std::move(impl));
}

ResultWriter::ResultWriter(ResultWriter&&) noexcept = default;
ResultWriter& ResultWriter::operator=(ResultWriter&&) noexcept = default;
ResultWriter::~ResultWriter() = default;

void ResultWriter::write_frame(const FrameView& frame) {
  if (!impl_ || impl_->finished) throw std::logic_error("ResultWriter::write_frame after finish");
  Impl& w = *impl_;
  const std::size_t n = w.particles;
  if (frame.position_m.size() != 3 * n || frame.velocity_m_per_s.size() != 3 * n ||
      frame.temperature_K.size() != n) {
    throw std::invalid_argument("FrameView: position_m and velocity_m_per_s need " +
                                std::to_string(3 * n) + " values, temperature_K " +
                                std::to_string(n));
  }
  std::size_t new_contacts = 0;
  if (w.store_contacts) {
    new_contacts = frame.normal_force_N.size();
    if (frame.contact_pair.size() != 2 * new_contacts ||
        frame.conductance_W_per_K.size() != new_contacts) {
      throw std::invalid_argument(
          "FrameView: contact_pair needs 2 C values, normal_force_N and conductance_W_per_K C");
    }
  }
  const hsize_t f = w.times.size();
  const hsize_t c = static_cast<hsize_t>(w.contacts);
  const std::int64_t total = w.contacts + static_cast<std::int64_t>(new_contacts);
  ScopedSilence silence;
  try {
    if (new_contacts > 0) {
      write_rows(w.pair.get(), c, new_contacts, frame.contact_pair.data(), H5T_NATIVE_INT64);
      write_rows(w.normal_force.get(), c, new_contacts, frame.normal_force_N.data(),
                 H5T_NATIVE_DOUBLE);
      write_rows(w.conductance.get(), c, new_contacts, frame.conductance_W_per_K.data(),
                 H5T_NATIVE_DOUBLE);
    }
    write_rows(w.position.get(), f, 1, frame.position_m.data(), H5T_NATIVE_DOUBLE);
    write_rows(w.velocity.get(), f, 1, frame.velocity_m_per_s.data(), H5T_NATIVE_DOUBLE);
    write_rows(w.temperature.get(), f, 1, frame.temperature_K.data(), H5T_NATIVE_DOUBLE);
    write_rows(w.thermal_energy.get(), f, 1, &frame.thermal_energy_J, H5T_NATIVE_DOUBLE);
    write_rows(w.boundary_heat.get(), f, 1, &frame.boundary_heat_J, H5T_NATIVE_DOUBLE);
    write_rows(w.contact_offset.get(), f + 1, 1, &total, H5T_NATIVE_INT64);
    write_rows(w.time.get(), f, 1, &frame.time_s, H5T_NATIVE_DOUBLE);  // last: commits the frame
    check_ok(H5Fflush(w.file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
  } catch (const Hdf5Failure& e) {
    const std::string message = "cannot write frame " + std::to_string(f) +
                                " to result file '" + w.path + "': " + e.what();
    try {
      w.cut_back(f, w.contacts);
      H5Fflush(w.file.get(), H5F_SCOPE_LOCAL);
    } catch (...) {
      // The original error is the one to report.
    }
    throw OutputError(message);
  }
  w.times.push_back(frame.time_s);
  w.contacts = total;
  w.rewrite_xdmf_if_due();
}

void ResultWriter::finish(std::string_view status) {
  if (status != "ok" && status != "failed") {
    throw std::invalid_argument("ResultWriter::finish: status must be \"ok\" or \"failed\", not \"" +
                                std::string(status) + "\"");
  }
  if (!impl_ || impl_->finished) return;
  impl_->close_with_status(status);
}

std::size_t ResultWriter::frames() const { return impl_ ? impl_->times.size() : 0; }
std::size_t ResultWriter::particles() const { return impl_ ? impl_->particles : 0; }
bool ResultWriter::finished() const { return !impl_ || impl_->finished; }
const std::string& ResultWriter::path() const {
  static const std::string empty;
  return impl_ ? impl_->path : empty;
}
std::string ResultWriter::xdmf_path() const { return xdmf_path_for(path()); }

}  // namespace tmdem::coupling
