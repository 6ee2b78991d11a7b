#pragma once
// Builds a Scene from a parsed scene table (the build step of SceneLoader: parse -> overrides ->
// build -> validate). Internal to coupling/scene; its members live in three files by what they
// read: SceneBuilder.cpp (the settings sections, the effects and the heat-transfer modes'
// sections), SceneBuilderBodies.cpp (materials, particles, walls, [[assign]]) and
// SceneBuilderGenerators.cpp ([[generate]]), ParticleImport.cpp ([[import]]). Checks across the whole scene are in
// SceneValidation.h.
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "coupling/scene/DepositSupport.h"
#include "coupling/scene/PackingFile.h"
#include "coupling/scene/RandomPlacement.h"
#include "coupling/scene/Scene.h"
#include "coupling/scene/SceneError.h"
#include "coupling/scene/SceneTable.h"

namespace tmdem::coupling {

inline constexpr std::int64_t kMaxParticles = 10'000'000;  // sanity bound on generated counts
inline constexpr std::int64_t kIntMax = std::numeric_limits<std::int64_t>::max();
inline constexpr double kOverlapTolerance = 1e-9;  // of the smaller radius (contract section 2)

// "[x, y, z]" for messages.
std::string format_vec3(const Vec3& v);

// Per-particle settings shared by [[particle]], [[generate]] and [[assign]].
struct ParticleSettings {
  std::optional<double> temperature_K;
  std::optional<bool> fixed_temperature;
  std::optional<double> heat_source_W;
  std::optional<bool> fixed;
  std::optional<int> material;

  bool any() const {
    return temperature_K || fixed_temperature || heat_source_W || fixed || material;
  }
  void apply_to(Particle& p) const {
    if (temperature_K) p.temperature_K = *temperature_K;
    if (fixed_temperature) p.fixed_temperature = *fixed_temperature;
    if (heat_source_W) p.heat_source_W = *heat_source_W;
    if (fixed) p.fixed = *fixed;
    if (material) p.material = *material;
  }
};

class SceneBuilder {
 public:
  SceneBuilder(const toml::table& root, std::string source)
      : root_(&root, "", "", source), source_(std::move(source)) {}

  // The scene, every value checked; throws SceneError naming the first problem.
  Scene build();

 private:
  // SceneBuilder.cpp
  void read_format();
  SceneTable section(std::string_view key, bool enforce) const;
  void read_simulation();
  void read_effects();
  void read_heat_modes();
  void read_settings();
  void check_rough_surfaces(const SceneTable& thermal_table) const;  // conductance = "bahrami"
  // SceneBuilderBodies.cpp
  void read_materials();
  int material_of(const SceneTable& t, std::string_view key) const;
  ParticleSettings read_settings_of(const SceneTable& t) const;
  void add_particle(const Vec3& position, double radius, const ParticleSettings& settings,
                    const std::string& origin, const SceneTable& t);
  void read_particles();
  void read_walls();
  void place_on_bed(Wall& w) const;  // a piston's start = "on_bed"
  void read_periodic();          // [periodic]: the periods (after [simulation])
  void check_periodic_bodies();  // the periods against the particles and walls; wraps them
  void read_assigns();
  // SceneBuilderGenerators.cpp
  void read_generators();
  void check_total(const SceneTable& t, std::string_view key, std::int64_t count) const;
  // kind = "random" or "deposit": spheres filling a box (tables[index]).
  void read_box_filling(const std::vector<SceneTable>& tables, std::size_t index,
                        const std::string& kind, std::vector<Vec3>& positions,
                        std::vector<double>& radii);
  // ParticleImport.cpp
  void read_imports();
  // ContactImport.cpp: an [[import]]'s contacts = "local dump" (its particles are scene ids
  // first .. first + packing.rows.size() - 1).
  void read_import_contacts(const SceneTable& t, const Packing& packing, std::size_t first,
                            ImportReport& report);

  SceneTable root_;
  std::string source_;
  // Positions laid by a joint deposit for the later [[generate]] entries of its group, by index.
  std::map<std::size_t, RandomPlacement> deposited_;
  // Every kind = "deposit" entry's particles and box, for the warning on a floor on no wall.
  std::vector<DepositedBlock> deposit_blocks_;
  Scene scene_;
  std::vector<std::string> origins_;  // per particle: "particle[3]" or "generate[0]"
  std::vector<int> import_of_;        // per particle: index of its [[import]], or -1
  std::map<std::string, int> material_ids_;
};

}  // namespace tmdem::coupling
