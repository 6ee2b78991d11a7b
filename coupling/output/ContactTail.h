#pragma once
// The rows of the result file's growing /contacts datasets in their last chunk, as they were
// when a checkpoint was written. Frames appended after it rewrite that chunk (compressed, it
// moves), and a crash in the middle of such a rewrite can leave those rows unreadable; the
// checkpoint carries them so that a restart writes them again (docs/restart-and-files.md).
#include <cstdint>
#include <vector>

namespace tmdem::coupling {

struct ContactTail {
  std::int64_t start = -1;  // first row held here; -1: none (a checkpoint without it)
  std::int64_t rows = 0;    // the contact rows the file held; the tail is [start, rows)
  // (rows - start) rows each; a dataset stored as a block series (frozen contacts) is empty
  // here: its blocks are written once, never rewritten.
  std::vector<std::int64_t> pair;        // x2
  std::vector<double> normal_force_N;
  std::vector<double> tangential_force_N;  // x3
  std::vector<double> conductance_W_per_K;
  std::vector<double> heat_flow_W;
  bool empty() const { return start < 0; }
};

}  // namespace tmdem::coupling
