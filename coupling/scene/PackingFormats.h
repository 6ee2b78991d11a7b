#pragma once
// The particle-file formats of [[import]] (format = "..."), one table in PackingFormats.cpp, as
// the contact solvers (mechanics/solvers/ContactSolverRegistry.cpp) and the heat-transfer modes
// are: each format's name, the file endings and the first line by which format = "auto" knows
// it, and its reader (CsvPackingReader.h, LammpsDumpReader.h, ResultPackingReader.h). The
// scene schema's choices and the messages take the names from the table; a new format is one
// row.
#include <string>
#include <string_view>
#include <vector>

#include "coupling/scene/PackingFile.h"

namespace tmdem::coupling {

class SceneTable;

// What every reader is given: the [[import]] table (a format's own keys, e.g. "tmdem"'s frame,
// are read by its reader), the file, and the file's text when the format is a text format.
struct PackingRequest {
  const SceneTable& table;
  std::string path;
  std::string temperature_column;  // the column holding the temperature in K
  bool z_required = true;          // a 3D scene: the file must have z
};

struct PackingFormat {
  std::string_view name;
  std::vector<std::string_view> endings{};  // format = "auto" takes it for a file ending so
  // format = "auto" takes it for a file with none of the formats' endings whose text this
  // recognises (nullptr: never); `recognised_by` says how, for the message when none does.
  bool (*recognises)(std::string_view text) = nullptr;
  std::string_view recognised_by{};
  bool reads_text = true;  // false: the reader opens the file itself (an HDF5 result)
  Packing (*read)(const PackingRequest& request, std::string_view text) = nullptr;
};

// Every format, in the order of the reference (docs/scene.md).
const std::vector<PackingFormat>& packing_formats();

// The format named `name`; nullptr for "auto" or an unknown name (the schema refuses those).
const PackingFormat* find_packing_format(std::string_view name);

// format = "auto": the format whose endings `path` has, else nullptr.
const PackingFormat* packing_format_by_ending(const std::string& path);
// format = "auto" for a file without a known ending: the format that recognises its text, else
// nullptr.
const PackingFormat* packing_format_by_text(std::string_view text);

// The schema's choices of [[import]] format: "auto", then every format's name.
std::vector<std::string> packing_format_choices();

// "(not .csv, .CSV, .h5 or .hdf5, and no \"ITEM:\" first line); give format = \"csv\",
// \"lammps\" or \"tmdem\"": why "auto" found no format, and what to write instead.
std::string unknown_packing_format_hint();

}  // namespace tmdem::coupling
