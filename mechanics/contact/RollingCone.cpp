#include "mechanics/contact/RollingCone.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace tmdem::mechanics {

TwoConeProjection project_onto_coulomb_and_rolling_cones(double normal, double tangential,
                                                         double mu, double rolling, double mu_r) {
  // The parts that can pull r_n up: coefficient k > 0 and length L > 0, kink at L / k (the
  // part is cut, and so pulls, for r_n below its kink).
  struct Part {
    double k, length, kink;
  };
  Part parts[2];
  int count = 0;
  for (const auto& [k, length] : {std::pair{mu, tangential}, std::pair{mu_r, rolling}}) {
    if (k > 0.0 && length > 0.0) parts[count++] = {k, length, length / k};
  }
  if (count == 2 && parts[1].kink < parts[0].kink) std::swap(parts[0], parts[1]);
  // On the interval below kink `first` the parts first..count-1 are cut: the derivative
  //   r_n - normal - sum k (L - k r_n)
  // vanishes at r_n = (normal + sum k L) / (1 + sum k^2).
  double r_n = 0.0;
  for (int first = 0; first <= count; ++first) {
    double pull = normal, stiffness = 1.0;
    for (int p = first; p < count; ++p) {
      pull += parts[p].k * parts[p].length;
      stiffness += parts[p].k * parts[p].k;
    }
    const double root = pull / stiffness;
    const double upper = first < count ? parts[first].kink : std::numeric_limits<double>::infinity();
    if (root <= upper) {
      r_n = std::max(root, 0.0);  // a root below 0 (the polar cone): the apex
      break;
    }
  }
  TwoConeProjection out;
  out.normal = r_n;
  out.tangential_factor = tangential > 0.0 ? std::min(1.0, mu * r_n / tangential) : 0.0;
  out.rolling_factor = rolling > 0.0 ? std::min(1.0, mu_r * r_n / rolling) : 0.0;
  return out;
}

}  // namespace tmdem::mechanics
