#pragma once
// The /contacts group of a result file: pair [C,2], normal_force [C], tangential_force [C,3],
// conductance [C] and heat_flow [C] (W, from i to j or the wall); the rows of frame f are contact_offset[f] .. contact_offset[f+1]-1.
// Group attribute "stored" = 1, or 0 when output.contacts is off (the datasets then stay empty).
// A frozen contact list (every frame the same C contacts: a settle run) stores pair,
// normal_force, tangential_force and conductance as block series of C rows (BlockSeries.h,
// blocks in /contacts/blocks): a frame equal to the previous one is a hard link, so they are
// written once; heat_flow changes with the temperatures and stays a plain dataset.
#include <hdf5.h>

#include <cstdint>
#include <vector>

#include "coupling/output/BlockSeries.h"
#include "coupling/output/ContactTail.h"
#include "coupling/output/Hdf5Handle.h"
#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

class ResultContacts {
 public:
  // frozen_contacts > 0: every frame brings exactly that many contacts (std::invalid_argument
  // from append otherwise).
  void create(hid_t file, std::size_t particles, bool stored, std::size_t frozen_contacts = 0);
  // Opens an existing group. Writable: a file written before tangential_force (heat_flow)
  // existed gets the dataset, filled with 0 (NaN: not known) for the rows it already holds.
  void open(hid_t file, bool writable = true);

  bool stored() const { return stored_; }
  std::int64_t rows() const;  // the shortest of the contact datasets

  // Appends frame.contact_* at row `first`; tangential_force is 0 and heat_flow NaN when the
  // frame has none.
  void append(std::int64_t first, const FrameView& frame);
  void cut_back(std::int64_t rows);
  // The rows [start, rows) of every plain dataset, start the first row of the earliest last
  // chunk among them (ContactTail.h).
  ContactTail tail(std::int64_t rows) const;
  // Drops each plain dataset's last chunk and writes its rows again from `tail`; the datasets
  // hold tail.rows rows (after cut_back). std::invalid_argument if the tail does not fit.
  void restore(const ContactTail& tail);
  void close();

 private:
  // Each dataset with its block series (nullptr: heat_flow has none) and columns.
  struct Part {
    const Hdf5Handle* dataset;
    const BlockSeries* blocks;
    hsize_t columns;
  };
  std::vector<Part> parts() const;
  // A plain (growing, not a block series) dataset's first row of the chunk that holds `rows - 1`.
  static hsize_t last_chunk_start(const Hdf5Handle& dataset, hsize_t rows);
  // Writes c rows at row `at` of `dataset`, or block at / c of `blocks` when it is active.
  void write(const Hdf5Handle& dataset, BlockSeries& blocks, hsize_t at, hsize_t c,
             const void* data, hid_t memory_type);

  Hdf5Handle pair_, normal_force_, tangential_force_, conductance_, heat_flow_;
  BlockSeries pair_blocks_, normal_force_blocks_, tangential_force_blocks_, conductance_blocks_;
  hid_t file_ = -1;  // not owned
  std::vector<double> filler_;  // zeros or NaN for rows a frame does not give
  bool stored_ = true;
};

}  // namespace tmdem::coupling
