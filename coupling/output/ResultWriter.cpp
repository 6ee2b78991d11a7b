#include "coupling/output/ResultWriter.h"

#include <hdf5.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Hdf5Io.h"
#include "coupling/output/PendingFrame.h"
#include "coupling/output/ResultContacts.h"
#include "coupling/output/ResultFileLock.h"
#include "coupling/output/ResultFrames.h"
#include "coupling/output/ResultMetadata.h"
#include "coupling/output/ResultProbes.h"
#include "coupling/output/ResultViews.h"
#include "coupling/output/XdmfWriter.h"

namespace tmdem::coupling {
namespace {

std::string folder_problem(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!parent.empty() && !std::filesystem::is_directory(parent, error)) {
    return "folder '" + parent.string() + "' does not exist";
  }
  return {};
}

// The file opened by HDF5 without its flock() (see ResultFileLock.h for why).
constexpr bool kHdf5Lock = false;

}  // namespace

struct ResultWriter::Impl {
  std::string path;
  ResultFileLock lock;
  Hdf5Handle file;
  ResultFrames frames;
  ResultContacts contacts;
  ResultProbes probes;
  ResultViews views;
  std::size_t particles = 0;
  std::vector<double> times;      // of the frames written, for the XDMF
  std::vector<FrameViewCounts> view_counts;  // of the frames written, for the XDMF
  std::int64_t contact_rows = 0;  // rows in /contacts/*
  std::size_t xdmf_frames = 0;    // frames in the last XDMF written
  std::chrono::steady_clock::time_point xdmf_time = std::chrono::steady_clock::now();
  std::vector<PendingFrame> pending;  // accepted, not yet in the .h5 (see sync_due)
  std::size_t pending_bytes = 0;
  bool finished = true;           // false once the file is complete and open

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  ~Impl() {
    if (finished) {
      close_ids();
      return;
    }
    try {
      close_with_status("failed");
    } catch (...) {
      // Best effort only: a destructor never throws.
    }
  }

  // The XDMF lists every frame (about 3.5 kB of text each), so rewriting it costs O(frames):
  // rewriting it after every frame made 4,000 frames take 28 s instead of 2 s, and even the
  // first 1024 frames one by one wrote 1.8 GB of XML (ResultWriterBatches: 13.6 s). And its
  // per-frame entries declare the datasets' frame count, so an XDMF older than the .h5 disagrees
  // with it. Hence frames reach the .h5 and the XDMF together, in batches: frames are stored
  // (written, flushed) and the XDMF rewritten when the frame count has grown by 1/32 (every
  // frame for the first 32), a second of wall time has passed, or 64 MiB of frames wait; frames
  // in between wait in memory. The text written is then about 33 times the final XDMF. After a
  // crash both files hold the same frames (all but the last second's, and at most 1/32 of them),
  // except in the moment between the flush of a batch and the XDMF's rename.
  bool sync_due(std::size_t total_frames) const {
    return (total_frames - xdmf_frames) * 32 >= total_frames ||
           std::chrono::steady_clock::now() - xdmf_time >= std::chrono::seconds(1) ||
           pending_bytes >= (std::size_t{64} << 20);
  }

