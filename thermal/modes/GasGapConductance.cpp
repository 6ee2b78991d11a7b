#include "thermal/modes/GasGapConductance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace tmdem::thermal {
namespace {

// R - sqrt(R^2 - r^2) without cancellation (the gas lens is thin where it matters).
double sag(double R, double r) {
  if (std::isinf(R)) return 0.0;
  return r * r / (R + std::sqrt(std::max(R * R - r * r, 0.0)));
}

// Gas thickness at distance r from the axis.
double thickness(const GasGap& g, double r) {
  return g.gap_m + sag(g.radius_a_m, r) + sag(g.radius_b_m, r);
}

// The shells' gas-equivalent thickness on the ray at r from the axis, m (0 without shells).
double shell_thickness(const GasGap& g, double r) {
  double t = 0.0;
  if (g.shell_gap_a_m > 0.0) t += g.shell_gap_a_m * (1.0 - sag(g.radius_a_m, r) / g.radius_a_m);
  if (g.shell_gap_b_m > 0.0 && !std::isinf(g.radius_b_m))
    t += g.shell_gap_b_m * (1.0 - sag(g.radius_b_m, r) / g.radius_b_m);
  return t;
}

// G7K15 (QUADPACK) on [a, b]: the Kronrod estimate and |Kronrod - Gauss|.
template <class F>
void kronrod(F&& f, double a, double b, double& value, double& error) {
  static constexpr double x[8] = {0.991455371120812639, 0.949107912342758525, 0.864864423359769073,
                                  0.741531185599394440, 0.586087235467691130, 0.405845151377397167,
                                  0.207784955007898468, 0.0};
  static constexpr double wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                                   0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                                   0.204432940075298892, 0.209482141084727828};
  static constexpr double wg[4] = {0.129484966168869693, 0.279705391489276668,
                                   0.381830050505118945, 0.417959183673469388};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double k = 0.0, g = 0.0;
  for (int i = 0; i < 7; ++i) {
    const double s = f(c - h * x[i]) + f(c + h * x[i]);
    k += wk[i] * s;
    if (i % 2 == 1) g += wg[i / 2] * s;
  }
  const double mid = f(c);
  k += wk[7] * mid;
  g += wg[3] * mid;
  value = h * k;
  error = std::abs(h * (k - g));
}

template <class F>
double adaptive(F&& f, double a, double b, double tolerance, int depth, double roundoff);

// The integral of f over [a, b] to a relative 1e-13 of the larger of its first estimate and
// `scale` (what it is added to). roundoff > 0: a piece also counts as converged once its error
// estimate is below roundoff x its value, so that a sharp peak holding a large share of the
// integral (the macro-gap at the contact's rim) does not halve the tolerance below what the
// arithmetic can resolve and split to the depth limit everywhere near it.
template <class F>
double integrate(F&& f, double a, double b, double scale = 0.0, double roundoff = 0.0) {
  double estimate = 0.0, error = 0.0;
  kronrod(f, a, b, estimate, error);
  return adaptive(f, a, b, 1e-13 * std::max(std::abs(estimate), scale), 0, roundoff);
}

template <class F>
double adaptive(F&& f, double a, double b, double tolerance, int depth, double roundoff) {
  double value = 0.0, error = 0.0;
  kronrod(f, a, b, value, error);
  if (error <= tolerance || error <= roundoff * std::abs(value) || depth >= 40) return value;
  const double m = 0.5 * (a + b);
  return adaptive(f, a, m, 0.5 * tolerance, depth + 1, roundoff) +
         adaptive(f, m, b, 0.5 * tolerance, depth + 1, roundoff);
}

}  // namespace

double gas_jump_length_m(double pressure_Pa, double mean_free_path_at_1atm_m, double accommodation) {
  if (!(pressure_Pa > 0.0)) return 0.0;
  constexpr double kAtmosphere_Pa = 101325.0;
  const double mean_free_path_m = mean_free_path_at_1atm_m * kAtmosphere_Pa / pressure_Pa;
  return 2.0 * (2.0 - accommodation) / accommodation * mean_free_path_m;
}

double gas_parameter_m(double pressure_Pa, double mean_free_path_at_1atm_m, double accommodation_1,
                       double accommodation_2, double heat_capacity_ratio, double prandtl) {
  if (!(pressure_Pa > 0.0)) return 0.0;
  constexpr double kAtmosphere_Pa = 101325.0;
  const double mean_free_path_m = mean_free_path_at_1atm_m * kAtmosphere_Pa / pressure_Pa;
  const double surfaces =
      (2.0 - accommodation_1) / accommodation_1 + (2.0 - accommodation_2) / accommodation_2;
  return surfaces * (2.0 * heat_capacity_ratio / (1.0 + heat_capacity_ratio)) * mean_free_path_m /
         prandtl;
}

