// Particle ids, the deterministic generators and [[assign]].
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "coupling/scene/SceneGenerators.h"
#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// 2D, 1 s; steel and glass.
SceneBuilder header() { return steel_scene().set("simulation.dimension", 2).add("material", glass()); }

double distance(const Vec3& a, const Vec3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

TEST(SceneGenerators, IdsExplicitParticlesFirstThenGeneratorsInFileOrder) {
  // [[generate]] entries appear before the [[particle]] entries in the file.
  const std::string text =
      header()
          .add("generate", column(2, {{"origin", {0.1, 0.001, 0.0}}}))
          .add("particle", particle({0.0, 0.001, 0.0}, {{"radius", 0.002}, {"material", "glass"}}))
          .add("generate", column(3, {{"origin", {0.2, 0.001, 0.0}}, {"material", "glass"}, {"temperature", 310.0}}))
          .add("particle", particle({0.05, 0.001, 0.0}, {{"radius", 0.003}}));
  const Scene scene = load_scene_text(text, "t");
  ASSERT_EQ(scene.particles.size(), 7u);
  EXPECT_EQ(scene.particles[0].radius_m, 0.002);
  EXPECT_EQ(scene.particles[1].radius_m, 0.003);
  EXPECT_EQ(scene.particles[2].position_m[0], 0.1);
  EXPECT_EQ(scene.particles[3].position_m[0], 0.1);
  for (int i = 4; i < 7; ++i) {
    EXPECT_EQ(scene.particles[i].position_m[0], 0.2);
    EXPECT_EQ(scene.particles[i].material, 1);
    EXPECT_EQ(scene.particles[i].temperature_K, 310.0);
  }
  EXPECT_EQ(scene.particles[2].temperature_K, 293.15);
}

TEST(SceneGenerators, TriangularPaperRows) {
  const double r = 0.001;
  const std::string text = header().add("generate", triangular({5, 4, 3, 2}));
  const Scene scene = load_scene_text(text, "t");
  ASSERT_EQ(scene.particles.size(), 14u);
  // Bottom row: origin, spacing 2 r along x.
  EXPECT_DOUBLE_EQ(scene.particles[0].position_m[0], 0.001);
  EXPECT_DOUBLE_EQ(scene.particles[0].position_m[1], 0.001);
  EXPECT_DOUBLE_EQ(scene.particles[4].position_m[0], 0.009);
  // Second row starts at origin + (r, sqrt(3) r); top row is centred on the bottom row.
  EXPECT_NEAR(scene.particles[5].position_m[0], 0.002, 1e-15);
  EXPECT_NEAR(scene.particles[5].position_m[1], 0.001 + std::sqrt(3.0) * r, 1e-15);
  EXPECT_NEAR((scene.particles[12].position_m[0] + scene.particles[13].position_m[0]) / 2, 0.005,
              1e-15);
  // Every particle touches its neighbours exactly; none overlap.
  int contacts = 0;
  for (std::size_t i = 0; i < 14; ++i)
    for (std::size_t j = i + 1; j < 14; ++j) {
      const double d = distance(scene.particles[i].position_m, scene.particles[j].position_m);
      EXPECT_GE(d, 2 * r * (1 - 1e-12));
      if (std::abs(d - 2 * r) <= 2 * r * 1e-12) ++contacts;
      EXPECT_EQ(scene.particles[i].position_m[2], 0.0);
    }
  // Rows: 4 + 3 + 2 + 1 within rows, 8 + 6 + 4 between rows.
  EXPECT_EQ(contacts, 10 + 18);
}

TEST(SceneGenerators, TriangularEqualRowsStackStraight) {
  const auto positions = triangular_positions({3, 3}, 1.0, {0.0, 0.0, 0.0});
  ASSERT_EQ(positions.size(), 6u);
  EXPECT_DOUBLE_EQ(positions[3][0], 0.0);
  EXPECT_DOUBLE_EQ(positions[3][1], 2.0);
}

TEST(SceneGenerators, ColumnGoesAgainstGravity) {
  const std::string text = header().add("generate", column(4));
  const Scene up = load_scene_text(text, "t");
  ASSERT_EQ(up.particles.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(up.particles[i].position_m[0], 0.0);
    EXPECT_NEAR(up.particles[i].position_m[1], 0.001 + 0.002 * i, 1e-15);
  }
  const Scene down = load_scene_text(text, "t", {"simulation.gravity=[0, 9.81, 0]"});
  EXPECT_NEAR(down.particles[3].position_m[1], 0.001 - 0.006, 1e-15);
  const Scene sideways = load_scene_text(text, "t", {"simulation.gravity=[-1, 0, 0]"});
  EXPECT_NEAR(sideways.particles[3].position_m[0], 0.006, 1e-15);
}

TEST(SceneGenerators, LatticeSimpleCubicXFastest) {
  const std::string text = header().add(
      "generate", lattice({3, 2, 2}, {{"spacing", 0.0025}, {"origin", {0.0, 0.0, 0.0}}, {"material", "glass"}}));
  const Scene scene = load_scene_text(text, "t", {"simulation.dimension=3"});
  ASSERT_EQ(scene.particles.size(), 12u);
  EXPECT_NEAR(scene.particles[1].position_m[0], 0.0025, 1e-15);
  EXPECT_NEAR(scene.particles[3].position_m[1], 0.0025, 1e-15);
  EXPECT_NEAR(scene.particles[6].position_m[2], 0.0025, 1e-15);
  EXPECT_NEAR(scene.particles[11].position_m[0], 0.005, 1e-15);
  EXPECT_EQ(scene.particles[11].material, 1);
}

TEST(SceneGenerators, GeneratorOptionalSettings) {
  const std::string text = header().add(
      "generate", column(2, {{"temperature", 400.0}, {"fixed_temperature", true}, {"heat_source", 0.5}, {"fixed", true}}));
  const Scene scene = load_scene_text(text, "t");
  for (const auto& p : scene.particles) {
    EXPECT_EQ(p.temperature_K, 400.0);
    EXPECT_TRUE(p.fixed_temperature);
    EXPECT_EQ(p.heat_source_W, 0.5);
    EXPECT_TRUE(p.fixed);
  }
}

// 50 spheres of two sizes in a 20 mm square.
TomlKeys random_in_square(std::string box) {
  return random_fill(50, std::move(box), {{"radii", {0.0005, 0.001}}, {"fractions", {0.6, 0.4}}});
}
const std::string kRandom =
    header().add("generate", random_in_square("{ min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.0] }"));

TEST(SceneGenerators, RandomIsReproducibleAndInsideTheBox) {
  const Scene a = load_scene_text(kRandom, "t");
  const Scene b = load_scene_text(kRandom, "t");
  ASSERT_EQ(a.particles.size(), 50u);
  int small = 0;
  for (std::size_t i = 0; i < 50; ++i) {
    const Particle& p = a.particles[i];
    EXPECT_EQ(p.position_m, b.particles[i].position_m);
    EXPECT_GE(p.position_m[0] - p.radius_m, 0.0);
    EXPECT_LE(p.position_m[0] + p.radius_m, 0.02);
    EXPECT_GE(p.position_m[1] - p.radius_m, 0.0);
    EXPECT_LE(p.position_m[1] + p.radius_m, 0.02);
    EXPECT_EQ(p.position_m[2], 0.0);
    if (p.radius_m == 0.0005) ++small;
  }
  EXPECT_EQ(small, 30);
  const Scene other = load_scene_text(kRandom, "t", {"simulation.seed=2"});
  EXPECT_NE(other.particles[0].position_m, a.particles[0].position_m);
}

TEST(SceneGenerators, RandomGeneratorsDrawDifferentPlacements) {
  const std::string text =
      header()
          .add("generate", random_in_square("{ min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.0] }"))
          .add("generate", random_in_square("{ min = [0.1, 0.0, 0.0], max = [0.12, 0.02, 0.0] }"));
  const Scene scene = load_scene_text(text, "t");
  ASSERT_EQ(scene.particles.size(), 100u);
  int same = 0;
  for (std::size_t i = 0; i < 50; ++i)
    if (std::abs(scene.particles[50 + i].position_m[0] - 0.1 - scene.particles[i].position_m[0]) <
        1e-12)
      ++same;
  EXPECT_LT(same, 50);
}

// A random fill keeps clear of [[particle]] entries too (read before the generators): a 4 mm
// disk in the middle of the 20 mm square covers 13% of it, so 50 disks placed without it
// would overlap it (and the scene would be refused for the overlap).
TEST(SceneGenerators, RandomFillKeepsClearOfHandPlacedParticles) {
  const std::string text =
      header()
          .add("generate", random_in_square("{ min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.0] }"))
          .add("particle", particle({0.01, 0.01, 0.0}, {{"radius", 0.004}}));
  const Scene scene = load_scene_text(text, "t");
  ASSERT_EQ(scene.particles.size(), 51u);
  const Particle& big = scene.particles[0];
  ASSERT_EQ(big.radius_m, 0.004);
  for (std::size_t i = 1; i < 51; ++i) {
    const double d = distance(scene.particles[i].position_m, big.position_m);
    EXPECT_GE(d, big.radius_m + scene.particles[i].radius_m) << "particle " << i;
  }
  // The same fill without the disk puts some of its particles where the disk is.
  const Scene alone = load_scene_text(kRandom, "t");
  int inside = 0;
  for (const auto& p : alone.particles)
    if (distance(p.position_m, big.position_m) < big.radius_m + p.radius_m) ++inside;
  EXPECT_GT(inside, 0);
}

TEST(SceneGenerators, RandomSingleRadiusThreeD) {
  const std::string text = header().add(
      "generate", random_fill(20, "{ min = [0.0, 0.0, 0.0], max = [0.01, 0.01, 0.01] }",
                              {{"radius", 0.001}, {"material", "glass"}}));
  const Scene scene = load_scene_text(text, "t", {"simulation.dimension=3"});
  ASSERT_EQ(scene.particles.size(), 20u);
  for (const auto& p : scene.particles) {
    EXPECT_EQ(p.radius_m, 0.001);
    EXPECT_EQ(p.material, 1);
    for (int d = 0; d < 3; ++d) {
      EXPECT_GE(p.position_m[d], 0.001);
      EXPECT_LE(p.position_m[d], 0.009);
    }
  }
}

TEST(SceneGenerators, RandomBoxTooFull) {
  expect_scene_error(kRandom, {"generate[0].box.max=[0.004, 0.004, 0.0]"},
                     {"generate[0]", "random placement failed"});
  expect_scene_error(kRandom, {"generate[0].box.max=[0.0015, 0.02, 0.0]"},
                     {"generate[0].box", "too small"});
}

// Random generators keep clear of the particles placed before them ([[particle]] entries and
// earlier generators), so several fill one box (they used to overlap and be refused).
TEST(SceneGenerators, RandomKeepsClearOfOtherParticles) {
  const std::string text =
      header()
          .add("generate", random_in_square("{ min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.0] }"))
          .add("generate", random_in_square("{ min = [0.0, 0.0, 0.0], max = [0.02, 0.02, 0.0] }"))
          .add("particle", particle({0.01, 0.01, 0.0}, {{"radius", 0.004}}));
  const Scene scene = load_scene_text(text, "t");
  ASSERT_GT(scene.particles.size(), 2u);
  for (std::size_t a = 0; a < scene.particles.size(); ++a) {
    for (std::size_t b = a + 1; b < scene.particles.size(); ++b) {
      const auto& p = scene.particles[a];
      const auto& q = scene.particles[b];
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) d2 += (p.position_m[k] - q.position_m[k]) * (p.position_m[k] - q.position_m[k]);
      EXPECT_GE(std::sqrt(d2), p.radius_m + q.radius_m) << a << " " << b;
    }
  }
}

