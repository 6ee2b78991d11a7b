#pragma once
// A result dataset stored as blocks of fixed shape, each written once: the dataset
// (e.g. /frames/position [F, N, 3]) is an HDF5 virtual dataset whose block b (rows
// b*R .. b*R+R-1, R the block's first dimension) is the dataset <blocks group>/<name>_<b>
// (a printf-style mapping "%b", so the dataset's extent follows the blocks present: readers
// see [F, ...] as before). A block equal bit for bit to the previous one is a hard link to it.
// A frozen (settle) bed thus writes its positions, velocities and contacts once, however many
// frames follow; h5py, the Python module and the XDMF views read them as before.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tmdem::coupling {

class BlockSeries {
 public:
  // How a block fills the dataset: one row of [B, block dims...] (a frame's positions [N, 3] in
  // /frames/position [F, N, 3]), or block_dims[0] rows of [B * block_dims[0], ...] (a frame's
  // C contacts in /contacts/pair [F * C, 2]).
  enum class Rows { OnePerBlock, BlockRows };

  // Creates the virtual dataset `dataset_path` of blocks of shape `block_dims` kept in the
  // group `blocks_path` (created if missing).
  void create(hid_t file, const std::string& dataset_path, const std::string& blocks_path,
              hid_t file_type, const std::vector<hsize_t>& block_dims, Rows rows,
              const char* units);
  // An existing one; false (and nothing kept) if `dataset_path` is not a virtual dataset.
  bool open(hid_t file, const std::string& dataset_path, const std::string& blocks_path,
            Rows rows);
  // True for a dataset made by create().
  static bool is_block_series(hid_t file, const std::string& dataset_path);

  bool active() const { return !blocks_path_.empty(); }
  // Rows of the dataset per block.
  std::size_t block_rows() const {
    return rows_ == Rows::OnePerBlock ? 1 : block_dims_.empty() ? 0 : block_dims_[0];
  }
  std::size_t block_values() const;
  std::string block_path(std::size_t block) const;  // <blocks group>/<name>_<block>
  std::size_t blocks(hid_t file) const;              // blocks present: 0, 1, ... until a gap

  // Block `block` (blocks before it exist): block_values() values of `memory_type`. A hard link
  // to the previous block when the bytes are the same.
  void append(hid_t file, std::size_t block, const void* data, hid_t memory_type);
  // Removes the blocks >= `blocks`.
  void cut_back(hid_t file, std::size_t blocks);

 private:
  std::string blocks_path_, name_;
  std::vector<hsize_t> block_dims_;
  Rows rows_ = Rows::OnePerBlock;
  hid_t file_type_ = -1;
  std::string units_;
  std::vector<unsigned char> previous_;  // the last block written by this process
  std::size_t previous_block_ = 0;
  bool previous_valid_ = false;
};

}  // namespace tmdem::coupling
