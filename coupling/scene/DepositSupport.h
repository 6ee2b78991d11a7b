#pragma once
// A deposit laid above its floor: a [[generate]] kind = "deposit" lays its spheres at rest on
// the floor of its box (mechanics/model/SequentialDeposition.h), but only the scene's walls and
// particles hold them in the run. When the box's floor is on no wall, the spheres resting on
// it fall at the first step (a bed deposited 1 mm above the floor drops 1 mm and is jumbled by
// the landing, instead of starting at rest): legal, and sometimes meant, so a warning, not a
// refusal. `tmdem check` and `tmdem run` print Scene::warnings.
#include <cstddef>
#include <string>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// What one [[generate]] kind = "deposit" laid: particles first .. first + count - 1.
struct DepositedBlock {
  std::size_t generate_index = 0;  // into the [[generate]] array
  std::size_t first = 0;
  std::size_t count = 0;
  Vec3 box_min_m{}, box_max_m{};
};

// One warning per block whose lowest spheres rest on the box's floor (within 1e-9 of their
// radius: nothing below them but that face) with no wall there: it names the block, how far
// its sphere on the floor farthest from a wall falls along gravity before it meets one (the
// nearest plane wall facing up below it), and that wall, or says that no wall is below. A block
// whose spheres all rest on particles laid before it (a [[particle]] or an earlier
// [[generate]]) gets none, and so does every block when mechanics is off (nothing moves);
// fixed spheres do not count. Gravity along one axis (as a deposit requires); walls as read.
std::vector<std::string> unsupported_deposit_warnings(const Scene& scene,
                                                      const std::vector<DepositedBlock>& blocks);

}  // namespace tmdem::coupling