// kind = "deposit": 40 steel and 40 glass spheres dropped into one 3D box under gravity -y.
std::string deposit_scene(const std::string& gravity = "[0.0, -9.81, 0.0]",
                          const std::string& second_box = "{ min = [0.0, 0.0, 0.0], max = [0.008, 0.03, 0.008] }") {
  return header()
      .set("simulation.dimension", 3)
      .set("simulation.gravity", raw(gravity))
      .add("generate", with(random_fill(40, "{ min = [0.0, 0.0, 0.0], max = [0.008, 0.03, 0.008] }",
                                        {{"radii", {0.0005, 0.001}}, {"fractions", {0.5, 0.5}}}),
                            {{"kind", "deposit"}}))
      .add("generate", with(random_fill(40, second_box, {{"radius", 0.0007}, {"material", "glass"}}),
                            {{"kind", "deposit"}}));
}

TEST(SceneGenerators, DepositLaysARestingBedOnTheFloorOfItsBox) {
  const Scene scene = load_scene_text(deposit_scene(), "t");
  ASSERT_EQ(scene.particles.size(), 80u);
  std::size_t on_floor = 0;
  double lowest_glass = 1.0, highest_steel = 0.0;
  for (std::size_t a = 0; a < 80; ++a) {
    const Particle& p = scene.particles[a];
    EXPECT_EQ(p.material, a < 40 ? 0 : 1);
    EXPECT_GE(p.position_m[1] - p.radius_m, -1e-15);
    for (const int d : {0, 2}) {
      EXPECT_GE(p.position_m[d] - p.radius_m, -1e-15);
      EXPECT_LE(p.position_m[d] + p.radius_m, 0.008 + 1e-15);
    }
    if (std::abs(p.position_m[1] - p.radius_m) < 1e-15) ++on_floor;
    bool touches = std::abs(p.position_m[1] - p.radius_m) < 1e-15;
    for (std::size_t b = 0; b < 80; ++b) {
      if (b == a) continue;
      const double gap = distance(p.position_m, scene.particles[b].position_m) - p.radius_m -
                         scene.particles[b].radius_m;
      EXPECT_GT(gap, -1e-15) << a << " " << b;
      touches = touches || gap < 1e-12;
    }
    EXPECT_TRUE(touches) << "particle " << a << " hangs in the air";
    (a < 40 ? highest_steel : lowest_glass) =
        a < 40 ? std::max(highest_steel, p.position_m[1]) : std::min(lowest_glass, p.position_m[1]);
  }
  EXPECT_GT(on_floor, 10u);
  // The two entries share the box, so they are dropped together: glass lies below steel's top.
  EXPECT_LT(lowest_glass, highest_steel);
  // Reproducible; another seed lays another bed.
  EXPECT_EQ(load_scene_text(deposit_scene(), "t").particles[7].position_m, scene.particles[7].position_m);
  EXPECT_NE(load_scene_text(deposit_scene(), "t", {"simulation.seed=5"}).particles[7].position_m,
            scene.particles[7].position_m);
}

