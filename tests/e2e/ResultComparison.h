#pragma once
// Bit-for-bit comparison of two result files (every dataset, all groups) and of two run
// summaries without their wall times: what "a restart equals the uninterrupted run" means.
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace tmdem::e2e {

namespace detail {

// Through links and H5Iget_type, which read the same in every HDF5 API version.
inline herr_t collect_dataset(hid_t group, const char* name, const H5L_info_t*, void* out) {
  const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
  if (object < 0) return 0;
  if (H5Iget_type(object) == H5I_DATASET) static_cast<std::vector<std::string>*>(out)->push_back(name);
  H5Oclose(object);
  return 0;
}

inline std::vector<std::string> dataset_names(hid_t file) {
  std::vector<std::string> names;
  H5Lvisit(file, H5_INDEX_NAME, H5_ITER_INC, collect_dataset, &names);
  return names;
}

// The dataset's bytes in its native memory type, with its dimensions and element size.
struct RawDataset {
  std::vector<hsize_t> dims;
  std::vector<unsigned char> bytes;
  std::size_t element_size = 0;
  bool is_double = false;
};

inline RawDataset read_raw(hid_t file, const std::string& name) {
  RawDataset r;
  const hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  r.dims.resize(std::size_t(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, r.dims.data(), nullptr);
  const hid_t type = H5Dget_type(d);
  const hid_t native = H5Tget_native_type(type, H5T_DIR_ASCEND);
  r.element_size = H5Tget_size(native);
  r.is_double = H5Tequal(native, H5T_NATIVE_DOUBLE) > 0;
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  r.bytes.resize(std::size_t(count) * r.element_size);
  if (count > 0 && H5Tget_class(native) != H5T_STRING && H5Tget_class(native) != H5T_VLEN)
    H5Dread(d, native, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.bytes.data());
  H5Tclose(native);
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(d);
  return r;
}

}  // namespace detail

// One line per dataset that is missing on one side, has other dimensions, or differs in any
// bit ("name: k of n values differ, largest |a - b| = ..."); empty when the files agree.
// `compared` counts the datasets compared.
inline std::vector<std::string> result_differences(const std::string& path_a, const std::string& path_b,
                                                   std::size_t* compared = nullptr) {
  std::vector<std::string> out;
  const hid_t a = H5Fopen(path_a.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t b = H5Fopen(path_b.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (a < 0 || b < 0) {
    out.push_back("cannot open " + std::string(a < 0 ? path_a : path_b));
  } else {
    const auto names_a = detail::dataset_names(a), names_b = detail::dataset_names(b);
    if (names_a != names_b) out.push_back("the files hold different datasets");
    if (compared) *compared = 0;
    for (const auto& name : names_a) {
      if (std::find(names_b.begin(), names_b.end(), name) == names_b.end()) continue;
      const auto ra = detail::read_raw(a, name), rb = detail::read_raw(b, name);
      if (compared) ++*compared;
      if (ra.dims != rb.dims || ra.element_size != rb.element_size) {
        out.push_back(name + ": other dimensions");
        continue;
      }
      if (ra.bytes == rb.bytes) continue;
      const std::size_t n = ra.bytes.size() / std::max<std::size_t>(ra.element_size, 1);
      std::size_t differing = 0;
      double largest = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        if (std::memcmp(&ra.bytes[k * ra.element_size], &rb.bytes[k * ra.element_size], ra.element_size) == 0)
          continue;
        ++differing;
        if (ra.is_double) {
          double x = 0.0, y = 0.0;
          std::memcpy(&x, &ra.bytes[k * 8], 8);
          std::memcpy(&y, &rb.bytes[k * 8], 8);
          largest = std::max(largest, std::abs(x - y));
        }
      }
      std::ostringstream line;
      line << name << ": " << differing << " of " << n << " values differ";
      if (ra.is_double) line << ", largest |a - b| = " << largest;
      out.push_back(line.str());
    }
  }
  if (a >= 0) H5Fclose(a);
  if (b >= 0) H5Fclose(b);
  return out;
}

// The summary without the wall times (which no two runs share).
inline nlohmann::json summary_without_wall_times(const std::string& path) {
  std::ifstream in(path);
  nlohmann::json s = nlohmann::json::parse(in);
  auto strip = [](auto& self, nlohmann::json& j) -> void {
    if (!j.is_object()) return;
    for (auto it = j.begin(); it != j.end();) {
      if (it.key().find("wall_time") != std::string::npos) {
        it = j.erase(it);
      } else {
        self(self, *it);
        ++it;
      }
    }
  };
  strip(strip, s);
  return s;
}

}  // namespace tmdem::e2e
