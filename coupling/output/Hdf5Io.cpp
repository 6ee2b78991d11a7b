#include "coupling/output/Hdf5Io.h"

#include <algorithm>

namespace tmdem::coupling::hdf5 {
namespace {

// HDF5 closes every file still registered from an atexit handler (H5close). A file whose last
// flush failed (disk full) stays registered half-closed, and that handler then crashes inside
// H5F__close_cb (exit 139 after the right error message). tmdem closes every id itself
// (Hdf5Handle), so the handler has nothing to do: switch it off before the library starts.
const bool kNoTeardownAtExit = [] {
  H5dont_atexit();
  return true;
}();

herr_t keep_innermost(unsigned n, const H5E_error2_t* error, void* data) {
  if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
  return 0;
}

Hdf5Handle utf8_string_type() {
  Hdf5Handle type(check_id(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  check_ok(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  check_ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  return type;
}

std::string attribute_what(const char* name) { return std::string("attribute '") + name + "'"; }

Hdf5Handle scalar_attribute(hid_t object, const char* name, hid_t file_type) {
  const std::string what = attribute_what(name);
  const htri_t present = H5Aexists(object, name);
  check_ok(present < 0 ? -1 : 0, what);
  if (present > 0) return Hdf5Handle(check_id(H5Aopen(object, name, H5P_DEFAULT), what), H5Aclose);
  Hdf5Handle space(check_id(H5Screate(H5S_SCALAR), what), H5Sclose);
  return Hdf5Handle(
      check_id(H5Acreate2(object, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), what),
      H5Aclose);
}

template <class T>
void write_scalar(hid_t object, const char* name, hid_t file_type, hid_t memory_type, T value) {
  Hdf5Handle attribute = scalar_attribute(object, name, file_type);
  check_ok(H5Awrite(attribute.get(), memory_type, &value), attribute_what(name));
}

template <class T>
bool read_scalar(hid_t object, const char* name, hid_t memory_type, T& value) {
  if (H5Aexists(object, name) <= 0) return false;
  Hdf5Handle attribute(check_id(H5Aopen(object, name, H5P_DEFAULT), attribute_what(name)),
                       H5Aclose);
  check_ok(H5Aread(attribute.get(), memory_type, &value), attribute_what(name));
  return true;
}

template <class T>
void write_whole(hid_t location, const char* name, const std::vector<T>& values, hsize_t columns,
                 hid_t file_type, hid_t memory_type, const char* units) {
  const hsize_t rows = columns == 0 ? values.size() : values.size() / columns;
  std::vector<hsize_t> dims{rows};
  if (columns != 0) dims.push_back(columns);
  Hdf5Handle dataset = create_dataset(location, name, file_type, dims, 0, units);
  write_rows(dataset.get(), 0, rows, values.data(), memory_type, false);
}

template <class T>
std::vector<T> read_whole(hid_t location, const char* name, hsize_t columns, hid_t memory_type) {
  const std::string what = std::string("dataset '") + name + "'";
  if (!exists(location, name)) throw Hdf5Failure(what + " is missing");
  Hdf5Handle dataset = open_dataset(location, name);
  const std::vector<hsize_t> dims = dataset_dims(dataset.get());
  if (dims.size() != (columns == 0 ? 1u : 2u)) throw Hdf5Failure(what + " has the wrong rank");
  if (columns != 0 && dims[1] != columns) {
    throw Hdf5Failure(what + " must have " + std::to_string(columns) + " columns");
  }
  std::vector<T> values(dims[0] * (columns == 0 ? 1 : columns));
  read_rows(dataset.get(), 0, dims[0], values.data(), memory_type);
  return values;
}

}  // namespace

std::string detail() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &text);
  return text;
}

void fail(const std::string& what) {
  const std::string text = detail();
  throw Hdf5Failure(text.empty() ? what : what + ": " + text);
}

hid_t check_id(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check_ok(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

Hdf5Handle file_access(bool lock) {
  Hdf5Handle properties(check_id(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
#if H5_VERSION_GE(1, 10, 7)
  check_ok(H5Pset_file_locking(properties.get(), lock, true), "H5Pset_file_locking");
#else
  (void)lock;
#endif
  return properties;
}

Hdf5Handle create_file(const std::string& path, bool lock) {
  Hdf5Handle access = file_access(lock);
  // The 1.8 object formats at least: compact link storage and smaller object headers, so a
  // frame's views and links cost fewer bytes than with the 1.6 formats (examples/first_scene:
  // 294 kB instead of 323 kB). Not 1.10 as the lowest bound: its superblock marks a file open
  // for writing and other processes could not read a running result any more.
  // (The virtual datasets need HDF5 1.10 to read anyway.)
  check_ok(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
           "H5Pset_libver_bounds");
  return Hdf5Handle(
      check_id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), "H5Fcreate"),
      H5Fclose);
}

Hdf5Handle open_file(const std::string& path, bool writable, bool lock) {
  Hdf5Handle access = file_access(lock);
  return Hdf5Handle(check_id(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY,
                                     access.get()),
                             "H5Fopen"),
                    H5Fclose);
}

Hdf5Handle create_group(hid_t location, const char* name) {
  return Hdf5Handle(check_id(H5Gcreate2(location, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             std::string("group ") + name),
                    H5Gclose);
}

Hdf5Handle open_group(hid_t location, const char* name) {
  if (!exists(location, name)) throw Hdf5Failure(std::string("group '") + name + "' is missing");
  return Hdf5Handle(check_id(H5Gopen2(location, name, H5P_DEFAULT), std::string("group ") + name),
                    H5Gclose);
}

bool exists(hid_t location, const char* name) { return H5Lexists(location, name, H5P_DEFAULT) > 0; }

void write_string_attribute(hid_t object, const char* name, const std::string& value) {
  Hdf5Handle type = utf8_string_type();
  Hdf5Handle attribute = scalar_attribute(object, name, type.get());
  const char* text = value.c_str();
  check_ok(H5Awrite(attribute.get(), type.get(), &text), attribute_what(name));
}

void write_string_array_attribute(hid_t object, const char* name,
                                  const std::vector<std::string>& values) {
  const std::string what = attribute_what(name);
  Hdf5Handle type = utf8_string_type();
  const hsize_t count = values.size();
  Hdf5Handle space(check_id(H5Screate_simple(1, &count, nullptr), what), H5Sclose);
  Hdf5Handle attribute(
      check_id(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), what),
      H5Aclose);
  std::vector<const char*> texts;
  for (const std::string& value : values) texts.push_back(value.c_str());
  check_ok(H5Awrite(attribute.get(), type.get(), texts.data()), what);
}

bool read_string_attribute(hid_t object, const char* name, std::string& value) {
  if (H5Aexists(object, name) <= 0) return false;
  const std::string what = attribute_what(name);
  Hdf5Handle attribute(check_id(H5Aopen(object, name, H5P_DEFAULT), what), H5Aclose);
  Hdf5Handle file_type(check_id(H5Aget_type(attribute.get()), what), H5Tclose);
  if (H5Tget_class(file_type.get()) != H5T_STRING) return false;
  if (H5Tis_variable_str(file_type.get()) > 0) {
    Hdf5Handle type = utf8_string_type();
    char* text = nullptr;
    check_ok(H5Aread(attribute.get(), type.get(), &text), what);
    value = text != nullptr ? text : "";
    H5free_memory(text);
  } else {
    std::string buffer(H5Tget_size(file_type.get()), '\0');
    Hdf5Handle type(check_id(H5Tcopy(file_type.get()), what), H5Tclose);
    check_ok(H5Aread(attribute.get(), type.get(), buffer.data()), what);
    value = buffer.substr(0, buffer.find('\0'));
  }
  return true;
}

void write_double_attribute(hid_t object, const char* name, double value) {
  write_scalar(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value);
}
void write_int64_attribute(hid_t object, const char* name, std::int64_t value) {
  write_scalar(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, value);
}
void write_int_attribute(hid_t object, const char* name, int value) {
  write_scalar(object, name, H5T_STD_I32LE, H5T_NATIVE_INT, value);
}
bool read_double_attribute(hid_t object, const char* name, double& value) {
  return read_scalar(object, name, H5T_NATIVE_DOUBLE, value);
}
bool read_int64_attribute(hid_t object, const char* name, std::int64_t& value) {
  return read_scalar(object, name, H5T_NATIVE_INT64, value);
}
bool read_int_attribute(hid_t object, const char* name, int& value) {
  return read_scalar(object, name, H5T_NATIVE_INT, value);
}

void write_double_array_attribute(hid_t object, const char* name,
                                  const std::vector<double>& values) {
  const std::string what = attribute_what(name);
  const htri_t present = H5Aexists(object, name);
  check_ok(present < 0 ? -1 : 0, what);
  // Its length changes from one restart to the next, so it is replaced rather than rewritten.
  if (present > 0) check_ok(H5Adelete(object, name), what);
  const hsize_t count = values.size();
  Hdf5Handle space(check_id(H5Screate_simple(1, &count, nullptr), what), H5Sclose);
  Hdf5Handle attribute(check_id(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(),
                                           H5P_DEFAULT, H5P_DEFAULT),
                                what),
                       H5Aclose);
  if (count > 0) check_ok(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, values.data()), what);
}

std::vector<double> read_double_array_attribute(hid_t object, const char* name) {
  const std::string what = attribute_what(name);
  const htri_t present = H5Aexists(object, name);
  check_ok(present < 0 ? -1 : 0, what);
  if (present == 0) return {};
  Hdf5Handle attribute(check_id(H5Aopen(object, name, H5P_DEFAULT), what), H5Aclose);
  Hdf5Handle space(check_id(H5Aget_space(attribute.get()), what), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  check_ok(count < 0 ? -1 : 0, what);
  std::vector<double> values(static_cast<std::size_t>(count));
  if (count > 0) check_ok(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()), what);
  return values;
}

Hdf5Handle create_dataset(hid_t location, const char* name, hid_t file_type,
                          const std::vector<hsize_t>& dims, hsize_t chunk_rows,
                          const char* units, bool compress) {
  const std::string what = std::string("dataset ") + name;
  std::vector<hsize_t> max_dims = dims;
  Hdf5Handle properties(check_id(H5Pcreate(H5P_DATASET_CREATE), what), H5Pclose);
  if (chunk_rows > 0) {
    max_dims[0] = H5S_UNLIMITED;
    std::vector<hsize_t> chunk = dims;
    chunk[0] = chunk_rows;
    for (hsize_t& c : chunk) c = std::max<hsize_t>(c, 1);
    check_ok(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()), what);
    // Level 1: nearly all of deflate's gain on these arrays (zero velocities of a frozen bed,
    // repeated contact rows, int64 pairs) at a fraction of the time of higher levels.
    if (compress && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      check_ok(H5Pset_shuffle(properties.get()), what);
      check_ok(H5Pset_deflate(properties.get(), 1), what);
    }
  }
  Hdf5Handle space(check_id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(),
                                             max_dims.data()),
                            what),
                   H5Sclose);
  Hdf5Handle dataset(check_id(H5Dcreate2(location, name, file_type, space.get(), H5P_DEFAULT,
                                         properties.get(), H5P_DEFAULT),
                              what),
                     H5Dclose);
  write_string_attribute(dataset.get(), "units", units);
  return dataset;
}

