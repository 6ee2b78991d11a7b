#pragma once
// Writes the HDF5 result file of contract section 3, frame by frame, plus RESULT.xdmf next to it.
//
// Layout (every dataset has a string attribute "units"):
//   /  attributes format = "tmdem-result-1", version, scene (TOML text), status
//      ("running" while the writer is open, then "ok", "failed" or "interrupted")
//   /particles/radius [N] m, mass [N] kg, heat_capacity [N] J/K, material [N] int32 ("1";
//      attribute "names" lists the material names when given)
//   /frames/time [F] s, position [F,N,3] m, velocity [F,N,3] m/s, temperature [F,N] K,
//      thermal_energy [F] J, boundary_heat [F] J, contact_offset [F+1] int64 ("1"),
//      wall_position [F,W,3] m (files with walls: each wall's point, which a piston moves along
//      its normal; files written before it existed lack it), wall_force [F,W] N (files with
//      walls: the normal forces of each wall's contacts in the frame, summed)
//   /contacts/pair [C,2] int64 ("1"; j < 0 is wall -1-j), normal_force [C] N,
//      tangential_force [C,3] N, conductance [C] W/K, heat_flow [C] W; group attribute
//      "stored" = 1 or 0
//   /periodic (scenes with [periodic] only): axis [3] int64 (1: periodic), low [3] m, high [3] m
//   /probes (scenes with [[probe]] only): per frame and probe the count, mean, min and max
//      temperature of the particles inside (ResultProbes.h)
//   /walls and /xdmf: the walls and the per-frame views RESULT.xdmf points at (ResultViews.h)
//   A frozen bed (ResultHeader::frozen): /frames/position and velocity, /contacts/pair,
//   normal_force, tangential_force and conductance are virtual datasets over blocks in
//   /frames/blocks and /contacts/blocks, one per frame, a hard link when unchanged.
// The parts are written by ResultMetadata, ResultFrames, ResultContacts and ResultViews.
//
// Reading while the run goes on: every write_frame() ends with H5Fflush, and the writer opens the
// file without HDF5's flock(), so any reader (h5py, ParaView, another tmdem) may open the file
// read-only at any time with default settings and sees every complete frame. The frame count is
// len(/frames/time) (written last in each frame). A reader that opens the file in the middle of
// a write_frame() may get an HDF5 error; reopen then. Readers that keep the file open may see
// stale metadata, not the later frames: reopen to refresh. Inside the writing process itself, a
// second H5Fopen of the file while the writer holds it must also switch file locking off
// (H5Pset_file_locking(fapl, false, true)), else HDF5 refuses: "file locking flag values don't
// match". A second writer is refused by ResultFileLock (a record lock, see ResultFileLock.h).
//
// Files are never lost silently: the constructor refuses an existing file unless told to
// overwrite it, and reopen() checks that the file belongs to the restarted scene before it
// changes a byte. Every HDF5 identifier is owned and closed on every path (also when the disk
// is full), so HDF5's teardown at exit finds nothing open.
//
// Frames reach the .h5 and RESULT.xdmf together: each batch of frames is written and flushed,
// then the XDMF is rewritten (atomically: temporary file then rename). A batch is whatever
// arrived until the frame count has grown by 1/32 (every frame for the first 32), a second of
// wall time has passed, or 64 MiB wait; finish(), flush() and the destructor store
// what waits. After a crash both files describe the same frames (the XDMF's declared frame
// count is the datasets'), missing at most those of the last second.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/output/ContactTail.h"
#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

// A wall as the result file describes it (/walls): a plane, or a cylinder (radius_m > 0)
// about the axis through point_m along normal.
struct WallPlane {
  std::array<double, 3> point_m{};
  std::array<double, 3> normal{};     // unit; plane: into the domain; cylinder: the axis
  double radius_m = 0.0;              // 0: plane
  double temperature_K = std::numeric_limits<double>::quiet_NaN();   // NaN: adiabatic
};

// The periodic box as the result file describes it (/periodic, written only when some axis is
// periodic): positions are stored wrapped into [low, high) along each periodic axis.
struct PeriodicBounds {
  std::array<bool, 3> axis{false, false, false};
  std::array<double, 3> low_m{}, high_m{};  // m; read along the periodic axes only
  bool any() const { return axis[0] || axis[1] || axis[2]; }
};

// A probe as the result file describes it (/probes, ResultProbes.h): a sphere of radius_m > 0
// around point_m, or (radius_m == 0) the axis-aligned box of full edge lengths box_m centred on it.
struct ProbeRegion {
  std::string name;
  std::array<double, 3> point_m{};
  double radius_m = 0.0;
  std::array<double, 3> box_m{};
};

