#include "coupling/scene/ResultPackingReader.h"

#include <toml++/toml.h>

#include "coupling/output/ResultFrameReader.h"
#include "coupling/scene/SceneTable.h"

namespace tmdem::coupling {

namespace {

// The [[material]] names of the scene stored in a result, in index order.
std::vector<std::string> material_names(const std::string& scene_text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(scene_text, path);
  } catch (const toml::parse_error& error) {
    throw PackingFileError(path, 0, 0, "its stored scene is not valid TOML: " +
                                           std::string(error.description()));
  }
  std::vector<std::string> names;
  if (const auto* materials = root["material"].as_array())
    for (const auto& entry : *materials) {
      const auto* table = entry.as_table();
      const auto name = table != nullptr ? (*table)["name"].value<std::string>() : std::nullopt;
      names.push_back(name.value_or(""));
    }
  return names;
}

}  // namespace

Packing read_result_packing(const std::string& path, std::int64_t frame) {
  const ResultFrame result = read_result_frame(path, frame);
  const auto names = material_names(result.scene, path);
  Packing packing;
  packing.rows.resize(result.radius_m.size());
  for (std::size_t i = 0; i < packing.rows.size(); ++i) {
    PackingRow& row = packing.rows[i];
    row.position = {result.position_m[3 * i], result.position_m[3 * i + 1],
                    result.position_m[3 * i + 2]};
    row.radius = result.radius_m[i];
    row.temperature_K = result.temperature_K[i];
    const auto m = result.material[i];
    if (m < 0 || static_cast<std::size_t>(m) >= names.size() || names[std::size_t(m)].empty())
      throw PackingFileError(path, 0, 0,
                             "particle " + std::to_string(i) + " has material index " +
                                 std::to_string(m) + ", which its stored scene does not name");
    row.material = names[std::size_t(m)];
  }
  packing.description = "frame " + std::to_string(result.index) + " of " +
                        std::to_string(result.frames) + " (t = " + format_number(result.time_s) +
                        " s)";
  return packing;
}

}  // namespace tmdem::coupling
