#include "coupling/scene/LammpsDumpReader.h"

#include "coupling/scene/PackingColumns.h"

namespace tmdem::coupling {

namespace {

bool starts_with(std::string_view line, std::string_view prefix) {
  return line.substr(0, prefix.size()) == prefix;
}

}  // namespace

bool looks_like_lammps_dump(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && starts_with(text.substr(first), "ITEM:");
}

Packing read_lammps_dump(std::string_view text, const std::string& file,
                         const std::string& temperature_column, bool z_required) {
  const auto lines = split_lines(text);
  // The last snapshot: from the last "ITEM: TIMESTEP" (a dump may hold many).
  std::size_t start = lines.size();
  for (std::size_t k = lines.size(); k-- > 0;)
    if (starts_with(lines[k], "ITEM: TIMESTEP")) {
      start = k;
      break;
    }
  if (start == lines.size())
    throw PackingFileError(file, 0, 0, "no \"ITEM: TIMESTEP\" line: not a LAMMPS text dump");
  long long atoms = -1;
  std::size_t header = lines.size();
  for (std::size_t k = start; k < lines.size(); ++k) {
    const long long number = static_cast<long long>(k) + 1;
    if (starts_with(lines[k], "ITEM: NUMBER OF ATOMS")) {
      if (k + 1 >= lines.size())
        throw PackingFileError(file, number, 0, "the atom count is missing after this line");
      const auto fields = split_fields(lines[k + 1], ' ');
      if (fields.size() != 1)
        throw PackingFileError(file, number + 1, 0, "expected the number of atoms");
      atoms = FieldReader(file, number + 1).integer(fields[0], "NUMBER OF ATOMS");
      if (atoms < 1)
        throw PackingFileError(file, number + 1, fields[0].column, "the snapshot has no atoms");
    } else if (starts_with(lines[k], "ITEM: ATOMS")) {
      header = k;
      break;
    }
  }
  const long long header_line = static_cast<long long>(header) + 1;
  if (header == lines.size())
    throw PackingFileError(file, static_cast<long long>(start) + 1, 0,
                           "the last snapshot has no \"ITEM: ATOMS\" line");
  if (atoms < 0)
    throw PackingFileError(file, header_line, 0,
                           "no \"ITEM: NUMBER OF ATOMS\" before the atoms of the last snapshot");
  const std::string_view names_text = lines[header].substr(std::string_view("ITEM: ATOMS").size());
  auto names = split_fields(names_text, ' ');
  const long long shift = static_cast<long long>(std::string_view("ITEM: ATOMS").size());
  for (auto& name : names) name.column += shift;
  const PackingColumns columns(names, temperature_column, z_required, file, header_line);

  Packing packing;
  std::vector<long long> ids;
  for (long long a = 0; a < atoms; ++a) {
    const std::size_t k = header + 1 + static_cast<std::size_t>(a);
    if (k >= lines.size() || starts_with(lines[k], "ITEM:"))
      throw PackingFileError(file, static_cast<long long>(k) + 1, 0,
                             "the last snapshot ends after " + std::to_string(a) + " of " +
                                 std::to_string(atoms) + " atoms (NUMBER OF ATOMS)");
    const auto fields = split_fields(lines[k], ' ');
    const long long number = static_cast<long long>(k) + 1;
    packing.rows.push_back(columns.read_row(fields, number));
    if (columns.has_id()) ids.push_back(columns.id_of(fields, number));
    if (columns.has_id()) packing.rows.back().id = ids.back();
  }
  columns.sort_by_id(packing.rows, ids);
  packing.ignored_columns = columns.ignored();
  if (start + 1 < lines.size()) {
    const auto fields = split_fields(lines[start + 1], ' ');
    if (fields.size() == 1)
      packing.timestep = FieldReader(file, static_cast<long long>(start) + 2).integer(fields[0], "TIMESTEP");
  }
  packing.description = "last snapshot (line " + std::to_string(start + 1) + ")";
  return packing;
}

}  // namespace tmdem::coupling