TEST(SceneGenerators, DepositsInDifferentBoxesAreLaidOneAfterTheOther) {
  // The glass entry's box differs (higher top): it is laid after the steel one, on top of it.
  const Scene scene = load_scene_text(
      deposit_scene("[0.0, -9.81, 0.0]", "{ min = [0.0, 0.0, 0.0], max = [0.008, 0.04, 0.008] }"), "t");
  double mean_steel = 0.0, mean_glass = 0.0;  // m, mean heights
  for (std::size_t a = 0; a < 80; ++a) (a < 40 ? mean_steel : mean_glass) += scene.particles[a].position_m[1] / 40;
  EXPECT_GT(mean_glass, 1.5 * mean_steel);
  // Filled together, they are mixed.
  const Scene mixed = load_scene_text(deposit_scene(), "t");
  double mixed_steel = 0.0, mixed_glass = 0.0;
  for (std::size_t a = 0; a < 80; ++a) (a < 40 ? mixed_steel : mixed_glass) += mixed.particles[a].position_m[1] / 40;
  EXPECT_LT(std::abs(mixed_glass - mixed_steel), 0.25 * mixed_steel);
}

TEST(SceneGenerators, DepositNeedsGravityAlongAnAxisAndRoom) {
  expect_scene_error(deposit_scene("[0.0, 0.0, 0.0]"), {}, {"generate[0].kind", "along gravity"});
  expect_scene_error(deposit_scene("[1.0, -9.81, 0.0]"), {}, {"generate[0].kind", "along gravity"});
  expect_scene_error(deposit_scene(), {"generate[0].box.max=[0.008, 0.004, 0.008]"},
                     {"generate[0].box", "too low"});
  // Gravity along +x works as well: the floor is then the box's face x = max.
  const Scene sideways = load_scene_text(deposit_scene("[9.81, 0.0, 0.0]"), "t");
  for (const auto& p : sideways.particles) EXPECT_LE(p.position_m[0] + p.radius_m, 0.008 + 1e-15);
}

