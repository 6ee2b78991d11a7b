#pragma once
// Small C-API helpers shared by the result file and the checkpoints: checked calls, string and
// scalar attributes, datasets with a "units" attribute, row-wise reads and writes. Every helper
// throws Hdf5Failure with the innermost HDF5 message; callers add the file name.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "coupling/output/Hdf5Handle.h"

namespace tmdem::coupling::hdf5 {

// The most specific message on the HDF5 error stack, e.g. "unable to open file: name = ...".
std::string detail();
[[noreturn]] void fail(const std::string& what);
hid_t check_id(hid_t id, const std::string& what);
void check_ok(herr_t status, const std::string& what);

// File access with HDF5's own file lock on or off (see ResultWriter.h for why the result file
// is opened without it).
Hdf5Handle file_access(bool lock);
Hdf5Handle create_file(const std::string& path, bool lock);           // truncates
Hdf5Handle open_file(const std::string& path, bool writable, bool lock);

Hdf5Handle create_group(hid_t location, const char* name);
Hdf5Handle open_group(hid_t location, const char* name);
bool exists(hid_t location, const char* name);  // a link of that name

// Scalar variable-length UTF-8 string attribute (h5py reads it as str); overwritten if present.
void write_string_attribute(hid_t object, const char* name, const std::string& value);
void write_string_array_attribute(hid_t object, const char* name,
                                  const std::vector<std::string>& values);
// Reads a scalar string attribute, variable- or fixed-length; false if absent or not a string.
bool read_string_attribute(hid_t object, const char* name, std::string& value);
// Scalar numeric attributes (file types IEEE_F64LE / STD_I64LE / STD_I32LE).
void write_double_attribute(hid_t object, const char* name, double value);
void write_int64_attribute(hid_t object, const char* name, std::int64_t value);
void write_int_attribute(hid_t object, const char* name, int value);
bool read_double_attribute(hid_t object, const char* name, double& value);
bool read_int64_attribute(hid_t object, const char* name, std::int64_t& value);
bool read_int_attribute(hid_t object, const char* name, int& value);
// 1-D double attribute [n] (IEEE_F64LE); replaced if present. Reading an absent one gives {}.
void write_double_array_attribute(hid_t object, const char* name,
                                  const std::vector<double>& values);
std::vector<double> read_double_array_attribute(hid_t object, const char* name);

// Dataset with a "units" attribute. Extendible (chunked, first dimension unlimited) and
// compressed (shuffle + deflate level 1, when the HDF5 library has deflate) when chunk_rows > 0,
// else fixed size and uncompressed. compress = false keeps a chunked dataset unfiltered: its
// chunks keep their size and place when rows are appended to them (see ResultFrames.cpp).
Hdf5Handle create_dataset(hid_t location, const char* name, hid_t file_type,
                          const std::vector<hsize_t>& dims, hsize_t chunk_rows,
                          const char* units, bool compress = true);
Hdf5Handle open_dataset(hid_t location, const char* name);
std::vector<hsize_t> dataset_dims(hid_t dataset);
hsize_t dataset_rows(hid_t dataset);
void set_rows(hid_t dataset, hsize_t rows);

// Writes `count` rows at row `first`, growing the dataset to first + count rows when `grow`.
void write_rows(hid_t dataset, hsize_t first, hsize_t count, const void* data, hid_t memory_type,
                bool grow = true);
void read_rows(hid_t dataset, hsize_t first, hsize_t count, void* data, hid_t memory_type);

// A whole fixed-size dataset [rows] (columns == 0) or [rows, columns], with units.
void write_array(hid_t location, const char* name, const std::vector<double>& values,
                 hsize_t columns, const char* units);
void write_array(hid_t location, const char* name, const std::vector<std::int64_t>& values,
                 hsize_t columns, const char* units);
// Reads a whole dataset of the given rank (columns == 0: [rows]); Hdf5Failure naming the
// dataset if it is missing or has another shape.
std::vector<double> read_double_array(hid_t location, const char* name, hsize_t columns);
std::vector<std::int64_t> read_int64_array(hid_t location, const char* name, hsize_t columns);

}  // namespace tmdem::coupling::hdf5
