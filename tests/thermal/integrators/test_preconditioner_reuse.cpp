// When CVODES' preconditioner set-up keeps the last V-cycle (PreconditionerReuse.h): only for
// amg, only with current Jacobian data, within a factor 2 of the last gamma, on the same network.
#include <gtest/gtest.h>

#include "thermal/integrators/PreconditionerReuse.h"

namespace tmdem::thermal {
namespace preconditioner_reuse {

TEST(PreconditionerReuse, KeepsOnlyWithinAFactorTwoOfGammaOnTheSameNetwork) {
  PreconditionerReuse reuse(true);
  EXPECT_FALSE(reuse.may_keep(true, 1.0, 7));  // nothing factored yet
  reuse.factored(true, 1.0, 7);
  EXPECT_TRUE(reuse.may_keep(true, 1.0, 7));
  EXPECT_TRUE(reuse.may_keep(true, 1.99, 7));
  EXPECT_TRUE(reuse.may_keep(true, 0.51, 7));
  EXPECT_FALSE(reuse.may_keep(true, 2.0, 7));   // a factor 2: rebuilt
  EXPECT_FALSE(reuse.may_keep(true, 0.5, 7));
  EXPECT_FALSE(reuse.may_keep(false, 1.0, 7));  // CVODES wants new Jacobian data
  EXPECT_FALSE(reuse.may_keep(true, 1.0, 8));   // the network changed
  reuse.factored(false, 1.0, 7);                // a breakdown leaves nothing to keep
  EXPECT_FALSE(reuse.may_keep(true, 1.0, 7));
}

TEST(PreconditionerReuse, NeverKeepsWhenDisabled) {
  PreconditionerReuse reuse(false);  // pcg, klu
  reuse.factored(true, 1.0, 7);
  EXPECT_FALSE(reuse.may_keep(true, 1.0, 7));
}

}  // namespace preconditioner_reuse
}  // namespace tmdem::thermal
