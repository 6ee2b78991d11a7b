#include "thermal/integrators/MpiWorld.h"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <string>

namespace tmdem::thermal {
namespace {

// The process count the launcher announced, 0 when not launched by one.
int launched_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return 0;
}

// MPI_Finalize at exit, after hypre's own finaliser (constructed later, so destroyed first).
struct Finalizer {
  ~Finalizer() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
  }
};

int g_rank = 0, g_size = 1;

}  // namespace

std::string MpiWorld::start_if_launched(int* argc, char*** argv) {
  const int launched = launched_size();
  if (launched <= 1) return "";
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    if (MPI_Init(argc, argv) != MPI_SUCCESS) return "MPI_Init failed";
    static Finalizer finalizer;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  if (g_size != launched)
    return "started as one of " + std::to_string(launched) + " processes, but MPI sees " +
           std::to_string(g_size) + ": launch tmdem with the mpirun of the MPI it links "
           "(Debian: OpenMPI, package openmpi-bin)";
  return "";
}

int MpiWorld::rank() { return g_rank; }
int MpiWorld::size() { return g_size; }

double MpiWorld::sum(double value) {
  if (g_size == 1) return value;
  double total = 0.0;
  MPI_Allreduce(&value, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return total;
}

bool MpiWorld::all(bool value) {
  if (g_size == 1) return value;
  int mine = value ? 1 : 0, every = 0;
  MPI_Allreduce(&mine, &every, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return every != 0;
}

int MpiWorld::from_root(int value) {
  if (g_size > 1) MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

bool MpiWorld::same_everywhere(double value) {
  if (g_size == 1) return true;
  double low = 0.0, high = 0.0;
  MPI_Allreduce(&value, &low, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&value, &high, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return low == high;
}

void MpiWorld::all_gather(std::span<const double> mine, std::span<double> all,
                          std::span<const int> counts, std::span<const int> displacements) {
  if (g_size == 1) {
    std::copy(mine.begin(), mine.end(), all.begin());
    return;
  }
  MPI_Allgatherv(mine.data(), int(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
                 displacements.data(), MPI_DOUBLE, MPI_COMM_WORLD);
}

void MpiWorld::abort(int code) {
  if (g_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace tmdem::thermal
