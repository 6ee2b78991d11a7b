#include "coupling/scene/ParticleImport.h"

#include <cmath>
#include <cstdio>

#include "coupling/output/OutputError.h"
#include "coupling/scene/PackingFile.h"
#include "coupling/scene/PackingFormats.h"
#include "coupling/scene/SceneBuilder.h"

namespace tmdem::coupling {

namespace {

// The file read by its format (PackingFormats.h); format = "auto" is replaced by the one found:
// by the file's ending, else by its text.
Packing read_packing(const SceneTable& t, const std::string& path, std::string& format,
                     const std::string& temperature_column, bool z_required) {
  const PackingFormat* chosen =
      format == "auto" ? packing_format_by_ending(path) : find_packing_format(format);
  std::string text;
  if (chosen == nullptr || chosen->reads_text) text = read_packing_text(path);
  if (chosen == nullptr) chosen = packing_format_by_text(text);
  if (chosen == nullptr)
    t.fail("file", "cannot tell the format of " + quote_text(path) + " " +
                       unknown_packing_format_hint());
  format = chosen->name;
  return chosen->read({t, path, temperature_column, z_required}, text);
}

// Three significant digits: the report is read, not parsed.
std::string brief(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

std::string describe_import(const ImportReport& r) {
  std::string out = r.origin + ": " + std::to_string(r.count) + " particles (ids " +
                    std::to_string(r.first_id) + "-" + std::to_string(r.first_id + r.count - 1) +
                    ") from " + r.file + " (" + r.format;
  if (!r.description.empty()) out += ", " + r.description;
  out += "); ";
  if (r.largest_overlap > 0.0)
    out += "largest overlap " + brief(r.largest_overlap) + " of the smaller radius (" +
           r.largest_overlap_between + ", " + brief(r.largest_overlap_m) +
           " m), accepted up to " + brief(r.overlap_tolerance) +
           (r.hold_overlaps ? ", overlaps = \"hold\"" : ", overlaps = \"push_out\"");
  else
    out += "no overlap";
  if (!r.contacts_file.empty())
    out += "; " + std::to_string(r.contact_count) + " pair contacts with forces from " +
           r.contacts_file + " (timestep " + std::to_string(r.contacts_timestep) + ")";
  if (!r.ignored_columns.empty()) {
    out += "; ignored columns:";
    for (const auto& c : r.ignored_columns) out += " " + c;
  }
  return out;
}

void SceneBuilder::read_imports() {
  const auto tables = root_.table_array("import", true);
  for (std::size_t index = 0; index < tables.size(); ++index) {
    const SceneTable& t = tables[index];
    ImportReport report;
    report.origin = t.path();
    report.file = t.required_string("file");
    if (report.file.empty()) t.fail("file", "must not be empty");
    report.format = t.choice("format");
    report.overlap_tolerance = t.number("overlap_tolerance");
    report.hold_overlaps = t.choice("overlaps") == "hold";
    const double scale = t.number("length_scale");
    const Vec3 offset = t.optional_vec3("offset", scene_.dimension).value_or(Vec3{});
    const std::string temperature_column =
        t.optional_string("temperature_column").value_or("temperature");
    if (temperature_column.empty()) t.fail("temperature_column", "must not be empty");
    std::vector<int> type_materials;
    if (t.has("type_materials")) {
      const auto* names = t.node("type_materials")->as_array();
      if (names == nullptr || names->empty())
        t.fail("type_materials", "expected a non-empty array of [[material]] names");
      for (std::size_t k = 0; k < names->size(); ++k) {
        const auto name = names->get(k)->value<std::string>();
        const auto it = name ? material_ids_.find(*name) : material_ids_.end();
        if (it == material_ids_.end())
          t.fail_at(names->get(k), t.key_path("type_materials") + "[" + std::to_string(k) + "]",
                    "expected the name of a [[material]]");
        type_materials.push_back(it->second);
      }
    }
    const ParticleSettings settings = read_settings_of(t);

    Packing packing;
    try {
      packing = read_packing(t, report.file, report.format, temperature_column,
                             scene_.dimension == 3);
    } catch (const PackingFileError& e) {
      t.fail("file", e.what());
    } catch (const OutputError& e) {  // a result file ([[import]] format = "tmdem")
      t.fail("file", e.what());
    }
    report.description = packing.description;
    report.ignored_columns = packing.ignored_columns;
    report.first_id = scene_.particles.size();
    report.count = packing.rows.size();

    for (const PackingRow& row : packing.rows) {
      const std::string at = row.line > 0 ? report.file + ":" + std::to_string(row.line)
                                          : report.file + ", particle " +
                                                std::to_string(scene_.particles.size() - report.first_id);
      const auto fail_row = [&](const std::string& problem) { t.fail("file", at + ": " + problem); };
      Vec3 position;
      for (int d = 0; d < 3; ++d) position[d] = row.position[d] * scale + offset[d];
      const double radius = row.radius * scale;
      if (!std::isfinite(position[0] + position[1] + position[2]) || !(radius > 0.0) ||
          !std::isfinite(radius))
        fail_row("position or radius is not finite after length_scale");
      if (scene_.dimension == 2 && position[2] != 0.0)
        fail_row("z = " + format_number(position[2]) +
                 " in a 2D scene (simulation.dimension = 2 needs z = 0)");
      ParticleSettings from_file;
      from_file.temperature_K = row.temperature_K;
      from_file.fixed = row.fixed;
      from_file.fixed_temperature = row.fixed_temperature;
      from_file.heat_source_W = row.heat_source_W;
      if (!settings.material) {
        if (row.material) {
          const auto it = material_ids_.find(*row.material);
          if (it == material_ids_.end())
            fail_row("unknown material " + quote_text(*row.material) +
                     " (define a [[material]] of that name, or set " + t.key_path("material") + ")");
          from_file.material = it->second;
        } else if (row.type && !type_materials.empty()) {
          if (*row.type < 1 || *row.type > static_cast<long long>(type_materials.size()))
            fail_row("atom type " + std::to_string(*row.type) + " has no entry in " +
                     t.key_path("type_materials") + " (" + std::to_string(type_materials.size()) +
                     " given, for types 1 to " + std::to_string(type_materials.size()) + ")");
          from_file.material = type_materials[std::size_t(*row.type - 1)];
        } else {
          t.fail("file", report.file + ": the file names no material" +
                             std::string(row.type ? " (it has atom types: give type_materials)" : "") +
                             "; set " + t.key_path("material"));
        }
      }
      ParticleSettings combined = from_file;
      combined.material = settings.material ? settings.material : from_file.material;
      if (settings.temperature_K) combined.temperature_K = settings.temperature_K;
      if (settings.fixed) combined.fixed = settings.fixed;
      if (settings.fixed_temperature) combined.fixed_temperature = settings.fixed_temperature;
      if (settings.heat_source_W) combined.heat_source_W = settings.heat_source_W;
      add_particle(position, radius, combined, report.origin + " (" + at + ")", t);
      import_of_.back() = static_cast<int>(scene_.imports.size());
    }
    if (t.has("contacts")) read_import_contacts(t, packing, report.first_id, report);
    else if (t.has("contact_columns") || t.has("wall_gap"))
      t.fail(t.has("contact_columns") ? "contact_columns" : "wall_gap",
             "goes with contacts (the local dump of the pair forces), which is not given");
    scene_.imports.push_back(std::move(report));
  }
  auto& forces = scene_.imported_forces;
  if (!forces.wall_gap.empty()) forces.wall_gap.resize(scene_.particles.size(), -1.0);
}

}  // namespace tmdem::coupling
