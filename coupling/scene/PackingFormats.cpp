#include "coupling/scene/PackingFormats.h"

#include "coupling/scene/CsvPackingReader.h"
#include "coupling/scene/LammpsDumpReader.h"
#include "coupling/scene/ResultPackingReader.h"
#include "coupling/scene/SceneTable.h"

namespace tmdem::coupling {

namespace {

Packing read_csv(const PackingRequest& r, std::string_view text) {
  return read_csv_packing(text, r.path, r.temperature_column, r.z_required);
}

Packing read_lammps(const PackingRequest& r, std::string_view text) {
  return read_lammps_dump(text, r.path, r.temperature_column, r.z_required);
}

// A frame of a result file; `frame` is read here, the only format that has one.
Packing read_result(const PackingRequest& r, std::string_view) {
  return read_result_packing(
      r.path, r.table.integer("frame", -1, -(std::int64_t{1} << 40), std::int64_t{1} << 40));
}

bool ends_with(const std::string& text, std::string_view suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "a, b or c".
std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? " or " : ", ";
    out += items[i];
  }
  return out;
}

}  // namespace

const std::vector<PackingFormat>& packing_formats() {
  static const std::vector<PackingFormat> formats = {
      {.name = "csv", .endings = {".csv", ".CSV"}, .read = &read_csv},
      {.name = "lammps",
       .recognises = &looks_like_lammps_dump,
       .recognised_by = "\"ITEM:\" first line",
       .read = &read_lammps},
      {.name = "tmdem", .endings = {".h5", ".hdf5"}, .reads_text = false, .read = &read_result},
  };
  return formats;
}

const PackingFormat* find_packing_format(std::string_view name) {
  for (const auto& format : packing_formats())
    if (format.name == name) return &format;
  return nullptr;
}

const PackingFormat* packing_format_by_ending(const std::string& path) {
  for (const auto& format : packing_formats())
    for (const auto ending : format.endings)
      if (ends_with(path, ending)) return &format;
  return nullptr;
}

const PackingFormat* packing_format_by_text(std::string_view text) {
  for (const auto& format : packing_formats())
    if (format.recognises != nullptr && format.recognises(text)) return &format;
  return nullptr;
}

std::vector<std::string> packing_format_choices() {
  std::vector<std::string> names{"auto"};
  for (const auto& format : packing_formats()) names.emplace_back(format.name);
  return names;
}

std::string unknown_packing_format_hint() {
  std::vector<std::string> endings, recognised, quoted;
  for (const auto& format : packing_formats()) {
    for (const auto ending : format.endings) endings.emplace_back(ending);
    if (!format.recognised_by.empty()) recognised.emplace_back(format.recognised_by);
    quoted.push_back('"' + std::string(format.name) + '"');
  }
  return "(not " + listed(endings) + ", and no " + listed(recognised) + "); give format = " +
         listed(quoted);
}

}  // namespace tmdem::coupling
