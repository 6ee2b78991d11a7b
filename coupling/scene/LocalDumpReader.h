#pragma once
// Pair contacts with their forces from a LAMMPS / LIGGGHTS *local* dump ([[import]] contacts):
//   ITEM: TIMESTEP / step / ITEM: NUMBER OF ENTRIES / n / ITEM: BOX BOUNDS ... / 3 lines /
//   ITEM: ENTRIES c_pc[1] c_pc[2] ... / n lines
// as `dump local` writes it for `compute pair/gran/local` (LIGGGHTS) or `compute pair/local`
// (LAMMPS). Columns by name (LocalDumpColumns); values in the file's force unit (N for SI runs).
// The particle ids are the particle dump's `id` column; ParticleImport.cpp maps them to scene
// particles and turns a force vector into its normal part.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// Which columns hold what. force: one name (the normal force, >= 0) or three (the force
// vector x, y, z acting between the two particles; its normal part is taken).
struct LocalDumpColumns {
  std::string id1 = "id1";
  std::string id2 = "id2";
  std::vector<std::string> force;  // empty: "fn" if the header has it, else "fx", "fy", "fz"
};

struct PairForceRow {
  long long id1 = 0, id2 = 0;  // the particle dump's ids
  Vec3 force{};                // [0]: the normal force when `vector` is false
  long long line = 0;          // 1-based line in the file
};

struct PairForces {
  std::vector<PairForceRow> rows;
  bool vector = false;      // rows hold force vectors (else normal forces)
  long long timestep = 0;   // of the snapshot read
  long long first_line = 0; // its "ITEM: TIMESTEP" line
};

// The snapshot of `timestep` when given (a particle dump's), else the last one. A missing
// timestep is a PackingFileError naming both files and the timesteps.
PairForces read_local_dump(std::string_view text, const std::string& file,
                           const LocalDumpColumns& columns, std::optional<long long> timestep,
                           const std::string& particle_file);

}  // namespace tmdem::coupling
