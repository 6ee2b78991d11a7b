#pragma once
// The /contacts group of a result file: pair [C,2], normal_force [C], tangential_force [C,3],
// conductance [C] and heat_flow [C] (W, from i to j or the wall); the rows of frame f are contact_offset[f] .. contact_offset[f+1]-1.
// Group attribute "stored" = 1, or 0 when output.contacts is off (the datasets then stay empty).
#include <hdf5.h>

#include <cstdint>
#include <vector>

#include "coupling/output/Hdf5Handle.h"
#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

class ResultContacts {
 public:
  void create(hid_t file, std::size_t particles, bool stored);
  // Opens an existing group. Writable: a file written before tangential_force (heat_flow)
  // existed gets the dataset, filled with 0 (NaN: not known) for the rows it already holds.
  void open(hid_t file, bool writable = true);

  bool stored() const { return stored_; }
  std::int64_t rows() const;  // the shortest of the contact datasets

  // Appends frame.contact_* at row `first`; tangential_force is 0 and heat_flow NaN when the
  // frame has none.
  void append(std::int64_t first, const FrameView& frame);
  void cut_back(std::int64_t rows);
  void close();

 private:
  Hdf5Handle pair_, normal_force_, tangential_force_, conductance_, heat_flow_;
  std::vector<double> filler_;  // zeros or NaN for rows a frame does not give
  bool stored_ = true;
};

}  // namespace tmdem::coupling
