#pragma once
// The contacts of one body solved together, every other reaction frozen (the block visit of
// "nlgs_block", BlockGaussSeidelSolver.h).
//
// Why: a light body L between a heavy body H and a wall makes Gauss-Seidel crawl. The Delassus
// block of L's two normal contacts is [[a + b, b], [b, b]] (a = 1/m_H, b = 1/m_L): each single
// visit of the contact above L moves L, the contact below undoes most of it, and the error
// contracts by b / (a + b) per forward sweep (25/26 for 0.5 mm glass under 1 mm steel; the
// symmetric sweeps give its square root per sweep, measured 0.980 on bench_pour's step 11).
// Solving L's contacts at once removes that mode: the heavy-on-light column is exact in one
// visit.
//
// How: with the others frozen, the block's local velocities are U = q + W R (R: the block's
// reactions; W: its Delassus block, dense through the shared body: W_cc' = J_c M_B^-1 J_c'^T
// for c != c', the problem's diag(w_n, w_t, w_t) on the diagonal). The law is solved by an
// active-set iteration on the contacts' statuses: open (r = 0), stick (u = 0), slip (u_n = 0,
// r_t = mu r_n d with d the direction opposite the slip velocity, taken from the previous
// iterate); each pass solves the linear system of the current statuses (dense LU), then
// switches statuses that violate the law (r_n < 0: open; an open contact closing: stick;
// |r_t| > mu r_n: slip; slip velocity along the friction: stick). The result is accepted
// only when every contact's closed-form single visit (CoulombCone.h) would leave it unchanged
// to 1e-9 of the block's impulse: then it is a solution of the block's law, and the outer
// sweep keeps Gauss-Seidel's fixed points. Otherwise (no settled statuses within the pass
// limit, or more contacts than the block holds) nothing is changed and the caller falls back
// to single visits.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mechanics/contact/ContactProblem.h"
#include "mechanics/solvers/GaussSeidelUpdate.h"

namespace tmdem::mechanics {

class BodyContactBlock {
 public:
  static constexpr int kMaxClosed = 12;  // closed contacts (36 unknowns) a block solves at most
  static constexpr int kMaxPasses = 30;  // active-set passes before giving up

  struct Result {
    bool solved = false;  // false: nothing changed, visit the contacts singly
    ContactUpdate update; // sums over the block's contacts, as single visits would give
    int passes = 0;
  };

  // Solves the contacts `contacts` of body `body` (each has `body` as body_i or body_j) with
  // every other reaction frozen; on success writes r and the velocities (as apply_impulse).
  Result solve(const ContactProblem& problem, std::size_t body, const std::int32_t* contacts,
               int count, std::vector<Eigen::Vector3d>& r, std::vector<Eigen::Vector3d>& velocity,
               std::vector<Eigen::Vector3d>& angular_velocity);

 private:
  enum class Status : std::uint8_t { open, stick, slip };
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * kMaxClosed, 3 * kMaxClosed>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kMaxClosed, 1>;

  // Per block contact (scratch kept between calls: no allocation once warm).
  std::vector<Eigen::Matrix<double, 3, 6>> jacobian_;  // local velocity from the body's (v, omega)
  std::vector<Eigen::Vector3d> q_, x_, u_, dir_;       // free local velocity, iterate, U, slip direction
  std::vector<Status> status_;
  std::vector<double> slip_gain_;                      // mu r_n0 / |u_t0| of a slip's Newton row, 1/kg
  std::vector<int> slot_;                              // position among the closed contacts, -1 open
  std::vector<char> column_built_;                     // per contact: W's column computed
  std::vector<double> coupling_;                       // W, (3 count) x (3 count), row-major
};

}  // namespace tmdem::mechanics
