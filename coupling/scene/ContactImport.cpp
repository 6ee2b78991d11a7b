// [[import]] contacts: the pair forces of an imported packing, from a LAMMPS / LIGGGHTS local
// dump (LocalDumpReader.h), as scene particle pairs with their normal force in N.
#include <algorithm>
#include <cmath>
#include <map>

#include "coupling/scene/LocalDumpReader.h"
#include "coupling/scene/SceneBuilder.h"

namespace tmdem::coupling {

namespace {

// contact_columns = { id1 = "...", id2 = "...", normal_force = "..." or force = [3 names] }
LocalDumpColumns contact_columns_of(const SceneTable& t) {
  LocalDumpColumns columns;
  const auto table = t.optional_table("contact_columns", true);
  if (!table) return columns;
  const auto name = [&](std::string_view key, std::string fallback) {
    const auto value = table->optional_string(key).value_or(fallback);
    if (value.empty()) table->fail(key, "must not be empty");
    return value;
  };
  columns.id1 = name("id1", columns.id1);
  columns.id2 = name("id2", columns.id2);
  if (table->has("normal_force") && table->has("force"))
    table->fail("force", "give normal_force or force, not both");
  if (table->has("normal_force")) columns.force = {name("normal_force", "")};
  if (table->has("force")) {
    const auto* names = table->node("force")->as_array();
    if (names == nullptr || names->size() != 3)
      table->fail("force", "expected 3 column names (the force vector x, y, z)");
    for (std::size_t k = 0; k < 3; ++k) {
      const auto text = names->get(k)->value<std::string>();
      if (!text || text->empty())
        table->fail_at(names->get(k), table->key_path("force") + "[" + std::to_string(k) + "]",
                       "expected a column name");
      columns.force.push_back(*text);
    }
  }
  return columns;
}

}  // namespace

void SceneBuilder::read_import_contacts(const SceneTable& t, const Packing& packing,
                                        std::size_t first, ImportReport& report) {
  const std::string path = t.required_string("contacts");
  if (path.empty()) t.fail("contacts", "must not be empty");
  const LocalDumpColumns columns = contact_columns_of(t);
  const double wall_gap = t.number("wall_gap");
  // Ids of the particle file -> scene particles.
  std::map<long long, std::size_t> scene_id;
  for (std::size_t k = 0; k < packing.rows.size(); ++k) {
    if (!packing.rows[k].id)
      t.fail("contacts", report.file + ": the particle file has no id column, which the "
                         "contacts of " + path + " refer to");
    scene_id[*packing.rows[k].id] = first + k;
  }
  PairForces forces;
  try {
    forces = read_local_dump(read_packing_text(path), path, columns, packing.timestep, report.file);
  } catch (const PackingFileError& e) {
    t.fail("contacts", e.what());
  }
  std::map<std::pair<std::size_t, std::size_t>, long long> line_of;  // duplicates
  auto& imported = scene_.imported_forces;
  for (const auto& row : forces.rows) {
    const auto at = path + ":" + std::to_string(row.line) + ": ";
    std::size_t ends[2];
    for (int e = 0; e < 2; ++e) {
      const long long id = e == 0 ? row.id1 : row.id2;
      const auto it = scene_id.find(id);
      if (it == scene_id.end())
        t.fail("contacts", at + "particle id " + std::to_string(id) + " is not in " + report.file);
      ends[e] = it->second;
    }
    const auto i = std::min(ends[0], ends[1]), j = std::max(ends[0], ends[1]);
    const auto [previous, fresh] = line_of.emplace(std::pair(i, j), row.line);
    if (!fresh)
      t.fail("contacts", at + "the contact of particles " + std::to_string(row.id1) + " and " +
                             std::to_string(row.id2) + " is also on line " +
                             std::to_string(previous->second));
    // n: the unit vector from j to i.
    const auto& a = scene_.particles[i].position_m;
    const auto& b = scene_.particles[j].position_m;
    // Through the nearest periodic image (a pair across a [periodic] boundary).
    const Eigen::Vector3d branch = periodic_box(scene_.periodic).minimum_image(
        Eigen::Vector3d(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    Vec3 n{};
    double length = 0.0;
    for (int d = 0; d < 3; ++d) {
      n[d] = branch[d];
      length += n[d] * n[d];
    }
    length = std::sqrt(length);
    if (!(length > 0.0))
      t.fail("contacts", at + "particles " + std::to_string(row.id1) + " and " +
                             std::to_string(row.id2) + " have the same centre");
    for (auto& component : n) component /= length;
    ImportedContact contact{i, j, row.force[0], {}};
    if (forces.vector) {
      // The normal part |F . n|: the tangential part presses nothing together. F is the force
      // on one of the two (LIGGGHTS: on id1); its normal part pushes that one away from the
      // other, which tells which one it is, so the convention need not be known.
      double along = 0.0;
      for (int d = 0; d < 3; ++d) along += row.force[d] * n[d];
      contact.normal_force_N = std::abs(along);
      for (int d = 0; d < 3; ++d) contact.force_on_i_N[d] = along >= 0.0 ? row.force[d] : -row.force[d];
    } else {
      for (int d = 0; d < 3; ++d) contact.force_on_i_N[d] = contact.normal_force_N * n[d];
    }
    imported.pairs.push_back(contact);
  }
  std::sort(imported.pairs.begin(), imported.pairs.end(), [](const auto& a, const auto& b) {
    return std::pair(a.i, a.j) < std::pair(b.i, b.j);
  });
  imported.wall_gap.resize(scene_.particles.size(), -1.0);
  for (std::size_t p = first; p < first + packing.rows.size(); ++p) imported.wall_gap[p] = wall_gap;
  report.contacts_file = path;
  report.contact_count = forces.rows.size();
  report.contacts_timestep = forces.timestep;
}

}  // namespace tmdem::coupling
