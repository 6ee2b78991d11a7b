#pragma once
// The /frames group of a result file: time, position, velocity, temperature, thermal_energy,
// boundary_heat, contact_offset and (with walls) wall_position, one row per frame. /frames/time
// is written last in each frame, so len(time) is the number of complete frames. With shared
// geometry (a frozen bed), position and velocity are block series (BlockSeries.h, blocks in
// /frames/blocks): written once, every later frame a hard link.
#include <hdf5.h>

#include <cstdint>
#include <vector>

#include "coupling/output/BlockSeries.h"
#include "coupling/output/Hdf5Handle.h"
#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

class ResultFrames {
 public:
  // Creates the empty datasets for `particles` particles and `walls` walls (wall_position only
  // when walls > 0); contact_offset = [0].
  void create(hid_t file, std::size_t particles, std::size_t walls, bool shared_geometry = false);
  // wall_position is optional (files written before it existed): then frames store no walls.
  void open(hid_t file);

  // Complete frames present: min over the frame datasets and len(contact_offset) - 1.
  std::size_t complete_frames() const;
  std::int64_t contact_offset(std::size_t frame) const;
  std::vector<double> times(std::size_t frames) const;

  // Frame `index` (rows before it exist); `contact_end` = contact rows after this frame.
  // frame.wall_point_m has 3 W values when the file has wall_position.
  void append(std::size_t index, const FrameView& frame, std::int64_t contact_end);
  void cut_back(std::size_t frames);
  void close();

 private:
  // Every [F, ...] dataset (wall_position when present).
  std::vector<const Hdf5Handle*> row_datasets() const;

  Hdf5Handle time_, position_, velocity_, temperature_, thermal_energy_, boundary_heat_,
      contact_offset_, wall_position_, wall_force_;
  std::vector<double> wall_force_N_;  // one frame's wall forces (no allocation per frame)
  hid_t file_ = -1;  // not owned
  BlockSeries position_blocks_, velocity_blocks_;  // active with shared geometry
};

}  // namespace tmdem::coupling