  // Appends `batch` to the datasets, flushes, then rewrites the XDMF. On an HDF5 failure the
  // datasets are cut back to where they were and OutputError is thrown.
  void store(const std::vector<FrameView>& batch) {
    const std::size_t first = times.size();
    std::int64_t rows = contact_rows;
    try {
      Hdf5ErrorSilence silence;
      for (std::size_t k = 0; k < batch.size(); ++k) {
        const std::size_t new_contacts = contacts.stored() ? batch[k].normal_force_N.size() : 0;
        if (new_contacts > 0) contacts.append(rows, batch[k]);
        rows += static_cast<std::int64_t>(new_contacts);
        probes.append(first + k, batch[k]);  // before frames.append, whose time commits the frame
        frames.append(first + k, batch[k], rows);
        view_counts.push_back(views.add_frame(file.get(), first + k, batch[k], contacts.stored(),
                                              rows - static_cast<std::int64_t>(new_contacts)));
      }
      hdf5::check_ok(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
    } catch (const Hdf5Failure& e) {
      const std::string which = batch.size() == 1 ? "frame " + std::to_string(first)
                                                  : "frames " + std::to_string(first) + " to " +
                                                        std::to_string(first + batch.size() - 1);
      const std::string message = "cannot write " + which + " to result file '" + path + "': " + e.what();
      try {
        Hdf5ErrorSilence silence;
        frames.cut_back(first);
        contacts.cut_back(contact_rows);
        probes.cut_back(first);
        views.cut_back(file.get(), first);
        view_counts.resize(first);
        H5Fflush(file.get(), H5F_SCOPE_LOCAL);
      } catch (...) {
        // The original error is the one to report.
      }
      throw OutputError(message);
    }
    for (const auto& f : batch) times.push_back(f.time_s);
    contact_rows = rows;
    write_xdmf(path, particles, views.wall_quads(), times, view_counts);
    xdmf_frames = times.size();
    xdmf_time = std::chrono::steady_clock::now();
  }

  // Stores the frames waiting in memory (they are dropped if that fails).
  void store_pending() {
    if (pending.empty()) return;
    const std::vector<PendingFrame> batch = std::move(pending);
    pending.clear();
    pending_bytes = 0;
    std::vector<FrameView> views;
    views.reserve(batch.size());
    for (const auto& p : batch) views.push_back(p.view());
    store(views);
  }

  // The views of the first `frames_kept` frames: read back where present, built from the
  // stored positions and pairs where missing (a file written before /xdmf existed).
  void rebuild_views(std::size_t frames_kept) {
    view_counts.clear();
    std::vector<double> position(3 * particles);
    std::vector<std::int64_t> pair;
    Hdf5Handle position_set = hdf5::open_dataset(file.get(), "/frames/position");
    Hdf5Handle pair_set = hdf5::open_dataset(file.get(), "/contacts/pair");
    for (std::size_t f = 0; f < frames_kept; ++f) {
      if (views.has_frame(file.get(), f)) {
        view_counts.push_back(views.counts(file.get(), f));
        continue;
      }
      const std::int64_t first = frames.contact_offset(f);
      const std::int64_t end = frames.contact_offset(f + 1);
      hdf5::read_rows(position_set.get(), f, 1, position.data(), H5T_NATIVE_DOUBLE);
      pair.resize(2 * std::size_t(end - first));
      hdf5::read_rows(pair_set.get(), hsize_t(first), hsize_t(end - first), pair.data(),
                      H5T_NATIVE_INT64);
      FrameView stored;  // positions and pairs only: rebuilt views are never linked
      stored.position_m = position;
      stored.contact_pair = pair;
      view_counts.push_back(views.add_frame(file.get(), f, stored, true, first));
    }
  }

  // Releases every HDF5 id (datasets first, then the file), whatever happened before.
  bool close_ids() noexcept {
    Hdf5ErrorSilence silence;
    frames.close();
    contacts.close();
    probes.close();
    return file.reset();
  }

  // Sets the status, closes the file and writes the XDMF; all steps are tried, the first error
  // is thrown as OutputError afterwards.
  void close_with_status(std::string_view status) {
    finished = true;
    std::string error;
    try {
      store_pending();
    } catch (const OutputError& e) {
      error = e.what();
    }
    {
      Hdf5ErrorSilence silence;
      try {
        write_result_status(file.get(), status);
        hdf5::check_ok(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
      } catch (const Hdf5Failure& e) {
        if (error.empty()) error = "cannot set status of result file '" + path + "': " + e.what();
      }
      if (!close_ids() && error.empty()) {
        error = "cannot close result file '" + path + "': " + hdf5::detail();
      }
    }
    lock.release();
    try {
      write_xdmf(path, particles, views.wall_quads(), times, view_counts);
    } catch (const OutputError& e) {
      if (error.empty()) error = e.what();
    }
    if (!error.empty()) throw OutputError(error);
  }
};

ResultWriter::ResultWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ResultWriter::ResultWriter(const std::string& path, const ResultHeader& header,
                           bool store_contacts, ExistingResult existing)
    : impl_(std::make_unique<Impl>()) {
  const std::size_t n = header.radius_m.size();
  if (header.mass_kg.size() != n || header.heat_capacity_J_per_K.size() != n ||
      header.material.size() != n) {
    throw std::invalid_argument(
        "ResultHeader: radius_m, mass_kg, heat_capacity_J_per_K and material must all have N "
        "entries");
  }
  Impl& w = *impl_;
  w.path = path;
  w.particles = n;
  const std::string cannot = "cannot create result file '" + path + "': ";
  if (const std::string problem = folder_problem(path); !problem.empty()) {
    throw OutputError(cannot + problem);
  }
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) throw OutputError(cannot + "it is a folder");
  if (existing == ExistingResult::Refuse && std::filesystem::exists(path, ignored)) {
    throw ResultMismatch(cannot + "the file exists (give --overwrite to replace it)");
  }
  w.lock = ResultFileLock(path, true);  // before anything is truncated
  try {
    Hdf5ErrorSilence silence;
    w.file = hdf5::create_file(path, kHdf5Lock);
    write_result_metadata(w.file.get(), header);
    w.frames.create(w.file.get(), n, header.walls.size(), header.frozen);
    w.contacts.create(w.file.get(), n, store_contacts,
                      header.frozen ? header.frozen_contacts : 0);
    w.views.create(w.file.get(), n, header.walls, header.periodic);
    w.probes.create(w.file.get(), header.probes);
    hdf5::check_ok(H5Fflush(w.file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
  } catch (const Hdf5Failure& e) {
    w.close_ids();
    std::filesystem::remove(path, ignored);
    throw OutputError(cannot + e.what());
  }
  w.finished = false;
}

ResultWriter ResultWriter::reopen(const std::string& path, std::size_t keep_frames,
                                  const RestartMatch* match) {
  auto impl = std::make_unique<Impl>();
  Impl& w = *impl;
  w.path = path;
  const std::string cannot = "cannot reopen result file '" + path + "': ";
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw OutputError(cannot + "no such file");
  w.lock = ResultFileLock(path, false);
  try {
    Hdf5ErrorSilence silence;
    // Everything is checked read-only first: a file that fails a check is left as it was.
    {
      Hdf5Handle file = hdf5::open_file(path, false, kHdf5Lock);
      const ResultIdentity identity = read_result_identity(file.get());
      if (identity.format != kResultFormat) {
        throw OutputError(cannot + "not a " + kResultFormat + " file");
      }
      if (match != nullptr && identity.particles != match->particles) {
        throw ResultMismatch(cannot + "it holds " + std::to_string(identity.particles) +
                          " particles, the checkpoint " + std::to_string(match->particles) +
                          " (it belongs to another scene)");
      }
      if (match != nullptr && identity.scene_toml != match->scene_toml) {
        throw ResultMismatch(cannot + "its scene differs from the checkpoint's scene (it belongs "
                          "to another run)");
      }
      ResultFrames frames;
      frames.open(file.get());
      ResultContacts contacts;
      contacts.open(file.get(), false);
      const std::size_t complete = frames.complete_frames();
      if (keep_frames > complete) {
        throw OutputError(cannot + "it holds " + std::to_string(complete) +
                          " complete frames, " + std::to_string(keep_frames) + " are needed");
      }
      const std::vector<double> times = frames.times(keep_frames);
      if (match != nullptr && !times.empty() && times.back() > match->checkpoint_time_s) {
        throw ResultMismatch(cannot + "its frame " + std::to_string(keep_frames - 1) + " at t = " +
                          std::to_string(times.back()) + " s lies after the checkpoint's time " +
                          std::to_string(match->checkpoint_time_s) + " s");
      }
      w.contact_rows = frames.contact_offset(keep_frames);
      const std::int64_t stored = contacts.rows();
      if (w.contact_rows < 0 || w.contact_rows > stored) {
        throw OutputError(cannot + "contact_offset[" + std::to_string(keep_frames) + "] = " +
                          std::to_string(w.contact_rows) + " exceeds the " +
                          std::to_string(stored) + " stored contacts");
      }
      w.particles = identity.particles;
      w.times = times;
      frames.close();
      contacts.close();
    }
    w.file = hdf5::open_file(path, true, kHdf5Lock);
    w.frames.open(w.file.get());
    w.contacts.open(w.file.get());
    w.frames.cut_back(keep_frames);
    w.contacts.cut_back(w.contact_rows);
    w.probes.open(w.file.get());
    w.probes.cut_back(keep_frames);
    // A crash while the last chunk was rewritten may have left its rows unreadable: write them
    // again from the checkpoint (a checkpoint without them leaves the chunk as it is).
    if (match != nullptr && match->contact_tail != nullptr && match->contact_tail->rows == w.contact_rows)
      w.contacts.restore(*match->contact_tail);
    w.views.open(w.file.get(), w.particles);
    w.views.cut_back(w.file.get(), keep_frames);
    w.rebuild_views(keep_frames);
    if (match != nullptr && !match->next_scene_toml.empty()) {
      write_result_scene(w.file.get(), match->next_scene_toml);
    }
    if (match != nullptr) append_result_restart(w.file.get(), match->checkpoint_time_s);
    write_result_status(w.file.get(), "running");
    hdf5::check_ok(H5Fflush(w.file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
  } catch (const Hdf5Failure& e) {
    w.close_ids();
    throw OutputError(cannot + e.what());
  } catch (const OutputError&) {
    w.close_ids();
    throw;
  }
  w.finished = false;
  return ResultWriter(std::move(impl));
}

ResultWriter::ResultWriter(ResultWriter&&) noexcept = default;
ResultWriter& ResultWriter::operator=(ResultWriter&&) noexcept = default;
ResultWriter::~ResultWriter() = default;

void ResultWriter::write_frame(const FrameView& frame) {
  if (!impl_ || impl_->finished) throw std::logic_error("ResultWriter::write_frame after finish");
  Impl& w = *impl_;
  const std::size_t n = w.particles;
  if (frame.position_m.size() != 3 * n || frame.velocity_m_per_s.size() != 3 * n ||
      frame.temperature_K.size() != n) {
    throw std::invalid_argument("FrameView: position_m and velocity_m_per_s need " +
                                std::to_string(3 * n) + " values, temperature_K " +
                                std::to_string(n));
  }
  std::size_t new_contacts = 0;
  if (w.contacts.stored()) {
    new_contacts = frame.normal_force_N.size();
    if (frame.contact_pair.size() != 2 * new_contacts ||
        frame.conductance_W_per_K.size() != new_contacts ||
        (!frame.tangential_force_N.empty() &&
         frame.tangential_force_N.size() != 3 * new_contacts)) {
      throw std::invalid_argument(
          "FrameView: contact_pair needs 2 C values, normal_force_N and conductance_W_per_K C, "
          "tangential_force_N 3 C or none");
    }
  }
  const auto& walls = w.views.walls();
  if (!frame.wall_point_m.empty() && frame.wall_point_m.size() != 3 * walls.size())
    throw std::invalid_argument("FrameView: wall_point_m needs " + std::to_string(3 * walls.size()) +
                                " values (3 per wall) or none");
  FrameView with_walls = frame;
  std::vector<double> still_walls;  // no wall positions given: the walls stand where /walls says
  if (frame.wall_point_m.empty() && !walls.empty()) {
    for (const WallPlane& wall : walls) still_walls.insert(still_walls.end(), wall.point_m.begin(), wall.point_m.end());
    with_walls.wall_point_m = still_walls;
  }
  const std::size_t total_frames = w.times.size() + w.pending.size() + 1;
  if (w.pending.empty() && w.sync_due(total_frames)) {
    w.store({with_walls});  // no copy while every frame is stored at once
    return;
  }
  w.pending.push_back(PendingFrame::copy_of(with_walls));
  w.pending_bytes += w.pending.back().bytes();
  if (w.sync_due(total_frames)) w.store_pending();
}

void ResultWriter::flush() {
  if (impl_ && !impl_->finished) impl_->store_pending();
}

void ResultWriter::finish(std::string_view status) {
  if (status != "ok" && status != "failed" && status != "interrupted") {
    throw std::invalid_argument(
        "ResultWriter::finish: status must be \"ok\", \"failed\" or \"interrupted\", not \"" +
        std::string(status) + "\"");
  }
  if (!impl_ || impl_->finished) return;
  impl_->close_with_status(status);
}

std::size_t ResultWriter::frames() const {
  return impl_ ? impl_->times.size() + impl_->pending.size() : 0;
}
std::size_t ResultWriter::stored_frames() const { return impl_ ? impl_->times.size() : 0; }

ContactTail ResultWriter::contact_tail() const {
  if (!impl_ || impl_->finished) return {};
  Hdf5ErrorSilence silence;
  try {
    return impl_->contacts.tail(impl_->contact_rows);
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot read the contacts of result file '" + impl_->path + "': " + e.what());
  }
}
std::size_t ResultWriter::particles() const { return impl_ ? impl_->particles : 0; }
bool ResultWriter::finished() const { return !impl_ || impl_->finished; }
const std::string& ResultWriter::path() const {
  static const std::string empty;
  return impl_ ? impl_->path : empty;
}
std::string ResultWriter::xdmf_path() const { return xdmf_path_for(path()); }

}  // namespace tmdem::coupling
