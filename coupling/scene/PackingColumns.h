#pragma once
// The columns of a text particle file (CSV header, or the "ITEM: ATOMS ..." line of a LAMMPS /
// LIGGGHTS dump), found by name:
//   x y z (or xu yu zu)   centre, file length unit; z may be left out in 2D (z = 0)
//   radius (or diameter)  file length unit
//   material              a [[material]] name        type   LAMMPS atom type (type_materials)
//   temperature           K; another name with [[import]] temperature_column
//   fixed, fixed_temperature   0/1/true/false          heat_source   W
//   id                    rows are sorted by id when present (dumps are written unordered)
// Any other column is ignored and listed (Packing::ignored_columns).
#include <string>
#include <vector>

#include "coupling/scene/PackingFile.h"
#include "coupling/scene/PackingText.h"

namespace tmdem::coupling {

class PackingColumns {
 public:
  // header: the column names with their positions, at `line` of `file`. PackingFileError for a
  // repeated name, scaled coordinates (xs), or a missing x, y, (z when z_required), radius.
  PackingColumns(const std::vector<TextField>& header, const std::string& temperature_column,
                 bool z_required, const std::string& file, long long line);

  // One data line (its fields already split); checks the field count and every value.
  PackingRow read_row(const std::vector<TextField>& fields, long long line) const;

  // Sorts rows by their id column when there is one; duplicate ids are an error.
  void sort_by_id(std::vector<PackingRow>& rows, std::vector<long long>& ids) const;

  bool has_id() const { return id_ >= 0; }
  const std::vector<std::string>& ignored() const { return ignored_; }
  std::size_t count() const { return count_; }
  long long id_of(const std::vector<TextField>& fields, long long line) const;

 private:
  std::string file_;
  std::size_t count_ = 0;
  int x_ = -1, y_ = -1, z_ = -1, radius_ = -1, diameter_ = -1, material_ = -1, type_ = -1,
      id_ = -1, temperature_ = -1, fixed_ = -1, fixed_temperature_ = -1, heat_source_ = -1;
  std::vector<std::string> names_;
  std::vector<std::string> ignored_;
};

}  // namespace tmdem::coupling
