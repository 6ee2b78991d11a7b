#include "coupling/output/BlockSeries.h"

#include <cstring>
#include <stdexcept>

#include "coupling/output/Hdf5Handle.h"
#include "coupling/output/Hdf5Io.h"

namespace tmdem::coupling {
namespace {

std::string leaf_of(const std::string& path) { return path.substr(path.rfind('/') + 1); }

hid_t memory_type_of(hid_t file_type) {
  return H5Tequal(file_type, H5T_STD_I64LE) > 0 ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
}

Hdf5Handle creation_properties(hid_t dataset) {
  return Hdf5Handle(hdf5::check_id(H5Dget_create_plist(dataset), "H5Dget_create_plist"),
                    H5Pclose);
}

}  // namespace

std::size_t BlockSeries::block_values() const {
  std::size_t values = block_dims_.empty() ? 0 : 1;
  for (hsize_t d : block_dims_) values *= d;
  return values;
}

std::string BlockSeries::block_path(std::size_t block) const {
  return blocks_path_ + "/" + name_ + "_" + std::to_string(block);
}

bool BlockSeries::is_block_series(hid_t file, const std::string& dataset_path) {
  if (!hdf5::exists(file, dataset_path.c_str())) return false;
  Hdf5Handle dataset = hdf5::open_dataset(file, dataset_path.c_str());
  return H5Pget_layout(creation_properties(dataset.get()).get()) == H5D_VIRTUAL;
}

void BlockSeries::create(hid_t file, const std::string& dataset_path,
                         const std::string& blocks_path, hid_t file_type,
                         const std::vector<hsize_t>& block_dims, Rows rows, const char* units) {
  blocks_path_ = blocks_path;
  name_ = leaf_of(dataset_path);
  block_dims_ = block_dims;
  rows_ = rows;
  file_type_ = file_type;
  units_ = units;
  previous_valid_ = false;
  if (block_values() == 0) throw std::logic_error("BlockSeries " + dataset_path + ": empty block");
  if (!hdf5::exists(file, blocks_path.c_str())) hdf5::create_group(file, blocks_path.c_str());

  const std::string what = "block series " + dataset_path;
  // The dataset [0, ...] grows without bound; block b fills its rows b*R .. b*R+R-1.
  std::vector<hsize_t> block = block_dims;
  if (rows == Rows::OnePerBlock) block.insert(block.begin(), 1);
  std::vector<hsize_t> dims = block, max_dims = block;
  dims[0] = 0;
  max_dims[0] = H5S_UNLIMITED;
  Hdf5Handle space(hdf5::check_id(H5Screate_simple(int(dims.size()), dims.data(),
                                                   max_dims.data()), what),
                   H5Sclose);
  Hdf5Handle virtual_space(hdf5::check_id(H5Screate_simple(int(dims.size()), dims.data(),
                                                           max_dims.data()), what),
                           H5Sclose);
  std::vector<hsize_t> start(dims.size(), 0), stride = block, count(dims.size(), 1);
  count[0] = H5S_UNLIMITED;
  hdf5::check_ok(H5Sselect_hyperslab(virtual_space.get(), H5S_SELECT_SET, start.data(),
                                     stride.data(), count.data(), block.data()),
                 what);
  Hdf5Handle source_space(hdf5::check_id(H5Screate_simple(int(block_dims.size()),
                                                          block_dims.data(), nullptr), what),
                          H5Sclose);
  Hdf5Handle properties(hdf5::check_id(H5Pcreate(H5P_DATASET_CREATE), what), H5Pclose);
  const std::string pattern = blocks_path + "/" + name_ + "_%b";
  hdf5::check_ok(H5Pset_virtual(properties.get(), virtual_space.get(), ".", pattern.c_str(),
                                source_space.get()),
                 what);
  Hdf5Handle dataset(hdf5::check_id(H5Dcreate2(file, dataset_path.c_str(), file_type,
                                               space.get(), H5P_DEFAULT, properties.get(),
                                               H5P_DEFAULT), what),
                     H5Dclose);
  hdf5::write_string_attribute(dataset.get(), "units", units);
}

bool BlockSeries::open(hid_t file, const std::string& dataset_path,
                       const std::string& blocks_path, Rows rows) {
  *this = BlockSeries{};
  if (!is_block_series(file, dataset_path)) return false;
  const std::string what = "block series " + dataset_path;
  Hdf5Handle dataset = hdf5::open_dataset(file, dataset_path.c_str());
  Hdf5Handle properties = creation_properties(dataset.get());
  // The block's shape: the block of the virtual selection (the source selection of a "%b"
  // mapping carries no extent), without its leading 1 for one row per block.
  Hdf5Handle virtual_space(hdf5::check_id(H5Pget_virtual_vspace(properties.get(), 0), what),
                           H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(virtual_space.get());
  hdf5::check_ok(rank, what);
  std::vector<hsize_t> start(static_cast<std::size_t>(rank), 0);
  std::vector<hsize_t> stride = start, count = start, block = start;
  hdf5::check_ok(H5Sget_regular_hyperslab(virtual_space.get(), start.data(), stride.data(),
                                          count.data(), block.data()),
                 what);
  if (rows == Rows::OnePerBlock) block.erase(block.begin());
  block_dims_ = block;
  rows_ = rows;
  Hdf5Handle type(hdf5::check_id(H5Dget_type(dataset.get()), what), H5Tclose);
  file_type_ = H5Tequal(type.get(), H5T_STD_I64LE) > 0 ? H5T_STD_I64LE : H5T_IEEE_F64LE;
  hdf5::read_string_attribute(dataset.get(), "units", units_);
  blocks_path_ = blocks_path;
  name_ = leaf_of(dataset_path);
  return true;
}

std::size_t BlockSeries::blocks(hid_t file) const {
  std::size_t b = 0;
  while (hdf5::exists(file, block_path(b).c_str())) ++b;
  return b;
}

void BlockSeries::append(hid_t file, std::size_t block, const void* data, hid_t memory_type) {
  const std::size_t bytes = block_values() * H5Tget_size(memory_type);
  const std::string path = block_path(block);
  if (previous_valid_ && previous_block_ + 1 == block && previous_.size() == bytes &&
      std::memcmp(previous_.data(), data, bytes) == 0) {
    hdf5::check_ok(H5Lcreate_hard(file, block_path(previous_block_).c_str(), file, path.c_str(),
                                  H5P_DEFAULT, H5P_DEFAULT),
                   "H5Lcreate_hard " + path);
  } else {
    // One chunk per block, compressed like every other result dataset.
    Hdf5Handle dataset = hdf5::create_dataset(file, path.c_str(), file_type_, block_dims_,
                                              block_dims_[0], units_.c_str());
    hdf5::write_rows(dataset.get(), 0, block_dims_[0], data, memory_type, false);
    const auto* first = static_cast<const unsigned char*>(data);
    previous_.assign(first, first + bytes);
  }
  previous_block_ = block;
  previous_valid_ = true;
}

void BlockSeries::cut_back(hid_t file, std::size_t blocks) {
  for (std::size_t b = blocks; hdf5::exists(file, block_path(b).c_str()); ++b)
    hdf5::check_ok(H5Ldelete(file, block_path(b).c_str(), H5P_DEFAULT), "H5Ldelete " + block_path(b));
  previous_valid_ = false;
  if (blocks == 0) return;
  // The last block kept, so that an unchanged block after a restart is linked too.
  Hdf5Handle last = hdf5::open_dataset(file, block_path(blocks - 1).c_str());
  const hid_t memory_type = memory_type_of(file_type_);
  previous_.resize(block_values() * H5Tget_size(memory_type));
  hdf5::read_rows(last.get(), 0, block_dims_[0], previous_.data(), memory_type);
  previous_block_ = blocks - 1;
  previous_valid_ = true;
}

}  // namespace tmdem::coupling
