#pragma once
// The residual Siconos reports for a frictional contact problem (fc3d_compute_error, fc2d in
// the plane), relative to ||q||:
//   e = sqrt( sum_c || r_c - proj_K(r_c - u~_c) ||^2 ) / ||q||,
//   u~_c = U_c + mu_c |U_t,c| n  (the modified velocity, CoulombCone.h), the step rho = 1,
//   q = the local velocities at r = 0 (free velocities with the position bias).
// Why beside NaturalMapResidual.h: Gauss-Seidel's stop test (change over total, per sweep) and
// the Jacobi natural map measure impulses against impulses and understate how far a slowly
// converging solve is from the law (a step of the re-imported 2,000 bed "converged" at 1e-5 on
// the sweep test had 1.1e-4 here). With rho = 1 and impulses far below velocities in size, e is
// in effect the velocity defect of the law (a loaded contact that still closes, an open one that
// still pushes) relative to the free velocities: the measure a user can check with another code.
// Rolling resistance (ContactProblem::rolling) adds, per contact, the same defect of the rolling
// law in impulse and velocity units: m_c / R_eff against the disk of radius mu_r r_n, and the
// rolling velocity times R_eff (Siconos has no rolling law; without rolling the figure is
// Siconos' own).

#include <Eigen/Core>
#include <vector>

#include "mechanics/contact/ContactProblem.h"

namespace tmdem::mechanics {

// ||q||_2 (m/s) over the solvable contacts: the normaliser above.
double free_velocity_norm(const ContactProblem& problem);

// e above for reactions r (and rolling impulses m when problem.rolling; not read otherwise) and
// the body velocities they give (v_free + M^-1 H r). q_norm: free_velocity_norm(problem); when it
// is 0 the absolute defect is returned (Siconos does the same below DBL_EPSILON).
double siconos_residual(const ContactProblem& problem, const std::vector<Eigen::Vector3d>& r,
                        const std::vector<Eigen::Vector3d>& m,
                        const std::vector<Eigen::Vector3d>& velocity,
                        const std::vector<Eigen::Vector3d>& angular_velocity, double q_norm);

}  // namespace tmdem::mechanics
