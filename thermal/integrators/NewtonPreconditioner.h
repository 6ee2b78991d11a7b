#pragma once
// A preconditioner of the symmetric Newton matrix M = scale * J + diag(shift) (J on the
// conductance-Laplacian pattern, both triangles, in pattern order) for the conjugate-gradient
// linear solvers: "pcg" (IncompleteCholesky.h) and "amg" (BoomerAmgPreconditioner.h). The
// integrators call analyse once per contact-graph shape, factor at each preconditioner setup and
// solve at each CG iteration.
#include <span>

#include "thermal/system/JacobianPattern.h"

namespace tmdem::thermal {

class NewtonPreconditioner {
 public:
  virtual ~NewtonPreconditioner() = default;
  virtual void analyse(const JacobianPattern& pattern) = 0;
  // Returns false when M could not be preconditioned (e.g. a non-positive pivot): the
  // integrator then retries with a smaller step.
  virtual bool factor(std::span<const double> J_values, double scale,
                      std::span<const double> shift) = 0;
  // z ~ M^-1 r.
  virtual void solve(std::span<const double> r, std::span<double> z) = 0;
};

}  // namespace tmdem::thermal
