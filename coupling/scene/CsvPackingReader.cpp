#include "coupling/scene/CsvPackingReader.h"

#include <optional>

#include "coupling/scene/PackingColumns.h"

namespace tmdem::coupling {

Packing read_csv_packing(std::string_view text, const std::string& file,
                         const std::string& temperature_column, bool z_required) {
  const auto lines = split_lines(text);
  std::optional<PackingColumns> columns;
  Packing packing;
  std::vector<long long> ids;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const std::string_view line = lines[k];
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;
    const long long number = static_cast<long long>(k) + 1;
    const auto fields = split_fields(line, ',');
    if (!columns) {
      columns.emplace(fields, temperature_column, z_required, file, number);
      continue;
    }
    packing.rows.push_back(columns->read_row(fields, number));
    if (columns->has_id()) ids.push_back(columns->id_of(fields, number));
    if (columns->has_id()) packing.rows.back().id = ids.back();
  }
  if (!columns) throw PackingFileError(file, 0, 0, "no header line (the file is empty)");
  if (packing.rows.empty()) throw PackingFileError(file, 0, 0, "no particle after the header");
  columns->sort_by_id(packing.rows, ids);
  packing.ignored_columns = columns->ignored();
  return packing;
}

}  // namespace tmdem::coupling
