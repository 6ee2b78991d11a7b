// libFuzzer target: particle files -> the [[import]] readers (CSV, LAMMPS/LIGGGHTS text dump,
// and with bit 8 of the first byte the local dump of contacts: LocalDumpReader.h).
// The first byte picks the reader and its options, the rest is the file's text. Any input must
// either be read or be refused with a PackingFileError (a message naming file, line and
// column); another exception escapes and libFuzzer reports it as a crash, as it does a
// sanitizer report or a hang (-timeout). A file that is read gives finite positions and
// radii > 0 (a local dump: finite forces, normal forces >= 0): the readers promise that much,
// the scene's own checks come after.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

#include "coupling/scene/CsvPackingReader.h"
#include "coupling/scene/LammpsDumpReader.h"
#include "coupling/scene/LocalDumpReader.h"
#include "coupling/scene/PackingFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t choice = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const bool dump = (choice & 1) != 0;
  const bool z_required = (choice & 2) != 0;
  const std::string temperature = (choice & 4) != 0 ? (dump ? "f_Temp[0]" : "temperature") : "";
  if ((choice & 8) != 0) {  // a local dump: bit 1 the LIGGGHTS names, bit 2 timestep 2000
    tmdem::coupling::LocalDumpColumns columns;
    if ((choice & 1) != 0) columns = {"c_pc[7]", "c_pc[8]", {"c_pc[10]", "c_pc[11]", "c_pc[12]"}};
    try {
      const auto forces = tmdem::coupling::read_local_dump(
          text, "fuzz.dump", columns, (choice & 4) != 0 ? std::optional<long long>(2000) : std::nullopt,
          "fuzz_particles.dump");
      for (const auto& row : forces.rows) {
        for (const double f : row.force)
          if (!std::isfinite(f)) std::abort();
        if (!forces.vector && !(row.force[0] >= 0.0)) std::abort();
        if (row.id1 == row.id2) std::abort();
      }
    } catch (const tmdem::coupling::PackingFileError&) {
    }
    return 0;
  }
  try {
    const tmdem::coupling::Packing packing =
        dump ? tmdem::coupling::read_lammps_dump(text, "fuzz.dump", temperature, z_required)
             : tmdem::coupling::read_csv_packing(text, "fuzz.csv", temperature, z_required);
    for (const auto& row : packing.rows) {
      for (const double x : row.position)
        if (!std::isfinite(x)) std::abort();  // a reader let a non-finite position through
      if (!(row.radius > 0.0) || !std::isfinite(row.radius)) std::abort();
    }
  } catch (const tmdem::coupling::PackingFileError&) {
    // A refused file is the expected outcome for most inputs.
  }
  return 0;
}
