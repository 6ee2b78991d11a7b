#pragma once
// The warm start of a first step that knows no forces: the normal impulses that would carry
// each particle's weight, and what rests on it, down to the bodies below it, by frictionless
// statics.
//
// Why: a bed laid by deposition or imported from another code starts at rest with no forces.
// Gauss-Seidel from zero impulses passes the weight down one contact layer per sweep or so, and
// the first steps of a deep bed ran thousands of sweeps (the deposited 10^4 bed: 5-10 s a step
// for its first 20 steps, against 0.3 s later). Passing the loads down once, top to bottom, gives
// the solver the forces' depth profile from the start; it then corrects them locally.
//
// How: particles are taken from the highest to the lowest along gravity. Each one's vertical
// load V (its weight plus what the particles above pass down) is shared among its supports
// (touching contacts whose normal into it points up, with a wall or a particle taken later) by
// the least-norm forces whose vertical parts carry it: f_k = V a_k / sum a_j^2, a_k = n_k . up;
// each support passes f_k a_k on. The floor then carries the whole weight. Only clusters of
// particles (joined by contacts that touch or close within the step's fall, |g| h^2) that reach
// a wall or a fixed particle are loaded: a cluster that reaches neither (a bed deposited above
// its floor) is falling, and its contacts start with no force. The horizontal
// balance is left to the solver: the frictionless statics (non-negative least squares on the
// supports, tried first) are ill-posed on a real bed: contacts near the horizontal carried up to
// 4,600 weights, and the floor of the deposited 2,000 bed 1.3 times the bed's weight, and the
// first step took 908 sweeps instead of 759 from zero. A contact counts as touching when its gap
// is at most 1e-6 of the first sphere's radius.
#include <Eigen/Core>
#include <vector>

#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

// reactions[c] = (r_n, 0, 0): the estimated normal impulse (N s) of contact c of `problem` over
// a step of h seconds; the others zero. gap_m: one per contact (m, < 0 overlap); positions: one
// per particle (m). A particle's mass is 1 / problem.inverse_mass (a fixed particle, inverse mass
// 0, carries like a wall). Gravity zero: all zero. Allocates (called once per run).
//
// balance_rounds > 0 (NscdParameters::static_balance_rounds) then balances every held particle,
// horizontally and in rotation too: the least change of the touching contacts' reactions (normal
// and, 100 times costlier, tangential) that leaves each particle at rest after the step, one
// sparse Cholesky (CHOLMOD) of H D^-1 H^T (6 rows per particle) per round, projected onto the cones;
// each further round over the contacts the last left closed. Why: in a deep shaft the vertical
// start puts the whole weight on the floor, where the side walls' friction carries most of it
// (Janssen), and the first solve spent thousands of sweeps finding that (docs/mechanics.md
// "The first step": the 160-layer shaft of bench/depth_and_load.py).
void static_warm_start(const ContactProblem& problem, const std::vector<double>& gap_m,
                       const std::vector<Eigen::Vector3d>& positions_m,
                       const Eigen::Vector3d& gravity_m_per_s2, double h_s,
                       std::vector<Eigen::Vector3d>& reactions, int balance_rounds = 0);

}  // namespace tmdem::mechanics
