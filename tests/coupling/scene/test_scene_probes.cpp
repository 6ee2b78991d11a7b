// [[probe]] tables (coupling/scene/SceneProbes.cpp): a sphere (radius) or a box around a point,
// read in file order; the errors name probe[k].key and the bad value.
#include <gtest/gtest.h>

#include <string>

#include "coupling/scene/SceneSchema.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {

TEST(SceneProbes, SphereAndBoxAreReadInFileOrder) {
  const std::string text = kBaseScene +
                           "\n[[probe]]\nname = \"centre\"\npoint = [0.001, 0.001, 0.0]\n"
                           "radius = 0.0015\n"
                           "\n[[probe]]\nname = \"right\"\npoint = [0.002, 0.001, 0.0]\n"
                           "box = [0.001, 0.002, 0.003]\n";
  const Scene scene = load_scene_text(text, "test.toml");
  ASSERT_EQ(scene.probes.size(), 2u);
  EXPECT_EQ(scene.probes[0].name, "centre");
  EXPECT_FALSE(scene.probes[0].is_box());
  EXPECT_EQ(scene.probes[0].radius_m, 0.0015);
  EXPECT_EQ(scene.probes[0].point_m, (std::array<double, 3>{0.001, 0.001, 0.0}));
  EXPECT_EQ(scene.probes[1].name, "right");
  EXPECT_TRUE(scene.probes[1].is_box());
  EXPECT_EQ(scene.probes[1].box_m, (std::array<double, 3>{0.001, 0.002, 0.003}));
  EXPECT_TRUE(load_scene_text(kBaseScene, "test.toml").probes.empty());
}

TEST(SceneProbes, ErrorsNameTheKeyAndTheValue) {
  const auto probe = [](const std::string& body) { return kBaseScene + "\n[[probe]]\n" + body; };
  const std::string point = "point = [0.0, 0.001, 0.0]\n";
  expect_scene_error(probe(point + "radius = 0.001\n"), {"probe[0].name", "required"});
  expect_scene_error(probe("name = \"a\"\nradius = 0.001\n"), {"probe[0].point", "required"});
  expect_scene_error(probe("name = \"a\"\n" + point), {"probe[0].radius", "box"});
  expect_scene_error(probe("name = \"a\"\n" + point + "radius = -0.5\n"),
                     {"probe[0].radius", "> 0", "-0.5"});
  expect_scene_error(probe("name = \"a\"\n" + point + "radius = 0.001\nbox = [1.0, 1.0, 1.0]\n"),
                     {"probe[0].box", "not both"});
  expect_scene_error(probe("name = \"a\"\n" + point + "box = [0.001, 0.0, 0.001]\n"),
                     {"probe[0].box", "> 0", "[0.001, 0, 0.001]"});
  expect_scene_error(probe("name = \"a\"\n" + point + "box = [0.001, 0.001]\n"),
                     {"probe[0].box", "3 numbers", "2 elements"});
  expect_scene_error(probe("name = \"a\"\n" + point + "radius = 0.001\ndiameter = 2\n"),
                     {"probe[0].diameter", "unknown key", "name, point, radius, box"});
  expect_scene_error(probe("name = \"\"\n" + point + "radius = 0.001\n"),
                     {"probe[0].name", "must not be empty"});
  expect_scene_error(probe("name = \"a\"\n" + point + "radius = 0.001\n\n[[probe]]\nname = \"a\"\n" +
                           point + "radius = 0.002\n"),
                     {"probe[1].name", "unique", "\"a\""});
  expect_scene_error(probe("name = 3\n" + point + "radius = 0.001\n"), {"probe[0].name", "string"});
}

TEST(SceneProbes, SchemaListsTheTableForTheReference) {
  ASSERT_NE(SceneSchema::find("", "probe"), nullptr);
  EXPECT_EQ(SceneSchema::find("", "probe")->kind, SceneSchema::Kind::TableArray);
  EXPECT_EQ(SceneSchema::key_list("probe"), "name, point, radius, box");
}

}  // namespace tmdem::coupling::test
