#pragma once
// What one KLU factorisation of the Newton matrix costs, known before an integrator makes one:
// KLU's symbolic analysis of the Jacobian pattern (the Newton matrix I - gamma J has the same
// pattern; the AMD ordering the integrators ask for) predicts its flops and fill, in time and
// memory linear in the non-zeros (0.01-0.05 s at 25,000 particles); one factorisation and one
// solve can then be timed. Why: the fill grows far faster than the network on 3D beds (a
// 24,389-particle lattice: 8.6e9 flops, 2-9 s a factorisation on the 2-core development
// machine, load decides; a slab of 25,088 particles 8 layers tall: 2.0e9 flops, 0.5-4 s; 10^6
// particles: out of memory), so the accuracy study predicts its klu runs from it and skips a
// run of hours instead of starting it.
#include <limits>

#include "thermal/system/JacobianPattern.h"

namespace tmdem::thermal {

struct KluFactorisationCost {
  double flops = 0.0;            // KLU's est_flops: floating-point operations of one factorisation
  double factor_nonzeros = 0.0;  // KLU's lnz + unz: the factors' size, what each solve reads once
  // Timed (time_klu_factorisation); NaN when only analysed.
  double factorisation_s = std::numeric_limits<double>::quiet_NaN();
  double solve_s = std::numeric_limits<double>::quiet_NaN();
};

// KLU's analysis alone. Throws ThermalSolverError when it fails (out of memory, overflow).
KluFactorisationCost analyse_klu_factorisation(const JacobianPattern& pattern);

// The analysis, then one factorisation and one forward and back solve, timed (steady_clock), of
// a matrix with the pattern and diagonally dominant values (off-diagonal -1, diagonal the
// column's count): the Newton matrix of a conductance network is diagonally dominant, so KLU
// keeps its diagonal pivots and does the work its analysis predicted, whatever the values.
// Throws ThermalSolverError when KLU fails.
KluFactorisationCost time_klu_factorisation(const JacobianPattern& pattern);

}  // namespace tmdem::thermal
