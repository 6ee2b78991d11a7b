#pragma once
// What RESULT.xdmf points at: the /walls group and the /xdmf group of a result file.
//
// ParaView 5.11's Xdmf3 readers (Xdmf3 Reader S and T) show 0 points for XDMF HyperSlab items,
// so RESULT.xdmf names one whole dataset per frame and array. Those per-frame datasets are HDF5
// virtual datasets onto the frame's rows of /frames/* and /contacts/* (no data is copied); only
// the contact line set's connectivity and the feet of wall contacts are real data.
//   /walls/point [W,3] m, normal [W,3] 1, radius [W] m (0: plane, else a cylinder about the
//     axis through point along normal), temperature [W] K (NaN: adiabatic)
//   /xdmf/vertices [N] int64 0..N-1: Polyvertex connectivity, and the particle id
//   /xdmf/walls/points [4Q,3] m, quads [Q,4], temperature [Q] K: Q quadrilaterals; a plane is
//     one square around the particles of the first frame (half side: the bounding box's half
//     diagonal plus twice r_max), a cylinder 32 strips over the particles' extent along its axis
//   /xdmf/frame_<f>/position [N,3], velocity [N,3], temperature [N]          (virtual)
//   /xdmf/frame_<f>/contact_lines [C_f,2] int64: particle ids i, j, or N + k for the k-th wall
//     contact of the frame, whose end is wall_feet[k] [W_f,3] (the centre's projection on it)
//   /xdmf/frame_<f>/image_ends [I_f,3] m (periodic scenes): a contact round a periodic boundary is
//     drawn from i to the image of j beside it, not across the box: its line's second end is
//     N + W_f + k for the k-th such contact of the frame, the point image_ends[k]
//   /xdmf/frame_<f>/contact_points [N+W_f+I_f,3]: the positions, wall_feet, image_ends (virtual)
//   /xdmf/frame_<f>/normal_force, conductance, heat_flow [C_f], tangential_force [C_f,3] (virtual)
//   /xdmf/frame_<f>/wall_points [4Q,3] m: only in a frame where a wall (a piston) stands away
//     from /walls/point: /xdmf/walls/points with each wall's quads shifted by how far its point
//     has moved (/frames/wall_position[f] - /walls/point)
// In a frozen bed every view but temperature and heat_flow is a hard link to frame 0's.
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

// What the XDMF of one frame needs to know.
struct FrameViewCounts {
  std::size_t contacts = 0;       // C_f (0: no contact grid in this frame)
  std::size_t wall_contacts = 0;  // W_f
  std::size_t image_ends = 0;     // I_f: contacts round a periodic boundary
  bool moved_walls = false;       // the frame has its own wall_points (a wall has moved)
};

class ResultViews {
 public:
  // /walls and /xdmf/vertices of a new file.
  // /periodic too when `periodic` has a periodic axis.
  void create(hid_t file, std::size_t particles, const std::vector<WallPlane>& walls,
              const PeriodicBounds& periodic = {});
  // An existing file; a file written before /xdmf existed gets /xdmf/vertices (and no walls).
  void open(hid_t file, std::size_t particles);

  std::size_t wall_quads() const { return wall_quads_; }  // 0 before the first frame
  const std::vector<WallPlane>& walls() const { return walls_; }  // as /walls describes them
  bool has_frame(hid_t file, std::size_t frame) const;

  // The view of frame `frame` (its contacts are rows first_contact.. of /contacts; none when
  // contacts are not stored). Draws the walls on the first call if they are not drawn yet. Views
  // equal to the previous frame's (a frozen bed: same positions, velocities, contacts and
  // forces) are hard links to that frame's, so only temperature and heat_flow are new.
  FrameViewCounts add_frame(hid_t file, std::size_t frame, const FrameView& data,
                            bool contacts_stored, std::int64_t first_contact);
  // Counts of an existing frame view.
  FrameViewCounts counts(hid_t file, std::size_t frame) const;
  // Removes the views of frames >= frames (a restart cuts the file back).
  void cut_back(hid_t file, std::size_t frames);

 private:
  void draw_walls(hid_t file, std::span<const double> position_m);
  // Writes the frame's wall_points when a wall is away from where it was drawn; false if none.
  bool write_moved_walls(hid_t file, hid_t frame_group, std::span<const double> wall_point_m);

  std::size_t particles_ = 0;
  std::vector<WallPlane> walls_;
  PeriodicBounds periodic_;
  std::size_t wall_quads_ = 0;
  std::vector<double> wall_corners_;    // /xdmf/walls/points, read when a wall first moves
  std::vector<std::size_t> quad_wall_;  // the wall each quad belongs to
  // The last frame's data, to tell an unchanged view (valid only after a complete frame).
  struct Previous {
    bool valid = false;
    std::size_t geometry_frame = 0;  // the frame whose position and velocity views are linked
    std::size_t contacts_frame = 0;  // the frame whose contact views are linked
    FrameViewCounts counts;
    std::vector<double> position, velocity, force, conductance, tangential;
    std::vector<std::int64_t> pair;
  } previous_;
};

}  // namespace tmdem::coupling
