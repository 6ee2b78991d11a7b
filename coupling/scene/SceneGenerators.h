#pragma once
// Geometry of the deterministic [[generate]] kinds (contract section 2). Pure functions of their
// arguments: the loader validates the keys and assigns ids in the order returned here.
#include <array>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// "Up" for a column: against gravity, +y when gravity is zero.
Vec3 up_direction(const Vec3& gravity);

// kind = "triangular": rows[0] is the bottom row, origin the centre of its first particle.
// Rows lie along +x and stack along +y (always +y, whatever the gravity), each row centred on the
// one below. Rows whose counts differ by an odd number sit in the hollows of the row below
// (dy = sqrt(3) r, hexagonal stacking); rows whose counts differ by an even number (e.g. equal
// rows) cannot touch that way and are stacked straight on top (dy = 2 r). Particles of a row
// touch (spacing 2 r). Ids: bottom row first, each row from -x to +x.
std::vector<Vec3> triangular_positions(const std::vector<int>& rows, double radius,
                                       const Vec3& origin);

// kind = "column": count touching particles from origin along `up` (spacing 2 r).
std::vector<Vec3> column_positions(int count, double radius, const Vec3& origin, const Vec3& up);

// kind = "lattice": simple cubic, counts = {nx, ny, nz}, x fastest, then y, then z.
std::vector<Vec3> lattice_positions(const std::array<int, 3>& counts, double spacing,
                                    const Vec3& origin);

}  // namespace tmdem::coupling
