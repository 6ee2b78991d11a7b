// NscdIntegrator's "hertz" normal law (NormalLaw.h): each candidate's Hertz law linearised for
// the step (HertzNormalLaw.h) as a normal compliance and a bias, after setup_contacts.
#include <algorithm>
#include <cmath>

#include "mechanics/contact/ContactKinematics.h"
#include "mechanics/contact/HertzNormalLaw.h"
#include "mechanics/integrator/NscdIntegrator.h"

namespace tmdem::mechanics {

void NscdIntegrator::set_hertz_laws(double h) {
  ContactProblem& p = problem_;
  const double theta = parameters_.theta;
  hertz_coefficient_.resize(p.size());
#pragma omp parallel for schedule(static) \
    if (static_cast<std::ptrdiff_t>(p.size()) >= parameters_.parallel_from)
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.compliance[k] = 0.0;
    hertz_coefficient_[k] = 0.0;
    if (!p.solvable(k)) continue;
    const std::int32_t i = p.body_i[k], j = p.body_j[k];
    const Material& a = materials_[particles_.material[i]];
    const Material& b = materials_[is_wall(j) ? walls_[wall_index(j)].material : particles_.material[j]];
    const double coefficient = hertz_coefficient(
        hertz_effective_modulus(a.young_modulus, a.poisson_ratio, b.young_modulus, b.poisson_ratio),
        hertz_effective_radius(p.lever_i[k], p.lever_j[k]));
    hertz_coefficient_[k] = coefficient;
    const Eigen::Vector3d& n = p.normal[k];
    // The tangent point: the force the pair carried last step; for a pair that carried none,
    // the force that stops its free approach (its speed with this step's gravity and loads)
    // within the step, so that a first touch is nearly rigid instead of a spring of zero
    // stiffness the body sinks into; or the overlap at the start of the step where it is much
    // deeper (a bed whose particles grew, an imported one).
    const double free_approach_m_per_s =
        -relative_velocity<Eigen::Vector3d>(p, k, p.free_velocity, p.free_angular_velocity).dot(n);
    const double carried_N = force_[k].dot(n);
    const double tangent_N =
        carried_N > 0.0 ? carried_N : std::max(free_approach_m_per_s, 0.0) / (h * p.w_n[k]);
    const double gap_m = gap_[k];
    // Only an overlap beyond twice the force's: at rest the two agree, and the switch between
    // them right at the solution made the iteration cycle (a piston on a sphere: 2e-8 m/s
    // after 20,000 steps).
    double tangent_m = hertz_overlap(coefficient, tangent_N);
    if (-gap_m > 2.0 * tangent_m) tangent_m = -gap_m;
    if (!(tangent_m > 0.0)) continue;  // nothing approaches, nothing carried: rigid this step
    // The predicted gap of setup_contacts; for a pair that carried no force, never an overlap
    // deeper than the one at the start of the step: the (1 - theta) h u_old of a landing is
    // the scheme's, not the spring's (pushed out, it would bounce a landing sphere back at a
    // third of its speed), and the position step removes what the scheme adds beyond the
    // elastic overlap. Not for loaded pairs: at rest the clamp's kink made them cycle.
    const double approach_m_per_s =
        -relative_velocity<Eigen::Vector3d, VelocityRounding::points_first>(p, k, old_velocity_,
                                                                            old_angular_velocity_)
             .dot(n);
    double predicted_m = gap_m - h * (1.0 - theta) * approach_m_per_s;
    if (!(carried_N > 0.0)) predicted_m = std::max(predicted_m, std::min(gap_m, 0.0));
    const HertzStepLaw law = hertz_step_law(coefficient, tangent_m, predicted_m, h);
    p.compliance[k] = law.compliance_per_kg;
    p.bias[k] = law.bias_m_per_s;
  }
}

void NscdIntegrator::add_elastic_overlaps(double h, std::vector<double>& gap_m) const {
  for (std::size_t k = 0; k < gap_m.size(); ++k) {
    if (hertz_coefficient_[k] > 0.0)
      gap_m[k] += hertz_overlap(hertz_coefficient_[k], std::max(reactions_[k][0], 0.0) / h);
  }
}

}  // namespace tmdem::mechanics
