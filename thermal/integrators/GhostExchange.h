#pragma once
// Fills the ghost entries of a LocalNetwork-ordered array (owned values first, then the ghosts)
// with their owners' values, over MPI_COMM_WORLD: one message each way per neighbouring process,
// received straight into the ghost slots (each neighbour's ghosts are contiguous). Buffers and
// requests are sized once, so an exchange (each right-hand side and Jacobian product) allocates
// nothing. Collective: every process calls it the same number of times.
#include <memory>
#include <span>
#include <vector>

#include "thermal/network/LocalNetwork.h"

namespace tmdem::thermal {

class GhostExchange {
 public:
  explicit GhostExchange(const LocalNetwork& local);
  ~GhostExchange();
  GhostExchange(const GhostExchange&) = delete;
  GhostExchange& operator=(const GhostExchange&) = delete;
  // values: one per local node; the owned entries are read, the ghost entries overwritten.
  void exchange(std::span<double> values);

 private:
  std::vector<GhostNeighbour> neighbours_;
  std::vector<std::vector<double>> send_buffers_;  // one per neighbour
  struct Requests;  // 2 MPI_Requests per neighbour (defined where mpi.h is included)
  std::unique_ptr<Requests> requests_;
};

}  // namespace tmdem::thermal
