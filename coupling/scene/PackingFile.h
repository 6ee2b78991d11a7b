#pragma once
// A packing read from a particle file, before it becomes scene particles ([[import]],
// coupling/scene/ParticleImport.cpp). The readers (CSV, LAMMPS/LIGGGHTS text dump, tmdem
// result) fill one row per particle with what the file holds; what it does not hold stays unset
// and comes from the [[import]] table or the defaults. Lengths are in the file's units (the
// import multiplies by its length_scale), temperatures in K.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

struct PackingRow {
  Vec3 position{};
  double radius = 0.0;
  std::optional<std::string> material;  // a material name (CSV column, tmdem result)
  std::optional<long long> type;        // a LAMMPS atom type (mapped by type_materials)
  std::optional<double> temperature_K;
  std::optional<bool> fixed;
  std::optional<bool> fixed_temperature;
  std::optional<double> heat_source_W;
  std::optional<long long> id;          // the file's id column (a dump's atom id)
  long long line = 0;  // 1-based line of the file (0: not a text file)
};

struct Packing {
  std::vector<PackingRow> rows;
  std::vector<std::string> ignored_columns;  // columns the file has and the import does not read
  std::string description;                   // e.g. "frame 20 of 21 (t = 1 s)", "" if nothing to say
  std::optional<long long> timestep;         // a LAMMPS dump's: the snapshot's ITEM: TIMESTEP
};

// A problem in a particle file, located "FILE:LINE:COLUMN" (column 1-based, in characters; 0
// when the problem is about the whole line, line 0 when it is about the whole file).
class PackingFileError : public std::runtime_error {
 public:
  PackingFileError(const std::string& file, long long line, long long column,
                   const std::string& problem)
      : std::runtime_error(located(file, line, column) + ": " + problem) {}

 private:
  static std::string located(const std::string& file, long long line, long long column) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string out = file;
    if (line > 0) {
      out += ':';
      out += std::to_string(line);
    }
    if (line > 0 && column > 0) {
      out += ':';
      out += std::to_string(column);
    }
    return out;
  }
};

// The whole of a regular file as text; PackingFileError if it cannot be read or is not a
// regular file (a device or a pipe would never end).
std::string read_packing_text(const std::string& path);

}  // namespace tmdem::coupling