double bahrami_macrogap_conductance_W_per_K(const GasGap& g, double k_f, double M) {
  const bool plane = std::isinf(g.radius_b_m);
  const double r_min = plane ? g.radius_a_m : std::min(g.radius_a_m, g.radius_b_m);
  const double a = std::clamp(g.contact_radius_m, 0.0, r_min);
  if (!(a < r_min)) return 0.0;
  // s(r) - s(a) of one sphere, sqrt(R^2 - a^2) - sqrt(R^2 - r^2), without cancellation.
  const auto opening = [a](double R, double r) {
    if (std::isinf(R)) return 0.0;
    return (r - a) * (r + a) /
           (std::sqrt(std::max(R * R - a * a, 0.0)) + std::sqrt(std::max(R * R - r * r, 0.0)));
  };
  // r = r_min sin(theta) removes the square-root end point at r = r_min.
  const auto f = [&](double theta) {
    const double r = r_min * std::sin(theta);
    return 2.0 * std::numbers::pi * r * r_min * std::cos(theta) /
           (opening(g.radius_a_m, r) + opening(g.radius_b_m, r) + M);
  };
  return k_f * integrate(f, std::asin(a / r_min), 0.5 * std::numbers::pi, 0.0, 1e-12);
}

bool surrounding_layer_reaches(const GasGap& g, double layer_fraction) {
  const double r_min =
      std::isinf(g.radius_b_m) ? g.radius_a_m : std::min(g.radius_a_m, g.radius_b_m);
  return g.gap_m < layer_fraction * r_min;
}

double equal_share_disk_radius_m(double radius_m, std::size_t neighbours) {
  if (neighbours <= 1) return std::numeric_limits<double>::infinity();
  const double z = static_cast<double>(neighbours);
  return 2.0 * radius_m * std::sqrt(z - 1.0) / z;
}

double surrounding_layer_conductance_W_per_K(const GasGap& g, double k_f, double layer_fraction,
                                             double min_gap_m, double jump_length_m,
                                             double max_disk_radius_m) {
  const bool plane = std::isinf(g.radius_b_m);
  const double r_min = plane ? g.radius_a_m : std::min(g.radius_a_m, g.radius_b_m);
  const double r_max = plane ? g.radius_a_m : std::max(g.radius_a_m, g.radius_b_m);
  const double layer = layer_fraction * r_min;
  if (!(g.gap_m < layer)) return 0.0;
  // Outer radius: where the layer sphere (radius P around the larger centre) meets the other
  // body; the whole smaller hemisphere when it lies inside the layer.
  const double P = r_max + layer;
  double r_out = r_min;
  if (plane) {
    const double h = g.radius_a_m + g.gap_m;  // centre to plane
    r_out = std::min(r_min, std::sqrt(std::max(P * P - h * h, 0.0)));
  } else {
    const double d = g.radius_a_m + g.radius_b_m + g.gap_m;
    if (d * d > P * P - r_min * r_min) {
      const double x = (d * d + P * P - r_min * r_min) / (2.0 * d);
      r_out = std::min(r_min, std::sqrt(std::max(P * P - x * x, 0.0)));
    }
  }
  r_out = std::min(r_out, max_disk_radius_m);  // the pair's share (infinity: no clip)
  const double r_in = std::clamp(g.contact_radius_m, 0.0, r_out);
  if (!(r_out > r_in)) return 0.0;
  // r_k: the gas is thinner than L_min inside it (S grows with r), so conduction there is
  // k_f pi (r_k^2 - r_in^2) / L_min exactly.
  double r_k = r_in;
  if (thickness(g, r_in) < min_gap_m) {
    if (thickness(g, r_out) <= min_gap_m) {
      r_k = r_out;
    } else {
      double lo = r_in, hi = r_out;
      for (int i = 0; i < 200 && hi - lo > 1e-15 * r_out; ++i) {
        const double mid = 0.5 * (lo + hi);
        (thickness(g, mid) < min_gap_m ? lo : hi) = mid;
      }
      r_k = 0.5 * (lo + hi);
    }
  }
  const double pi = std::numbers::pi;
  const bool shells = g.shell_gap_a_m > 0.0 || g.shell_gap_b_m > 0.0;
  double H = 0.0;
  if (!shells) {
    H = pi * (r_k * r_k - r_in * r_in) / (min_gap_m + jump_length_m);
  } else if (r_k > r_in) {
    // Constant gas thickness L_min, but the shells thin towards the rim: integrated.
    const auto f = [&](double r) {
      return 2.0 * pi * r / (min_gap_m + jump_length_m + shell_thickness(g, r));
    };
    H = integrate(f, r_in, r_k);
  }
  if (r_out > r_k) {
    // r = r_min sin(theta) removes the square-root end point at r = r_min.
    const auto f = [&](double theta) {
      const double r = r_min * std::sin(theta);
      return 2.0 * pi * r * r_min * std::cos(theta) /
             (std::max(min_gap_m, thickness(g, r)) + jump_length_m + shell_thickness(g, r));
    };
    const double t0 = std::asin(std::min(r_k / r_min, 1.0));
    const double t1 = std::asin(std::min(r_out / r_min, 1.0));
    H += integrate(f, t0, t1, H);
  }
  return k_f * H;
}

double vargas_mccarthy_conductance_W_per_K(const GasGap& g, double k_f) {
  const double R = std::isinf(g.radius_b_m) ? g.radius_a_m : 0.5 * (g.radius_a_m + g.radius_b_m);
  const double a = std::clamp(g.contact_radius_m, 0.0, R);
  return 2.0 * std::numbers::pi * k_f * (R - a) * (1.0 - 0.5 * (a / R) * (a / R)) /
         (1.0 - std::numbers::pi / 4.0);
}

}  // namespace tmdem::thermal
