#include "coupling/scene/PackingColumns.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace tmdem::coupling {

PackingColumns::PackingColumns(const std::vector<TextField>& header,
                               const std::string& temperature_column, bool z_required,
                               const std::string& file, long long line)
    : file_(file), count_(header.size()) {
  const std::vector<std::pair<std::string, int*>> known{
      {"x", &x_},         {"xu", &x_},           {"y", &y_},
      {"yu", &y_},        {"z", &z_},            {"zu", &z_},
      {"radius", &radius_}, {"diameter", &diameter_}, {"material", &material_},
      {"type", &type_},   {"id", &id_},          {temperature_column, &temperature_},
      {"fixed", &fixed_}, {"fixed_temperature", &fixed_temperature_},
      {"heat_source", &heat_source_}};
  for (std::size_t k = 0; k < header.size(); ++k) {
    const std::string name(header[k].text);
    if (name.empty())
      throw PackingFileError(file, line, header[k].column, "empty column name in the header");
    for (std::size_t m = 0; m < k; ++m)
      if (names_[m] == name)
        throw PackingFileError(file, line, header[k].column,
                               "column " + name + " appears twice in the header");
    names_.push_back(name);
    if (name == "xs" || name == "ys" || name == "zs")
      throw PackingFileError(file, line, header[k].column,
                             "scaled coordinates (" + name +
                                 ") are not read; dump x y z or xu yu zu instead");
    const auto it = std::find_if(known.begin(), known.end(),
                                 [&](const auto& entry) { return entry.first == name; });
    if (it == known.end()) {
      ignored_.push_back(name);
      continue;
    }
    if (*it->second >= 0)  // x and xu both given
      throw PackingFileError(file, line, header[k].column,
                             "column " + name + " repeats the column " +
                                 names_[std::size_t(*it->second)]);
    *it->second = static_cast<int>(k);
  }
  if (radius_ >= 0 && diameter_ >= 0)
    throw PackingFileError(file, line, 0, "give radius or diameter, not both");
  std::string missing;
  for (const auto& [name, index] : {std::pair<const char*, int>{"x", x_}, {"y", y_},
                                    {"z", z_required ? z_ : 0},
                                    {"radius (or diameter)", std::max(radius_, diameter_)}})
    if (index < 0) missing += (missing.empty() ? "" : ", ") + std::string(name);
  if (!missing.empty())
    throw PackingFileError(file, line, 0,
                           "the header has no column " + missing + " (columns: x, y, z, radius; "
                           "optional: material, type, id, " + temperature_column +
                           ", fixed, fixed_temperature, heat_source)");
}

long long PackingColumns::id_of(const std::vector<TextField>& fields, long long line) const {
  return FieldReader(file_, line).integer(fields[std::size_t(id_)], "id");
}

PackingRow PackingColumns::read_row(const std::vector<TextField>& fields, long long line) const {
  if (fields.size() != count_)
    throw PackingFileError(file_, line, 0,
                           "expected " + std::to_string(count_) + " values (one per column), got " +
                               std::to_string(fields.size()));
  const FieldReader read(file_, line);
  const auto field = [&](int index) -> const TextField& { return fields[std::size_t(index)]; };
  const auto name = [&](int index) -> const std::string& { return names_[std::size_t(index)]; };
  PackingRow row;
  row.line = line;
  row.position[0] = read.number(field(x_), name(x_));
  row.position[1] = read.number(field(y_), name(y_));
  if (z_ >= 0) row.position[2] = read.number(field(z_), name(z_));
  const int size = radius_ >= 0 ? radius_ : diameter_;
  row.radius = read.number(field(size), name(size)) * (radius_ >= 0 ? 1.0 : 0.5);
  if (!(row.radius > 0.0))
    throw PackingFileError(file_, line, field(size).column,
                           "column " + name(size) + ": must be > 0, got " +
                               std::string(field(size).text));
  if (material_ >= 0) {
    if (field(material_).text.empty())
      throw PackingFileError(file_, line, field(material_).column,
                             "column material: empty material name");
    row.material = std::string(field(material_).text);
  }
  if (type_ >= 0) row.type = read.integer(field(type_), "type");
  if (temperature_ >= 0) {
    row.temperature_K = read.number(field(temperature_), name(temperature_));
    if (!(*row.temperature_K > 0.0))
      throw PackingFileError(file_, line, field(temperature_).column,
                             "column " + name(temperature_) + ": a temperature must be > 0 K, got " +
                                 std::string(field(temperature_).text));
  }
  if (fixed_ >= 0) row.fixed = read.boolean(field(fixed_), "fixed");
  if (fixed_temperature_ >= 0)
    row.fixed_temperature = read.boolean(field(fixed_temperature_), "fixed_temperature");
  if (heat_source_ >= 0) row.heat_source_W = read.number(field(heat_source_), "heat_source");
  return row;
}

void PackingColumns::sort_by_id(std::vector<PackingRow>& rows, std::vector<long long>& ids) const {
  if (id_ < 0) return;
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  std::vector<PackingRow> sorted;
  sorted.reserve(rows.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && ids[order[k]] == ids[order[k - 1]])
      throw PackingFileError(file_, rows[order[k]].line, 0,
                             "id " + std::to_string(ids[order[k]]) + " also on line " +
                                 std::to_string(rows[order[k - 1]].line));
    sorted.push_back(std::move(rows[order[k]]));
  }
  rows = std::move(sorted);
}

}  // namespace tmdem::coupling