// A box-filling generator places by its box alone: a deposit given the bounding square of a
// cylinder puts its corner spheres through the cylinder's wall. The error says so, and how wide
// a square fits: (R - r) / sqrt(2) for the sphere it names.
TEST(SceneGenerators, ABoxReachingThroughACylinderWallIsRefusedWithTheSquareThatFits) {
  const std::string cylinder =
      "\n[[wall]]\nshape = \"cylinder\"\npoint = [0.004, 0.0, 0.004]\naxis = [0.0, 1.0, 0.0]\n"
      "radius = 0.004\nmaterial = \"steel\"\n";
  const std::string error = scene_error(deposit_scene() + cylinder);
  EXPECT_NE(error.find("and wall[0] overlap at start"), std::string::npos) << error;
  EXPECT_NE(error.find("generate[0] places its particles by its box alone, not by the walls"), std::string::npos)
      << error;
  // The named particle's radius decides the square.
  bool figure = false;
  for (const double r : {0.0005, 0.001}) {
    std::ostringstream expected;  // six significant digits
    expected << "spheres of radius " << r << " m fit in a square of half-width " << (0.004 - r) / std::sqrt(2.0) << " m";
    figure = figure || error.find(expected.str()) != std::string::npos;
  }
  EXPECT_TRUE(figure) << error;
  // Inside that square (half-width 2.12 mm for the 1 mm spheres) the deposit loads.
  const std::string inside = "{ min = [0.0019, 0.0, 0.0019], max = [0.0061, 0.03, 0.0061] }";
  EXPECT_NO_THROW(load_scene_text(deposit_scene("[0.0, -9.81, 0.0]", inside) + cylinder, "t",
                                  {"generate[0].box=" + inside}));
}

