#pragma once
// The normal contact law, chosen by name ([mechanics] normal_law): "rigid", the unilateral
// contact of NSCD (no overlap, forces of a hyperstatic packing not unique), or "hertz", an
// elastic contact at the materials' real moduli (HertzNormalLaw.h): F = K delta^(3/2), within
// the same Moreau-Jean step as a normal compliance (ContactProblem::compliance), so that a
// confined bed carries the force of its particles' growth and every packing has one set of
// forces. The name is parsed once, here, at the scene's edge.

#include <string>
#include <string_view>
#include <vector>

namespace tmdem::mechanics {

enum class NormalLaw { rigid, hertz };

// The valid names, in the order of the enum.
const std::vector<std::string>& normal_law_names();
const std::string& normal_law_name(NormalLaw law);
// std::invalid_argument naming the bad value and the valid ones.
NormalLaw parse_normal_law(std::string_view name);

}  // namespace tmdem::mechanics
