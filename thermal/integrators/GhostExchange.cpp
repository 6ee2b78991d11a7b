#include "thermal/integrators/GhostExchange.h"

#include <mpi.h>

#include <string>

#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {

struct GhostExchange::Requests {
  std::vector<MPI_Request> all;
};

GhostExchange::GhostExchange(const LocalNetwork& local)
    : neighbours_(local.neighbours), requests_(std::make_unique<Requests>()) {
  for (const auto& n : neighbours_) send_buffers_.emplace_back(n.send.size(), 0.0);
  requests_->all.resize(2 * neighbours_.size());
}

GhostExchange::~GhostExchange() = default;

void GhostExchange::exchange(std::span<double> values) {
  if (neighbours_.empty()) return;
  MPI_Request* requests = requests_->all.data();
  constexpr int kTag = 2501;  // ghost temperatures (issue 25 item 5)
  int count = 0;
  for (std::size_t k = 0; k < neighbours_.size(); ++k) {
    const auto& n = neighbours_[k];
    MPI_Irecv(values.data() + n.ghost_begin, n.ghost_end - n.ghost_begin, MPI_DOUBLE, n.rank,
              kTag, MPI_COMM_WORLD, &requests[count++]);
  }
  for (std::size_t k = 0; k < neighbours_.size(); ++k) {
    const auto& n = neighbours_[k];
    auto& buffer = send_buffers_[k];
    for (std::size_t s = 0; s < n.send.size(); ++s) buffer[s] = values[std::size_t(n.send[s])];
    MPI_Isend(buffer.data(), int(buffer.size()), MPI_DOUBLE, n.rank, kTag, MPI_COMM_WORLD,
              &requests[count++]);
  }
  if (MPI_Waitall(count, requests, MPI_STATUSES_IGNORE) != MPI_SUCCESS)
    throw ThermalSolverError("ghost exchange: MPI_Waitall failed with " +
                             std::to_string(neighbours_.size()) + " neighbouring processes");
}

}  // namespace tmdem::thermal
