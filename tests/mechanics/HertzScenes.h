#pragma once
// What the "hertz" normal law's tests share: their solver settings and the steel pair's E*.

#include "mechanics/MechanicsTestScenes.h"
#include "mechanics/contact/HertzNormalLaw.h"

namespace tmdem::mechanics::test {

// nncg (the default solver, which takes compliant problems) to 1e-10, without a sweep limit.
inline NscdParameters hertz_parameters() {
  NscdParameters parameters = nlgs_parameters();
  parameters.solver = "nncg_subspace";
  parameters.normal_law = NormalLaw::hertz;
  parameters.tolerance = 1e-10;
  parameters.max_iterations = 100000;
  return parameters;
}

// E* of two steel() bodies (E 2.1e11 Pa, nu 0.3), Pa.
inline double steel_pair_modulus() {
  const Material m = steel(0.0);
  return hertz_effective_modulus(m.young_modulus, m.poisson_ratio, m.young_modulus, m.poisson_ratio);
}

}  // namespace tmdem::mechanics::test
