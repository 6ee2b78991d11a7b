#pragma once
// Which near pairs of a thermal network see each other: a pair is shadowed when the segment
// between the two centres passes through a third particle (centre closer to it than its
// radius). A blocker of such a segment lies within reach of one of the pair's ends, so only
// their network neighbours are tested: O(edges x neighbours). Contacts are never shadowed.
// Used by pair radiation (thermal/modes/PairRadiationGeometry.h); a binary test of the centre
// line, not a partial view factor.
#include <cstdint>
#include <vector>

#include "mechanics/model/ParticleSet.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::coupling {

// Per edge of `edges` (whose nodes are the particles of `geometry`): 1 when shadowed.
std::vector<std::uint8_t> shadowed_edges(const thermal::ThermalNetwork& edges,
                                         const mechanics::ParticleSet& geometry);

}  // namespace tmdem::coupling
