#include "coupling/scene/SceneProbes.h"

#include <set>

#include "coupling/scene/SceneBuilder.h"

namespace tmdem::coupling {

namespace {

using Key = SceneSchema::Key;

// A probe key has no default: SceneSchema's plain value key with an empty default text.
Key probe_value(std::string name, std::string unit, std::string allowed, std::string description,
                bool required) {
  return schema_value_key(std::move(name), std::move(unit), "", std::move(allowed),
                          std::move(description), required);
}

}  // namespace

SceneSchema::Key probe_schema_key() {
  Key k;
  k.name = "probe";
  k.table = "probe";
  k.kind = SceneSchema::Kind::TableArray;
  k.description = "thermocouple-like readings: particle temperatures summarised per frame";
  return k;
}

SceneSchema::Section probe_schema_section() {
  Key radius = probe_value("radius", "m", "> 0", "a sphere of this radius around point (not with box)",
                           false);
  radius.range = Range::greater(0.0);
  radius.allowed = radius.range->interval();
  return {"probe",
          "a probe: every frame the result stores the count, mean, min and max temperature of "
          "the particles whose centre lies inside (boundary included) under /probes; a probe "
          "holding no particle stores count 0 and temperatures 0 (docs/result-file.md). "
          "Exactly one of radius, box",
          {probe_value("name", "", "non-empty, unique", "the probe's name in the result", true),
           probe_value("point", "m", "3 finite numbers (2 in 2D, z = 0)",
                       "centre of the sphere or box", true),
           radius,
           probe_value("box", "m", "3 numbers > 0 (2 in 2D)",
                       "[dx, dy, dz]: full edge lengths of the axis-aligned box centred on point "
                       "(not with radius)",
                       false)}};
}

std::vector<Probe> read_probes(const SceneTable& root, int dimension) {
  std::vector<Probe> probes;
  std::set<std::string> names;
  for (const SceneTable& t : root.table_array("probe", true)) {
    Probe p;
    p.name = t.required_string("name");
    if (p.name.empty()) t.fail("name", "must not be empty");
    if (!names.insert(p.name).second)
      t.fail("name", "must be unique: another [[probe]] is already named " + quote_text(p.name));
    p.point_m = t.required_vec3("point", dimension);
    if (dimension == 2 && p.point_m[2] != 0.0)
      t.fail("point", "in 2D (dimension = 2) the particles lie at z = 0: the z component must be "
                      "0 (got " + format_vec3(p.point_m) + ")");
    const auto radius = t.optional_number("radius");
    const auto box = t.optional_vec3("box", dimension);
    if (radius && box) t.fail("box", "give either radius (a sphere) or box, not both");
    if (!radius && !box)
      t.fail("radius", "required key is missing: give radius (a sphere, m) or box = [dx, dy, dz] (m)");
    if (radius) {
      p.radius_m = *radius;
    } else {
      // In 2D the particles lie at z = 0, so only the edges in the plane must be positive.
      for (int k = 0; k < dimension; ++k)
        if (!((*box)[std::size_t(k)] > 0.0))
          t.fail("box", "every edge length must be > 0 (got " + format_vec3(*box) + ")");
      p.box_m = *box;
    }
    probes.push_back(std::move(p));
  }
  return probes;
}

}  // namespace tmdem::coupling
