#include "mechanics/NscdIntegrator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "mechanics/CoulombCone.h"

namespace tmdem::mechanics {
namespace {

// Two unit tangents completing n. In 2D, t1 stays in the plane and t2 = z, so that the
// out-of-plane tangential reaction is exactly zero.
void tangent_frame(const Eigen::Vector3d& n, int dimension, Eigen::Vector3d& t1,
                   Eigen::Vector3d& t2) {
  if (dimension == 2) {
    t1 = Eigen::Vector3d(-n.y(), n.x(), 0.0);
    t2 = Eigen::Vector3d::UnitZ();
    return;
  }
  const Eigen::Vector3d a =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  t1 = (a - a.dot(n) * n).normalized();
  t2 = n.cross(t1);
}

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("mechanics: " + message);
}

}  // namespace

NscdIntegrator::NscdIntegrator(ParticleSet particles, std::vector<Material> materials,
                               std::vector<Wall> walls, const Eigen::Vector3d& gravity_m_per_s2,
                               int dimension, NscdParameters parameters)
    : particles_(std::move(particles)),
      materials_(std::move(materials)),
      walls_(std::move(walls)),
      gravity_(gravity_m_per_s2),
      dimension_(dimension),
      parameters_(parameters),
      detector_(parameters.min_margin_fraction * std::max(particles_.max_radius(), 1e-300),
                parameters.max_margin_fraction * std::max(particles_.max_radius(), 1e-300)) {
  particles_.validate();
  require(dimension == 2 || dimension == 3, "dimension must be 2 or 3");
  require(gravity_.allFinite(), "gravity must be finite");
  require(parameters_.time_step > 0.0 && std::isfinite(parameters_.time_step),
          "time_step must be positive");
  require(parameters_.theta > 0.0 && parameters_.theta <= 1.0, "theta must be in (0, 1]");
  require(parameters_.tolerance > 0.0, "tolerance must be positive");
  require(parameters_.max_iterations >= 1, "max_iterations must be at least 1");
  require(parameters_.relaxation > 0.0 && parameters_.relaxation < 2.0,
          "relaxation must be in (0, 2)");
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    require(materials_[m].friction >= 0.0 && std::isfinite(materials_[m].friction),
            "material " + std::to_string(m) + ": friction must be >= 0");
  }
  const auto material_count = static_cast<int>(materials_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    require(particles_.material[i] < material_count,
            "particle " + std::to_string(i) + ": material index out of range");
  }
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    require(walls_[w].material >= 0 && walls_[w].material < material_count,
            "wall " + std::to_string(w) + ": material index out of range");
    require(walls_[w].point.allFinite() && walls_[w].normal.allFinite() &&
                std::abs(walls_[w].normal.norm() - 1.0) < 1e-12,
            "wall " + std::to_string(w) + ": normal must be a unit vector");
  }
  if (dimension_ == 2) {
    gravity_.z() = 0.0;
    // A wall normal with a z component would push particles out of the plane.
    for (auto& wall : walls_) {
      wall.normal.z() = 0.0;
      require(wall.normal.norm() > 0.0, "a wall normal along z makes no sense in 2D");
      wall.normal.normalize();
    }
  }

  const std::size_t n = particles_.size();
  inverse_mass_.resize(n);
  inverse_inertia_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool fixed = particles_.fixed[i] != 0;
    inverse_mass_[i] = fixed ? 0.0 : 1.0 / particles_.mass[i];
    inverse_inertia_[i] = fixed ? 0.0 : 1.0 / particles_.inertia[i];
    if (fixed) {
      particles_.velocity[i].setZero();
      particles_.angular_velocity[i].setZero();
    }
  }
  keep_in_plane();
  old_velocity_.resize(n);
  old_angular_velocity_.resize(n);
  lookahead_.resize(n);
}

void NscdIntegrator::invalidate_contacts() { detector_.invalidate(); }

void NscdIntegrator::keep_in_plane() {
  if (dimension_ != 2) return;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    particles_.velocity[i].z() = 0.0;
    particles_.angular_velocity[i].x() = 0.0;
    particles_.angular_velocity[i].y() = 0.0;
  }
}

StepReport NscdIntegrator::step() { return step(parameters_.time_step); }

void NscdIntegrator::refresh_candidates(double h) {
  // Look-ahead: a bound on the displacement during the coming step, doubled for the
  // contact impulses and the (1 - theta) part of the next position term.
  const double g = gravity_.norm();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    lookahead_[i] = 2.0 * h * (particles_.velocity[i].norm() + h * g);
  }
  if (!detector_.update(particles_, walls_, lookahead_)) return;
  // Carry the forces of pairs that stay candidates over to the new table (warm start).
  std::swap(force_, old_force_);
  const auto& previous = detector_.previous_index();
  force_.resize(detector_.pairs().size());
  for (std::size_t k = 0; k < force_.size(); ++k) {
    force_[k] = previous[k] >= 0 ? old_force_[previous[k]] : Eigen::Vector3d::Zero();
  }
}

