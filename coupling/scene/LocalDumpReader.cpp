#include "coupling/scene/LocalDumpReader.h"

#include <cmath>

#include <algorithm>

#include "coupling/scene/PackingFile.h"
#include "coupling/scene/PackingText.h"

namespace tmdem::coupling {

namespace {

bool local_starts_with(std::string_view line, std::string_view prefix) {
  return line.substr(0, prefix.size()) == prefix;
}

// The line after `k` as one integer (the value of an ITEM line).
long long local_item_value(const std::vector<std::string_view>& lines, std::size_t k,
                     const std::string& file, std::string_view what) {
  const long long number = static_cast<long long>(k) + 1;
  if (k + 1 >= lines.size())
    throw PackingFileError(file, number, 0, "the " + std::string(what) + " is missing after this line");
  const auto fields = split_fields(lines[k + 1], ' ');
  if (fields.size() != 1)
    throw PackingFileError(file, number + 1, 0, "expected the " + std::string(what));
  return FieldReader(file, number + 1).integer(fields[0], what);
}

std::string local_list_of(const std::vector<long long>& steps) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(steps.size(), 5);
  for (std::size_t k = 0; k < shown; ++k) {
    if (k > 0) out += ", ";
    out += std::to_string(steps[k]);
  }
  if (steps.size() > shown) out += ", ... " + std::to_string(steps.back());
  return out;
}

// Index of the named column in the header, or -1.
int local_find_column(const std::vector<TextField>& header, std::string_view name) {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k].text == name) return static_cast<int>(k);
  return -1;
}

}  // namespace

