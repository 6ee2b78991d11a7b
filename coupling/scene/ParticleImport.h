#pragma once
// [[import]]: particles from a file (reference: docs/scene.md, section import). The readers:
// CsvPackingReader.h, LammpsDumpReader.h, ResultPackingReader.h; the columns: PackingColumns.h.
// SceneBuilder::read_imports (ParticleImport.cpp) turns their rows into scene particles:
// lengths x length_scale + offset, the material from the table, else the file's material name,
// else its LAMMPS type through type_materials. A problem in the file is a SceneError located at
// the [[import]] key and naming FILE:LINE:COLUMN of the file, e.g.
//   bed.toml:31:8: import[0].file: packing.csv:12:17: column radius: expected a finite number,
//   got "0.0o1"
#include <string>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// One line: "import[0]: 80 particles (ids 0-79) from bed.csv (csv); largest overlap 2.1e-3 of
// the smaller radius (particles 3 and 17, 1.05e-6 m), accepted up to 0.01"
std::string describe_import(const ImportReport& report);

}  // namespace tmdem::coupling
