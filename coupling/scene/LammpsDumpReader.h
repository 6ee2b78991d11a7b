#pragma once
// Particles from the last snapshot of a LAMMPS / LIGGGHTS text dump (dump style custom or
// atom):
//   ITEM: TIMESTEP / step / ITEM: NUMBER OF ATOMS / n / ITEM: BOX BOUNDS ... / 3 lines /
//   ITEM: ATOMS id type x y z radius ... / n lines
// Columns by name as in PackingColumns.h (x or xu; radius or diameter; type is mapped to a
// material by [[import]] type_materials). The box is not read.
#include <string>
#include <string_view>

#include "coupling/scene/PackingFile.h"

namespace tmdem::coupling {

Packing read_lammps_dump(std::string_view text, const std::string& file,
                         const std::string& temperature_column, bool z_required);

// True if the text looks like a dump (its first non-blank line starts with "ITEM:").
bool looks_like_lammps_dump(std::string_view text);

}  // namespace tmdem::coupling