Eigen::Vector3d NscdIntegrator::relative_velocity(const ContactRow& c) const {
  // Velocity of i's material point at the contact minus j's: contact points sit at
  // x_i - R_i n and x_j + R_j n.
  const auto& v = particles_.velocity;
  const auto& w = particles_.angular_velocity;
  if (c.j >= 0) {
    return v[c.i] - v[c.j] - (c.lever_i * w[c.i] + c.lever_j * w[c.j]).cross(c.n);
  }
  return v[c.i] - (c.lever_i * w[c.i]).cross(c.n);
}

void NscdIntegrator::apply_impulse(const ContactRow& c, const Eigen::Vector3d& p) {
  // p acts on i at x_i - R_i n (torque -R_i n x p) and -p on j at x_j + R_j n (same sign).
  const Eigen::Vector3d nxp = c.n.cross(p);
  particles_.velocity[c.i] += inverse_mass_[c.i] * p;
  particles_.angular_velocity[c.i] -= (inverse_inertia_[c.i] * c.lever_i) * nxp;
  if (c.j >= 0) {
    particles_.velocity[c.j] -= inverse_mass_[c.j] * p;
    particles_.angular_velocity[c.j] -= (inverse_inertia_[c.j] * c.lever_j) * nxp;
  }
}

void NscdIntegrator::setup_contacts(double h) {
  const auto& pairs = detector_.pairs();
  const double theta = parameters_.theta;
  rows_.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    ContactRow& c = rows_[k];
    c.i = pairs[k].i;
    c.j = pairs[k].j;
    const Eigen::Vector3d& xi = particles_.position[c.i];
    c.lever_i = particles_.radius[c.i];
    double inverse_mass = inverse_mass_[c.i];
    double inverse_rotation = c.lever_i * c.lever_i * inverse_inertia_[c.i];
    int other_material;
    if (c.j >= 0) {
      const Eigen::Vector3d d = xi - particles_.position[c.j];
      const double distance = d.norm();
      // Coincident centres have no defined normal; any unit vector in the plane will do.
      c.n = distance > 0.0 ? Eigen::Vector3d(d / distance) : Eigen::Vector3d::UnitY();
      // 2D: centres share z, so n_z is 0 already; enforce it if a scene breaks that.
      if (dimension_ == 2 && c.n.z() != 0.0) {
        c.n.z() = 0.0;
        c.n = c.n.norm() > 0.0 ? Eigen::Vector3d(c.n.normalized()) : Eigen::Vector3d::UnitY();
      }
      c.lever_j = particles_.radius[c.j];
      c.gap = distance - c.lever_i - c.lever_j;
      inverse_mass += inverse_mass_[c.j];
      inverse_rotation += c.lever_j * c.lever_j * inverse_inertia_[c.j];
      other_material = particles_.material[c.j];
    } else {
      const Wall& wall = walls_[-1 - c.j];
      c.n = wall.normal;
      c.lever_j = 0.0;
      c.gap = wall.signed_distance(xi) - c.lever_i;
      other_material = wall.material;
    }
    tangent_frame(c.n, dimension_, c.t1, c.t2);
    // W = H^T M^-1 H: (1/m_i + 1/m_j) I + (R_i^2/I_i + R_j^2/I_j) (I - n n^T), i.e.
    // diag(w_n, w_t, w_t) in the local frame.
    c.w_n = inverse_mass;
    c.w_t = inverse_mass + inverse_rotation;
    c.solved = c.w_n > 0.0;
    c.mu = contact_friction(materials_[particles_.material[c.i]], materials_[other_material]);

    // Position term P / h, with the normal velocity at the start of the step.
    const Eigen::Vector3d& vi = old_velocity_[c.i];
    const Eigen::Vector3d& wi = old_angular_velocity_[c.i];
    Eigen::Vector3d u_old = vi - (c.lever_i * wi).cross(c.n);
    if (c.j >= 0) {
      u_old -= old_velocity_[c.j] + (c.lever_j * old_angular_velocity_[c.j]).cross(c.n);
    }
    c.bias = (c.gap + h * (1.0 - theta) * u_old.dot(c.n)) / h;

    // Warm start: last step's force of this pair, in the new frame, as an impulse.
    const Eigen::Vector3d impulse = force_[k] * h;
    c.r = Eigen::Vector3d(impulse.dot(c.n), impulse.dot(c.t1),
                          dimension_ == 2 ? 0.0 : impulse.dot(c.t2));
    c.r = c.solved ? project_onto_coulomb_cone(c.r, c.mu) : Eigen::Vector3d::Zero();
    if (c.r[0] > 0.0) {
      apply_impulse(c, c.r[0] * c.n + c.r[1] * c.t1 + c.r[2] * c.t2);
    }
  }
}

