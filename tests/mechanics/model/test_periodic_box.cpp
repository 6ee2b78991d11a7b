// PeriodicBox: the nearest image of a branch vector and the wrap into [low, high), by hand; a box
// without periodic axes leaves every vector as it is, bit for bit.
#include <gtest/gtest.h>

#include "mechanics/model/PeriodicBox.h"

using tmdem::mechanics::PeriodicBox;
using Eigen::Vector3d;

namespace {

PeriodicBox xz_box() {  // x in [0, 10) mm, z in [-2, 3) mm, y open
  PeriodicBox box;
  box.periodic = {true, false, true};
  box.low = Vector3d(0.0, 0.0, -2e-3);
  box.high = Vector3d(10e-3, 0.0, 3e-3);
  return box;
}

}  // namespace

TEST(PeriodicBox, NoPeriodicAxisChangesNothing) {
  const PeriodicBox box;
  EXPECT_FALSE(box.any());
  const Vector3d d(123.456, -7e-3, 1e300);
  EXPECT_EQ(box.minimum_image(d), d);
  EXPECT_EQ(box.wrap(d), d);
}

TEST(PeriodicBox, MinimumImageIsTheNearestOfTheImages) {
  const PeriodicBox box = xz_box();
  EXPECT_TRUE(box.any());
  EXPECT_DOUBLE_EQ(box.length(0), 10e-3);
  EXPECT_DOUBLE_EQ(box.length(2), 5e-3);
  // 0.5 mm and 8.4 mm apart along x: 7.9 mm one way, 2.1 mm the other way round.
  const Vector3d d = box.minimum_image(Vector3d(0.5e-3 - 8.4e-3, 7.0, 2.9e-3 - (-1.9e-3)));
  EXPECT_NEAR(d.x(), 2.1e-3, 1e-17);
  EXPECT_EQ(d.y(), 7.0);                 // open axis: untouched
  EXPECT_NEAR(d.z(), 4.8e-3 - 5e-3, 1e-17);
  // Within half a period: untouched, bit for bit.
  const Vector3d near(4.9e-3, -1.0, -2.4e-3);
  EXPECT_EQ(box.minimum_image(near), near);
  // Several periods away: still the nearest image.
  EXPECT_NEAR(box.minimum_image(Vector3d(31e-3, 0, 0)).x(), 1e-3, 1e-17);
}

TEST(PeriodicBox, WrapMovesByWholePeriodsIntoTheBox) {
  const PeriodicBox box = xz_box();
  const Vector3d x = box.wrap(Vector3d(10.25e-3, 5.0, -2.5e-3));
  EXPECT_NEAR(x.x(), 0.25e-3, 1e-17);
  EXPECT_EQ(x.y(), 5.0);
  EXPECT_NEAR(x.z(), 2.5e-3, 1e-17);
  EXPECT_NEAR(box.wrap(Vector3d(-25.5e-3, 0, 0)).x(), 4.5e-3, 1e-17);
  // high itself is low's image; a point inside is untouched.
  EXPECT_EQ(box.wrap(Vector3d(10e-3, 0, 0)).x(), 0.0);
  const Vector3d inside(9.999e-3, 1.0, 2.999e-3);
  EXPECT_EQ(box.wrap(inside), inside);
  // Just below low: rounding must not leave it at high.
  const double below = box.wrap(Vector3d(-1e-20, 0, 0)).x();
  EXPECT_GE(below, 0.0);
  EXPECT_LT(below, 10e-3);
}
