#pragma once
// The /probes group of a result file (scenes with [[probe]] only): per frame and probe the count
// of particles whose centre lies inside the probe and their mean, min and max temperature.
//   /probes/names [P] strings, point [P,3] m, radius [P] m (0: a box), box [P,3] m (full edge
//   lengths; 0 for a sphere): what each probe is, written once
//   /probes/count [F,P] int64 ("1"), mean_K, min_K, max_K [F,P] K: one row per frame
// A probe holding no particle stores count 0 and mean = min = max = 0 K: results hold no NaN,
// and 0 K is no temperature a particle can have, so the count tells (docs/result-file.md).
// The rows are a function of the frame's positions and temperatures alone, so the writer
// computes them as it stores the frame (before /frames/time, which commits it) and a restart
// that cuts the frames back and writes them again writes the same rows.
#include <hdf5.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "coupling/output/Hdf5Handle.h"
#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

// One frame's readings, one entry per probe.
struct ProbeReadings {
  std::vector<std::int64_t> count;
  std::vector<double> mean_K, min_K, max_K;  // 0 where count is 0
};

// True when the centre x lies inside the probe (its boundary included).
bool probe_contains(const ProbeRegion& probe, const double* x);

// The readings of `probes` over particles at `position_m` (N*3) with `temperature_K` (N).
ProbeReadings read_probes_of_frame(const std::vector<ProbeRegion>& probes,
                                   std::span<const double> position_m,
                                   std::span<const double> temperature_K);

class ResultProbes {
 public:
  // Writes the probes' description and empty [0, P] datasets; nothing without probes.
  void create(hid_t file, const std::vector<ProbeRegion>& probes);
  // The probes of an existing file (none when it has no /probes).
  void open(hid_t file);
  bool active() const { return !probes_.empty(); }

  void append(std::size_t index, const FrameView& frame);
  void cut_back(std::size_t frames);
  void close();

 private:
  std::vector<ProbeRegion> probes_;
  Hdf5Handle count_, mean_, min_, max_;
};

// Every complete frame's readings of a result file, for `tmdem probes` and the Python module.
struct ProbeSeries {
  std::vector<std::string> names;         // P
  std::vector<double> time_s;             // F
  std::vector<std::int64_t> count;        // F*P, row-major by frame
  std::vector<double> mean_K, min_K, max_K;
};

// Throws OutputError naming the file when it cannot be read; `has_probes` false (and nothing
// read) when the file has no /probes.
ProbeSeries read_probe_series(const std::string& path, bool& has_probes);

}  // namespace tmdem::coupling