// Static data, written once. All vectors have N entries (N = radius_m.size()).
struct ResultHeader {
  std::string scene_toml;                     // resolved scene, root attribute "scene"
  std::vector<double> radius_m;
  std::vector<double> mass_kg;
  std::vector<double> heat_capacity_J_per_K;  // m c
  std::vector<int> material;                  // index into the scene's materials
  std::vector<std::string> material_names;    // optional; attribute "names" of /particles/material
  std::vector<WallPlane> walls;               // /walls, drawn in RESULT.xdmf
  PeriodicBounds periodic;                    // /periodic (none: not written)
  std::vector<ProbeRegion> probes;            // /probes (none: not written)
  // A frozen bed (mechanics "settle" or "off"): every frame has the same positions, velocities
  // and frozen_contacts contacts. Those are then written once (BlockSeries.h: each later frame
  // is a hard link while the values stay the same); readers see the same [F, ...] datasets.
  bool frozen = false;
  std::size_t frozen_contacts = 0;
};

// One frame. The spans point into the caller's arrays; nothing is kept after write_frame().
struct FrameView {
  double time_s = 0.0;
  std::span<const double> position_m;           // N*3, xyz interleaved
  std::span<const double> velocity_m_per_s;     // N*3
  std::span<const double> temperature_K;        // N
  double thermal_energy_J = 0.0;                // sum C_i T_i
  double boundary_heat_J = 0.0;                 // since t = 0
  std::span<const std::int64_t> contact_pair;   // C*2; j < 0 is wall number (-1 - j)
  std::span<const double> normal_force_N;       // C
  std::span<const double> conductance_W_per_K;  // C
  std::span<const double> tangential_force_N;   // C*3 (xyz, on i), or empty: stored as 0
  std::span<const double> heat_flow_W;          // C, from i to j (or the wall), or empty: NaN
  std::span<const double> wall_point_m;         // W*3, each wall's point now (pistons move), or
                                                // empty: where /walls/point puts it
};

// What reopen() checks before it changes a byte of an existing result file.
struct RestartMatch {
  std::size_t particles = 0;
  std::string scene_toml;        // the checkpoint's scene: must equal the file's "scene"
  double checkpoint_time_s = 0;  // the last kept frame may not lie after it
  std::string next_scene_toml;   // written as "scene" once the checks pass (empty: kept)
  // The contacts' last chunk as the checkpoint saw it (ContactTail.h; nullptr or empty: none),
  // written again once the file is cut back.
  const ContactTail* contact_tail = nullptr;
};

enum class ExistingResult { Refuse, Overwrite };

class ResultWriter {
 public:
  // Creates the file and writes header, empty frame/contact datasets and contact_offset = [0];
  // status "running". An existing file is refused (OutputError naming it) unless `existing` is
  // Overwrite; a file another writer holds is always refused. Throws OutputError naming the path
  // if the file cannot be created, std::invalid_argument if the header vectors differ in length.
  ResultWriter(const std::string& path, const ResultHeader& header, bool store_contacts,
               ExistingResult existing = ExistingResult::Refuse);

  // Restart: opens an existing result file, keeps its first keep_frames frames (and their
  // contacts), drops the rest and sets status "running" again. Throws OutputError naming the
  // path, with the file unchanged, if it is missing, held by another writer, not a
  // tmdem-result-1 file, has fewer than keep_frames frames, or (with `match`) holds another
  // particle count, another scene, or a kept frame after the checkpoint's time.
  static ResultWriter reopen(const std::string& path, std::size_t keep_frames,
                             const RestartMatch* match = nullptr);

  ResultWriter(ResultWriter&&) noexcept;
  ResultWriter& operator=(ResultWriter&&) noexcept;
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;
  // Not finished: sets status "failed", closes and writes the XDMF, best effort; never throws.
  ~ResultWriter();

  // Appends one frame (stored now or with the next batch, see above). Span sizes must match N
  // (std::invalid_argument otherwise); contacts are ignored when store_contacts is false
  // (contact_offset then stays 0). On an HDF5 failure the datasets are cut back to the previous
  // batch and OutputError is thrown; OutputError also when RESULT.xdmf cannot be rewritten (the
  // frames are then in the .h5). std::logic_error after finish(). Not thread-safe (serial
  // HDF5): one writing thread.
  void write_frame(const FrameView& frame);
  // Stores the frames waiting for their batch now (e.g. before a checkpoint counts them).
  void flush();
  // The stored contacts' last chunk (ContactTail.h), for a checkpoint; call after flush().
  ContactTail contact_tail() const;

  // status is "ok", "failed" or "interrupted" (std::invalid_argument otherwise). Sets the root attribute,
  // closes the file and writes RESULT.xdmf. A second call does nothing. Throws OutputError.
  void finish(std::string_view status);

  std::size_t frames() const;         // frames written so far, stored or waiting
  std::size_t stored_frames() const;  // frames in the .h5 (F) and in the XDMF
  std::size_t particles() const;   // N
  bool finished() const;
  const std::string& path() const;
  std::string xdmf_path() const;   // RESULT.xdmf next to RESULT.h5

 private:
  struct Impl;
  explicit ResultWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tmdem::coupling