int NscdIntegrator::gauss_seidel(double& residual, bool& converged) {
  const double tolerance = parameters_.tolerance;
  const bool planar = dimension_ == 2;
  const double relaxation = parameters_.relaxation;
  int sweep = 0;
  converged = false;
  residual = 0.0;
  while (sweep < parameters_.max_iterations) {
    ++sweep;
    double change = 0.0, total = 0.0;
    // Symmetric Gauss-Seidel: sweeps alternate forward and backward through the contacts,
    // so that a load travels the whole length of a chain (a column, a force path) in one
    // pair of sweeps whichever way the contacts happen to be numbered.
    const bool forward = sweep % 2 == 1;
    const std::size_t count = rows_.size();
    for (std::size_t visit = 0; visit < count; ++visit) {
      ContactRow& c = rows_[forward ? visit : count - 1 - visit];
      if (!c.solved) continue;
      const Eigen::Vector3d u = relative_velocity(c);
      // Local velocity without this contact's own reaction: u0 = u - W r.
      Eigen::Vector3d u0(u.dot(c.n) + c.bias - c.w_n * c.r[0], u.dot(c.t1) - c.w_t * c.r[1],
                         planar ? 0.0 : u.dot(c.t2) - c.w_t * c.r[2]);
      // Exact local solve (closed form of the bipotential fixed point, CoulombCone.h).
      Eigen::Vector3d r;
      solve_contact_bipotential(u0, c.w_n, c.w_t, c.mu, r);
      if (relaxation != 1.0) r = project_onto_coulomb_cone(c.r + relaxation * (r - c.r), c.mu);
      if (planar) r[2] = 0.0;
      const Eigen::Vector3d dr = r - c.r;
      if (dr[0] != 0.0 || dr[1] != 0.0 || dr[2] != 0.0) {
        apply_impulse(c, dr[0] * c.n + dr[1] * c.t1 + dr[2] * c.t2);
        c.r = r;
      }
      change += dr.norm();
      total += r.norm();
    }
    residual = total > 0.0 ? change / total : 0.0;
    if (change <= tolerance * total) {
      converged = true;
      break;
    }
  }
  return sweep;
}

StepReport NscdIntegrator::step(double h) {
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("mechanics: step must be > 0");
  StepReport report;
  const std::size_t n = particles_.size();
  const std::size_t rebuilds_before = detector_.rebuild_count();
  refresh_candidates(h);
  report.rebuilt_candidates = detector_.rebuild_count() != rebuilds_before;

  // Free velocities (gravity only; no external torque).
  for (std::size_t i = 0; i < n; ++i) {
    old_velocity_[i] = particles_.velocity[i];
    old_angular_velocity_[i] = particles_.angular_velocity[i];
    if (inverse_mass_[i] > 0.0) particles_.velocity[i] += h * gravity_;
  }
  setup_contacts(h);
  report.candidates = rows_.size();
  report.sweeps = gauss_seidel(report.residual, report.converged);
  keep_in_plane();

  // Positions: q_{n+1} = q_n + h (theta v_{n+1} + (1 - theta) v_n).
  const double theta = parameters_.theta;
  for (std::size_t i = 0; i < n; ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    particles_.position[i] += h * (theta * particles_.velocity[i] + (1.0 - theta) * old_velocity_[i]);
  }

  // Forces for the warm start and the contact list; penetration after the step.
  contacts_.clear();
  double penetration = 0.0;
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    const ContactRow& c = rows_[k];
    const Eigen::Vector3d impulse = c.r[0] * c.n + c.r[1] * c.t1 + c.r[2] * c.t2;
    force_[k] = impulse / h;
    double gap;
    if (c.j >= 0) {
      gap = (particles_.position[c.i] - particles_.position[c.j]).norm() - c.lever_i - c.lever_j;
    } else {
      gap = walls_[-1 - c.j].signed_distance(particles_.position[c.i]) - c.lever_i;
    }
    penetration = std::max(penetration, -gap);
    if (c.r[0] > 0.0) {
      ContactForce out;
      out.i = c.i;
      out.j = c.j;
      out.normal = c.n;
      out.gap_m = c.gap;
      out.normal_impulse_Ns = c.r[0];
      out.normal_force_N = c.r[0] / h;
      out.tangential_force_N = (c.r[1] * c.t1 + c.r[2] * c.t2) / h;
      contacts_.push_back(out);
    }
  }
  report.max_penetration_m = penetration;
  report.active_contacts = contacts_.size();
  stats_.add(report);
  return report;
}

double NscdIntegrator::kinetic_energy() const {
  double energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    energy += 0.5 * particles_.mass[i] * particles_.velocity[i].squaredNorm() +
              0.5 * particles_.inertia[i] * particles_.angular_velocity[i].squaredNorm();
  }
  return energy;
}

double NscdIntegrator::potential_energy() const {
  double energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    energy -= particles_.mass[i] * gravity_.dot(particles_.position[i]);
  }
  return energy;
}

double NscdIntegrator::max_speed() const {
  double speed = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass_[i] == 0.0) continue;
    speed = std::max(speed, particles_.velocity[i].norm());
  }
  return speed;
}

}  // namespace tmdem::mechanics