TEST(SceneGenerators, DepositFillsAPeriodicBoxAcrossItsSides) {
  // Periodic along x and z: the spheres rest on each other round the sides (a pair closer than
  // the period's half apart only through the boundary) and the box must span the periods.
  const std::string text = header()
                               .set("simulation.dimension", 3)
                               .set("simulation.gravity", raw("[0.0, -9.81, 0.0]"))
                               .set("periodic.x", raw("[0.0, 0.01]"))
                               .set("periodic.z", raw("[0.0, 0.01]"))
                               .add("generate", with(random_fill(150, "{ min = [0.0, 0.0, 0.0], max = [0.01, 0.03, 0.01] }",
                                                                 {{"radius", 0.0006}}),
                                                     {{"kind", "deposit"}}))
                               .str();
  const Scene scene = load_scene_text(text, "t");
  ASSERT_EQ(scene.particles.size(), 150u);
  int across = 0;
  for (std::size_t a = 0; a < 150; ++a) {
    const auto& p = scene.particles[a].position_m;
    EXPECT_TRUE(p[0] >= 0.0 && p[0] < 0.01 && p[2] >= 0.0 && p[2] < 0.01) << a;
    for (std::size_t b = a + 1; b < 150; ++b) {
      const auto& q = scene.particles[b].position_m;
      double d2 = (p[1] - q[1]) * (p[1] - q[1]);
      bool wrapped = false;
      for (const int k : {0, 2}) {
        double d = p[k] - q[k];
        if (std::abs(d) > 0.005) {
          d -= std::copysign(0.01, d);
          wrapped = true;
        }
        d2 += d * d;
      }
      EXPECT_GT(std::sqrt(d2), 0.0012 * (1.0 - 1e-12)) << a << " " << b;
      if (wrapped && std::sqrt(d2) < 0.0012 * (1.0 + 1e-9)) ++across;
    }
  }
  EXPECT_GT(across, 5);
  expect_scene_error(text, {"generate[0].box.max=[0.009, 0.03, 0.01]"},
                     {"generate[0].box", "must span the period"});
}