Hdf5Handle open_dataset(hid_t location, const char* name) {
  return Hdf5Handle(
      check_id(H5Dopen2(location, name, H5P_DEFAULT), std::string("dataset ") + name), H5Dclose);
}

std::vector<hsize_t> dataset_dims(hid_t dataset) {
  Hdf5Handle space(check_id(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
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

namespace {

// The file selection of rows [first, first + count) and a matching memory space; false when
// the selection is empty (nothing to transfer).
bool select_rows(hid_t dataset, hsize_t first, hsize_t count, Hdf5Handle& file_space,
                 Hdf5Handle& memory_space) {
  const std::vector<hsize_t> dims = dataset_dims(dataset);
  std::vector<hsize_t> start(dims.size(), 0);
  std::vector<hsize_t> block = dims;
  start[0] = first;
  block[0] = count;
  hsize_t elements = 1;
  for (hsize_t b : block) elements *= b;
  if (elements == 0) return false;
  file_space = Hdf5Handle(check_id(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  check_ok(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                               block.data(), nullptr),
           "H5Sselect_hyperslab");
  memory_space = Hdf5Handle(
      check_id(H5Screate_simple(static_cast<int>(block.size()), block.data(), nullptr),
               "H5Screate_simple"),
      H5Sclose);
  return true;
}

}  // namespace

void write_rows(hid_t dataset, hsize_t first, hsize_t count, const void* data, hid_t memory_type,
                bool grow) {
  if (grow) {
    std::vector<hsize_t> dims = dataset_dims(dataset);
    dims[0] = first + count;
    check_ok(H5Dset_extent(dataset, dims.data()), "H5Dset_extent");
  }
  Hdf5Handle file_space, memory_space;
  if (!select_rows(dataset, first, count, file_space, memory_space)) return;
  check_ok(H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT,
                    data),
           "H5Dwrite");
}

void read_rows(hid_t dataset, hsize_t first, hsize_t count, void* data, hid_t memory_type) {
  Hdf5Handle file_space, memory_space;
  if (count == 0 || !select_rows(dataset, first, count, file_space, memory_space)) return;
  check_ok(H5Dread(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data),
           "H5Dread");
}

void write_array(hid_t location, const char* name, const std::vector<double>& values,
                 hsize_t columns, const char* units) {
  write_whole(location, name, values, columns, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, units);
}
void write_array(hid_t location, const char* name, const std::vector<std::int64_t>& values,
                 hsize_t columns, const char* units) {
  write_whole(location, name, values, columns, H5T_STD_I64LE, H5T_NATIVE_INT64, units);
}
std::vector<double> read_double_array(hid_t location, const char* name, hsize_t columns) {
  return read_whole<double>(location, name, columns, H5T_NATIVE_DOUBLE);
}
std::vector<std::int64_t> read_int64_array(hid_t location, const char* name, hsize_t columns) {
  return read_whole<std::int64_t>(location, name, columns, H5T_NATIVE_INT64);
}

}  // namespace tmdem::coupling::hdf5
