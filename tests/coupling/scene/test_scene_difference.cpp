// first_scene_difference: what a restart compares between the checkpoint's scene and the new one.
#include <gtest/gtest.h>

#include "coupling/scene/SceneDifference.h"
#include "coupling/scene/SceneError.h"

using tmdem::coupling::first_scene_difference;

namespace {
const std::string kBase =
    "format = \"tmdem-scene-1\"\n"
    "[simulation]\nduration = 10.0\ngravity = [0.0, -9.81, 0.0]\n"
    "[thermal]\nconstant_conductance = 0.001\n"
    "[output]\nfile = \"a.h5\"\ninterval = 0.5\n"
    "[[generate]]\nkind = \"lattice\"\nradius = 0.001\n"
    "[[generate]]\nkind = \"lattice\"\nradius = 0.002\n";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}
}  // namespace

TEST(SceneDifference, IdenticalScenesAgree) {
  EXPECT_FALSE(first_scene_difference(kBase, kBase).has_value());
}

TEST(SceneDifference, DurationAndOutputMayChange) {
  std::string after = replaced(kBase, "duration = 10.0", "duration = 25.0");
  after = replaced(after, "file = \"a.h5\"\ninterval = 0.5", "file = \"b.h5\"\ninterval = 0.1\ncheckpoint_interval = 2.0");
  EXPECT_FALSE(first_scene_difference(kBase, after).has_value());
}

TEST(SceneDifference, NamesTheChangedKeyWithBothValues) {
  const auto d = first_scene_difference(
      kBase, replaced(kBase, "constant_conductance = 0.001", "constant_conductance = 1.0"));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->key, "thermal.constant_conductance");
  EXPECT_EQ(d->before_value, "0.001");
  EXPECT_EQ(d->after_value, "1.0");
}

TEST(SceneDifference, NamesTheEntryOfAnArrayOfTables) {
  const auto d = first_scene_difference(kBase, replaced(kBase, "radius = 0.002", "radius = 0.003"));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->key, "generate[1].radius");
}

TEST(SceneDifference, AnAddedKeyOrSectionIsADifference) {
  auto d = first_scene_difference(kBase, kBase + "[effects]\nconvection = true\n");
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->key, "effects");
  EXPECT_EQ(d->before_value, "(absent)");
  d = first_scene_difference(kBase, replaced(kBase, "[thermal]\n", "[thermal]\nintegrator = \"ida\"\n"));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->key, "thermal.integrator");
  EXPECT_EQ(d->after_value, "\"ida\"");
}

TEST(SceneDifference, PlainArraysCompareAsAWhole) {
  const auto d = first_scene_difference(kBase, replaced(kBase, "-9.81", "-9.8"));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->key, "simulation.gravity");
  EXPECT_EQ(d->before_value, "[0.0, -9.81, 0.0]");
}

TEST(SceneDifference, InvalidTextIsASceneError) {
  EXPECT_THROW(first_scene_difference(kBase, "[[x"), tmdem::coupling::SceneError);
}