PairForces read_local_dump(std::string_view text, const std::string& file,
                           const LocalDumpColumns& wanted, std::optional<long long> timestep,
                           const std::string& particle_file) {
  const auto lines = split_lines(text);
  std::vector<std::size_t> starts;
  std::vector<long long> steps;
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (local_starts_with(lines[k], "ITEM: TIMESTEP")) {
      starts.push_back(k);
      steps.push_back(local_item_value(lines, k, file, "TIMESTEP"));
    }
  if (starts.empty())
    throw PackingFileError(file, 0, 0, "no \"ITEM: TIMESTEP\" line: not a LAMMPS local dump");
  std::size_t block = starts.size() - 1;
  if (timestep) {
    const auto it = std::find(steps.rbegin(), steps.rend(), *timestep);
    if (it == steps.rend())
      throw PackingFileError(file, 0, 0,
                             "no snapshot of timestep " + std::to_string(*timestep) + " (the one of " +
                                 particle_file + "); its timesteps: " + local_list_of(steps));
    block = static_cast<std::size_t>(steps.rend() - it) - 1;
  }
  const std::size_t start = starts[block];
  const std::size_t end = block + 1 < starts.size() ? starts[block + 1] : lines.size();

  long long entries = -1;
  std::size_t header = end;
  for (std::size_t k = start; k < end; ++k) {
    if (local_starts_with(lines[k], "ITEM: NUMBER OF ENTRIES")) {
      entries = local_item_value(lines, k, file, "NUMBER OF ENTRIES");
      if (entries < 0)
        throw PackingFileError(file, static_cast<long long>(k) + 2, 0, "a negative number of entries");
    } else if (local_starts_with(lines[k], "ITEM: ENTRIES")) {
      header = k;
      break;
    } else if (local_starts_with(lines[k], "ITEM: ATOMS")) {
      throw PackingFileError(file, static_cast<long long>(k) + 1, 0,
                             "a particle dump (ITEM: ATOMS), not a local dump (ITEM: ENTRIES): "
                             "contacts names the file of `dump local`");
    }
  }
  if (header == end)
    throw PackingFileError(file, static_cast<long long>(start) + 1, 0,
                           "the snapshot has no \"ITEM: ENTRIES\" line");
  const long long header_line = static_cast<long long>(header) + 1;
  if (entries < 0)
    throw PackingFileError(file, header_line, 0, "no \"ITEM: NUMBER OF ENTRIES\" before the entries");
  auto names = split_fields(lines[header].substr(std::string_view("ITEM: ENTRIES").size()), ' ');
  for (auto& name : names) name.column += static_cast<long long>(std::string_view("ITEM: ENTRIES").size());

  // The columns read, by name.
  std::vector<std::string> force = wanted.force;
  if (force.empty())
    force = local_find_column(names, "fn") >= 0 ? std::vector<std::string>{"fn"}
                                         : std::vector<std::string>{"fx", "fy", "fz"};
  std::vector<std::string> needed{wanted.id1, wanted.id2};
  needed.insert(needed.end(), force.begin(), force.end());
  std::vector<int> index;
  std::string missing;
  for (const auto& name : needed) {
    index.push_back(local_find_column(names, name));
    if (index.back() >= 0) continue;
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    if (!missing.empty()) missing += ", ";
    missing += name;
  }
  if (!missing.empty()) {
    std::string present;
    for (const auto& n : names) {
      if (!present.empty()) present += ' ';
      present += n.text;
    }
    throw PackingFileError(file, header_line, 0,
                           "no column " + missing + " (columns: " + present +
                               "); name them with [[import]] contact_columns");
  }

  PairForces out;
  out.vector = force.size() == 3;
  out.timestep = steps[block];
  out.first_line = static_cast<long long>(start) + 1;
  for (long long e = 0; e < entries; ++e) {
    const std::size_t k = header + 1 + static_cast<std::size_t>(e);
    const long long number = static_cast<long long>(k) + 1;
    if (k >= end || local_starts_with(lines[k], "ITEM:"))
      throw PackingFileError(file, number, 0,
                             "the snapshot ends after " + std::to_string(e) + " of " +
                                 std::to_string(entries) + " entries (NUMBER OF ENTRIES)");
    const auto fields = split_fields(lines[k], ' ');
    if (fields.size() != names.size())
      throw PackingFileError(file, number, 0,
                             "expected " + std::to_string(names.size()) +
                                 " values (one per column), got " + std::to_string(fields.size()));
    const FieldReader read(file, number);
    PairForceRow row;
    row.line = number;
    // LAMMPS writes ids as integers; a float column (c_pc[7] of pair/gran/local) holds them as
    // "12" or "12.0": accept any number that is a whole one.
    const auto id = [&](std::size_t c) {
      const auto& field = fields[std::size_t(index[c])];
      const double value = read.number(field, needed[c]);
      // Whole and within 2^53 (every such double is an exact integer; the cast of one beyond
      // long long's range is undefined, found by fuzz_packing).
      constexpr double kLargestExactId = 9007199254740992.0;
      if (!(value == std::floor(value) && std::abs(value) <= kLargestExactId))
        throw PackingFileError(file, number, field.column,
                               "column " + needed[c] + ": expected a particle id, got \"" +
                                   std::string(field.text) + "\"");
      return static_cast<long long>(value);
    };
    row.id1 = id(0);
    row.id2 = id(1);
    if (row.id1 == row.id2)
      throw PackingFileError(file, number, 0, "a contact of particle " + std::to_string(row.id1) + " with itself");
    for (std::size_t d = 0; d < force.size(); ++d)
      row.force[d] = read.number(fields[std::size_t(index[2 + d])], needed[2 + d]);
    if (!out.vector && row.force[0] < 0.0)
      throw PackingFileError(file, number, fields[std::size_t(index[2])].column,
                             "column " + needed[2] + ": a normal force must be >= 0 N, got " +
                                 std::string(fields[std::size_t(index[2])].text));
    out.rows.push_back(row);
  }
  if (header + 1 + static_cast<std::size_t>(entries) < end) {
    const std::size_t k = header + 1 + static_cast<std::size_t>(entries);
    if (!split_fields(lines[k], ' ').empty() && !local_starts_with(lines[k], "ITEM:"))
      throw PackingFileError(file, static_cast<long long>(k) + 1, 0,
                             "more entries than NUMBER OF ENTRIES (" + std::to_string(entries) + ")");
  }
  return out;
}

}  // namespace tmdem::coupling