// 4 x 4 touching steel spheres in the plane z = 0.
SceneBuilder lattice_for_assign() {
  return header().add("generate", lattice({4, 4, 1}, {{"origin", {0.001, 0.001, 0.0}}}));
}

TEST(SceneAssign, ById) {
  const std::string text = lattice_for_assign().add(
      "assign", assign_ids({0, 5}, {{"temperature", 373.15},
                                    {"fixed_temperature", true},
                                    {"heat_source", 2.0},
                                    {"fixed", true},
                                    {"material", "glass"}}));
  const Scene scene = load_scene_text(text, "t");
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    const bool chosen = i == 0 || i == 5;
    const Particle& p = scene.particles[i];
    EXPECT_EQ(p.temperature_K, chosen ? 373.15 : 293.15) << i;
    EXPECT_EQ(p.fixed_temperature, chosen);
    EXPECT_EQ(p.heat_source_W, chosen ? 2.0 : 0.0);
    EXPECT_EQ(p.fixed, chosen);
    EXPECT_EQ(p.material, chosen ? 1 : 0);
  }
}

TEST(SceneAssign, ByBoxInFileOrder) {
  const std::string text =
      lattice_for_assign()
          .add("assign", {{"box", raw("{ min = [0.0, 0.0, -1.0], max = [0.004, 0.004, 1.0] }")},
                          {"temperature", 350.0}})
          .add("assign", assign_ids({0}, {{"temperature", 360.0}}));
  const Scene scene = load_scene_text(text, "t");
  // Centres inside the box: (1,1), (3,1), (1,3), (3,3) mm -> ids 0, 1, 4, 5; later assign wins.
  std::set<std::size_t> hot;
  for (std::size_t i = 0; i < scene.particles.size(); ++i)
    if (scene.particles[i].temperature_K > 300.0) hot.insert(i);
  EXPECT_EQ(hot, (std::set<std::size_t>{0, 1, 4, 5}));
  EXPECT_EQ(scene.particles[0].temperature_K, 360.0);
  EXPECT_EQ(scene.particles[5].temperature_K, 350.0);
}

TEST(SceneAssign, ByNearest) {
  const std::string text = lattice_for_assign().add(
      "assign", {{"nearest", raw("{ point = [0.0085, 0.0, 0.0], count = 3 }")}, {"temperature", 373.15}});
  const Scene scene = load_scene_text(text, "t");
  // Nearest to (8.5, 0) mm: (7,1) id 3, then (5,1) id 2 and (7,3) id 7.
  std::set<std::size_t> hot;
  for (std::size_t i = 0; i < scene.particles.size(); ++i)
    if (scene.particles[i].temperature_K > 300.0) hot.insert(i);
  EXPECT_EQ(hot, (std::set<std::size_t>{2, 3, 7}));
}

}  // namespace
}  // namespace tmdem::coupling::test
