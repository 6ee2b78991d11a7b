#pragma once
// This process's place in MPI_COMM_WORLD, for the heating over MPI (docs/scale-out.md). MPI is
// started only when the program was launched by mpirun with more than one process: a serial
// run never initialises MPI here (hypre's BoomerAMG still does, in singleton mode, when it is
// used: BoomerAmgPreconditioner.h). No MPI types in this header, so the coupling rooms need no
// MPI headers.
#include <cstdint>
#include <span>
#include <string>

namespace tmdem::thermal {

class MpiWorld {
 public:
  // Call first thing in main: MPI_Init when mpirun (OpenMPI: OMPI_COMM_WORLD_SIZE; MPICH and
  // others: PMI_SIZE) started more than one process, else nothing. MPI_Finalize runs at exit.
  // Returns why the processes cannot work together (empty: they can), e.g. a launcher of
  // another MPI than the one tmdem links (OpenMPI on Debian), whose processes each see a world
  // of one and would each run the whole scene.
  static std::string start_if_launched(int* argc, char*** argv);
  // 0 and 1 unless start_if_launched started MPI.
  static int rank();
  static int size();
  static bool distributed() { return size() > 1; }

  // Collective over MPI_COMM_WORLD (identity with one process).
  static double sum(double value);
  static bool all(bool value);
  // Rank 0's value, on every process.
  static int from_root(int value);
  // True when every process passed the same value.
  static bool same_everywhere(double value);
  // Every process's `mine` in rank order, into `all` (sized to the total; counts per rank).
  static void all_gather(std::span<const double> mine, std::span<double> all,
                         std::span<const int> counts, std::span<const int> displacements);
  // Ends every process at once (MPI_Abort) with `code`: for a failure one process sees alone,
  // which would leave the others waiting in a collective call forever.
  [[noreturn]] static void abort(int code);
};

}  // namespace tmdem::thermal
