// POV-Ray renders the emitted scene as it is: the image is not blank and the structure is
// framed, in 3D and in the plane.

#include "dla/models/aggregate.h"
#include "dla/models/ballistic.h"
#include "dla/models/breakdown.h"
#include "dla/models/drop.h"
#include "dla/models/eden.h"
#include "dla/models/dla.h"
#include "dla/io/pov_writer.h"
#include "dla/mesh/constraint.h"
#include "dla/mesh/text.h"
#include "dla/mesh/shapes.h"
#include "dla/mesh/surface_distance.h"
#include "mesh_util.h"
#include "png_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <vector>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

using testing::Picture;
using testing::read_png;

// Runs POV-Ray on dir/scene.pov at 160x120 with `options`, into scene.png (or, animated,
// sceneN.png); a failure that shows its log when it fails.
bool run_povray(const ScratchDir& dir, const std::string& options) {
  const std::string command = "cd '" + dir.path().string() + "' && '" + std::string(POVRAY_PATH) +
                              "' +Iscene.pov +Oscene.png +W160 +H120 -D -V " + options + " > povray.log 2>&1";
  if (std::system(command.c_str()) == 0) return true;
  ADD_FAILURE() << read_file(dir / "povray.log");
  return false;
}

// Renders dir/scene.pov (run_povray); an empty image when it fails.
Picture render(const ScratchDir& dir, const std::string& options) {
  if (!run_povray(dir, options)) return {};
  Picture image = read_png(dir / "scene.png");
  if (image.width != 160) ADD_FAILURE() << "no image: " << read_file(dir / "povray.log");
  return image;
}

// Which pixels differ from the background (the top left corner's colour).
std::vector<bool> structure_pixels(const Picture& image) {
  std::vector<bool> lit(image.width * image.height, false);
  if (image.width == 0) return lit;
  const std::array<int, 3> background = image.at(0, 0);
  for (std::size_t y = 0; y < image.height; ++y)
    for (std::size_t x = 0; x < image.width; ++x) lit[y * image.width + x] = image.at(x, y) != background;
  return lit;
}

// Writes the scene, applies `edit` to the .pov (a user's change to a switch), renders it at
// 160x120 and checks what it shows; returns the number of pixels of structure.
int expect_framed_render(const Cluster& cluster, const ScratchDir& dir, const TriangleMesh* mesh = nullptr,
                         const PovOptions& options = {}, const Look* look = nullptr,
                         const std::function<void(std::string&)>& edit = {}) {
  const std::string povray = POVRAY_PATH;
  if (povray.empty() || povray.find("NOTFOUND") != std::string::npos) {
    ADD_FAILURE() << "POV-Ray is not installed: the README's setup command installs the povray package";
    return 0;
  }
  write_pov(cluster, dir / "scene", options, mesh, look);
  if (edit) {
    std::string pov = read_file(dir / "scene.pov");
    edit(pov);
    std::ofstream(dir / "scene.pov") << pov;
  }
  const Picture image = render(dir, "+A0.3");
  if (image.width != 160) return 0;

  const std::array<int, 3> background = image.at(0, 0);
  const int width = static_cast<int>(image.width), height = static_cast<int>(image.height);
  int lit = 0, x0 = width, x1 = -1, y0 = height, y1 = -1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::array<int, 3> p = image.at(static_cast<std::size_t>(x), static_cast<std::size_t>(y));
      if (std::abs(p[0] - background[0]) + std::abs(p[1] - background[1]) + std::abs(p[2] - background[2]) < 60)
        continue;
      ++lit;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  EXPECT_GT(lit, width * height / 50) << "the image is (nearly) blank";
  EXPECT_GT(x0, 0) << "cut at the left";
  EXPECT_LT(x1, width - 1) << "cut at the right";
  EXPECT_GT(y0, 0) << "cut at the top";
  EXPECT_LT(y1, height - 1) << "cut at the bottom";
  EXPECT_GT(std::max(x1 - x0, y1 - y0), height / 2) << "too small to see";
  return lit;
}

//! Sets `#declare NAME = VALUE;` in a scene.
std::function<void(std::string&)> set(const std::string& name, const std::string& value) {
  return [=](std::string& pov) {
    const std::size_t at = pov.find("#declare " + name + " = ");
    ASSERT_NE(at, std::string::npos) << name;
    const std::size_t end = pov.find(';', at);
    pov.replace(at, end - at, "#declare " + name + " = " + value);
  };
}

// Every radius model is a switch in the .pov: each renders, in frame, and the uniform model
// (the base radius everywhere) covers more than the taper.
TEST(Render, EveryRadiusModelIsASwitchInTheScene) {
  const MeshConstraint ball(make_sphere(Vec3::Zero(), 16.0, 12, 24), {}, 1.0);
  DlaOptions o;
  o.particles = 2000;
  o.spawn = SpawnMode::inside;
  const Cluster c = grow(o, ball);
  const SurfaceDistance surface(ball.mesh());
  LookOptions options;
  options.color_by = ColorBy::depth;
  const Look look = make_look(c, options, {&surface});
  std::map<std::string, int> lit;
  for (const char* model : {"taper", "pipe", "boundary", "seed-distance", "uniform"}) {
    SCOPED_TRACE(model);
    ScratchDir dir;
    lit[model] = expect_framed_render(c, dir, nullptr, {}, &look, set("DLA_RadiusModel", std::string("\"") + model + "\""));
  }
  EXPECT_GT(lit["uniform"], lit["taper"]);
  EXPECT_GT(lit["uniform"], lit["pipe"]);
}

// The glow look: a discharge gives light on black, as bright as its current: its main channel
// as bright as the same scene with every branch at full glow, the whole darker, the sky black.
TEST(Render, AGlowingDischargeIsBrightestOnItsMainChannel) {
  DlaOptions walk;
  walk.particles = 5000;
  walk.rng_seed = 8;
  BreakdownOptions o;
  o.eta = 2.0;
  o.target.kind = TargetKind::plane;
  o.target.at = -30.0;
  const Cluster c = breakdown(walk, o, nullptr);
  ASSERT_GE(c.strike, 0);
  PovOptions glow;
  glow.style = PovStyle::glow;
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  const Look look = make_look(c, options, {});
  // The picture's summed brightness, and its brightest pixel's.
  const auto brightness = [&](const ScratchDir& dir) {
    const Picture image = read_png(dir / "scene.png");
    EXPECT_EQ(image.at(0, 0), (std::array<int, 3>{0, 0, 0}));
    std::pair<long long, int> sum_and_most{0, 0};
    for (std::size_t y = 0; y < image.height; ++y)
      for (std::size_t x = 0; x < image.width; ++x) {
        const std::array<int, 3> p = image.at(x, y);
        sum_and_most.first += p[0] + p[1] + p[2];
        sum_and_most.second = std::max(sum_and_most.second, p[0] + p[1] + p[2]);
      }
    return sum_and_most;
  };
  ScratchDir dir;  // one a test: each render is measured before the next
  expect_framed_render(c, dir, nullptr, glow, &look);
  EXPECT_NE(read_file(dir / "scene.pov").find("Brightness by current"), std::string::npos);
  const auto by_current = brightness(dir);
  expect_framed_render(c, dir, nullptr, glow, &look, set("DLA_GlowFloor", "1"));
  const auto uniform = brightness(dir);
  // The channel glows as brightly as every branch does at full glow; the side branches fade.
  EXPECT_GE(by_current.second, uniform.second * 9 / 10);
  EXPECT_LT(by_current.first, uniform.first * 4 / 5);
}

// The blob look (metaballs) renders in frame, and so does DLA_Tip at every tip, a leaf of a
// user's own here: the tips cover more of the picture than the branches alone.
TEST(Render, BlobLookAndTipsRender) {
  DlaOptions o;
  o.particles = 1200;
  const Cluster c = grow(o);
  PovOptions blob;
  blob.style = PovStyle::blob;
  {
    ScratchDir dir;
    expect_framed_render(c, dir, nullptr, blob);
    EXPECT_NE(read_file(dir / "scene.inc").find("blob {"), std::string::npos);
  }
  int plain = 0, leaves = 0;
  {
    ScratchDir dir;
    plain = expect_framed_render(c, dir);
  }
  PovOptions tips;
  tips.tips = true;
  {
    ScratchDir dir;
    leaves = expect_framed_render(c, dir, nullptr, tips, nullptr, [](std::string& pov) {
      set("DLA_ShowTips", "on")(pov);
      const std::size_t at = pov.find("  sphere { Position, min(Scale, 1.5 * DLA_TipRadius) }");
      ASSERT_NE(at, std::string::npos);
      pov.replace(at, 54, "  disc { Position, Direction, 1.5 * Scale }");
    });
  }
  EXPECT_GT(leaves, plain + plain / 10);
  // Without PREFIX_tips.inc, showing the tips stops POV-Ray with a message that says why.
  ScratchDir dir;
  write_pov(c, dir / "scene");
  std::string pov = read_file(dir / "scene.pov");
  set("DLA_ShowTips", "on")(pov);
  std::ofstream(dir / "scene.pov") << pov;
  const std::string command = "cd '" + dir.path().string() + "' && '" + std::string(POVRAY_PATH) +
                              "' +Iscene.pov +Oscene.ppm +FP +W16 +H12 -D -V > povray.log 2>&1";
  EXPECT_NE(std::system(command.c_str()), 0);
  EXPECT_NE(read_file(dir / "povray.log").find("DLA_ShowTips needs scene_tips.inc"), std::string::npos)
      << read_file(dir / "povray.log");
}

TEST(Render, PovRayShowsTheStructure3D) {
  ScratchDir dir;
  DlaOptions o;
  o.particles = 1500;
  expect_framed_render(grow(o), dir);
}

// An aggregate, a sphere of each monomer's own radius: framed, and no bigger than its
// spheres, drawn with the radius model that reads each particle's radius.
TEST(Render, PovRayShowsAnAggregatesSpheres) {
  AggregateOptions o;
  o.mode = AggregateMode::tuned;
  o.monomers = 400;
  o.sizes = MonomerSizes::lognormal;
  o.spread = 1.4;
  const Cluster aggregate = dla::aggregate(o);
  LookOptions particle;
  particle.radius.model = RadiusModel::particle;
  const Look look = make_look(aggregate, particle);
  PovOptions spheres;
  spheres.style = PovStyle::spheres;
  ScratchDir dir;
  expect_framed_render(aggregate, dir, nullptr, spheres, &look);
  const std::string scene = read_file(dir / "scene.inc") + read_file(dir / "scene_growth.inc");
  EXPECT_NE(scene.find("sphere {"), std::string::npos);
}

// DLA_Show renders the structure as it was part way: at a quarter, fewer pixels of structure,
// each of them structure in the finished picture too (branches only thicken as they grow,
// under the taper and the pipe model). Just short of 1 the scene is built from
// PREFIX_growth.inc by the scene's own code, and shows what PREFIX.inc does, up to rounding.
TEST(Render, GrowthFramesShowTheStructureAsItGrew) {
  DlaOptions o;
  o.particles = 2000;
  const Cluster c = grow(o);
  const auto count = [](const std::vector<bool>& pixels) { return std::count(pixels.begin(), pixels.end(), true); };
  for (const char* model : {"taper", "pipe"}) {
    SCOPED_TRACE(model);
    std::map<std::string, std::vector<bool>> lit;
    for (const char* show : {"0.25", "0.99999", "1"}) {
      ScratchDir dir;
      write_pov(c, dir / "scene");
      std::string pov = read_file(dir / "scene.pov");
      set("DLA_Show", show)(pov);
      set("DLA_RadiusModel", std::string("\"") + model + "\"")(pov);
      std::ofstream(dir / "scene.pov") << pov;
      lit[show] = structure_pixels(render(dir, "-A"));
    }
    std::size_t early_only = 0, differ = 0;
    for (std::size_t i = 0; i < lit["1"].size(); ++i) {
      early_only += lit["0.25"][i] && !lit["1"][i];
      differ += lit["0.99999"][i] != lit["1"][i];
    }
    EXPECT_GT(count(lit["0.25"]), 100);
    EXPECT_LT(count(lit["0.25"]), count(lit["1"]) * 3 / 4);
    EXPECT_EQ(early_only, 0u);
    EXPECT_LT(differ, lit["1"].size() / 500) << "PREFIX_growth.inc draws what PREFIX.inc does";
  }
}

// An animation follows the clock: three frames, each with more structure than the one before;
// every radius model, the blob look and the tips of the moment render part way.
TEST(Render, AnAnimationRendersGrowth) {
  DlaOptions o;
  o.particles = 1500;
  const Cluster c = grow(o);
  {
    ScratchDir dir;
    write_pov(c, dir / "scene");
    ASSERT_TRUE(run_povray(dir, "-A +KFF3"));
    std::vector<long> lit;
    for (const char* frame : {"scene1.png", "scene2.png", "scene3.png"}) {
      const std::vector<bool> pixels = structure_pixels(read_png(dir / frame));
      lit.push_back(std::count(pixels.begin(), pixels.end(), true));
    }
    EXPECT_LT(lit[0], lit[1]);
    EXPECT_LT(lit[1], lit[2]);
  }
  for (const char* model : {"taper", "pipe", "seed-distance", "uniform"}) {
    SCOPED_TRACE(model);
    ScratchDir dir;
    PovOptions options;
    options.tips = true;
    expect_framed_render(c, dir, nullptr, options, nullptr, [&](std::string& pov) {
      set("DLA_RadiusModel", std::string("\"") + model + "\"")(pov);
      set("DLA_Show", "0.6")(pov);
      set("DLA_ShowTips", "on")(pov);
    });
  }
  ScratchDir dir;
  PovOptions blob;
  blob.style = PovStyle::blob;
  expect_framed_render(c, dir, nullptr, blob, nullptr, set("DLA_Show", "0.6"));
}

TEST(Render, PovRayShowsTheStructureInTheBust) {
  DLA_NEED_BUST(path);
  const MeshConstraint constraint(read_mesh(path), {}, 0.3);
  DlaOptions o;
  o.particles = 3000;
  o.spacing = 0.3;
  o.spawn = SpawnMode::inside;
  o.seeds = constraint.place_seeds(2, o.rng_seed);
  PovOptions look;
  look.up = Axis::z;
  ScratchDir dir;
  expect_framed_render(grow(o, constraint), dir, &constraint.mesh(), look);
}

// Growth from seeds the artist chose: a painted cap, and where a rod enters.
TEST(Render, PovRayShowsGrowthFromPaintAndFromARodEntering) {
  TriangleMesh ball = make_sphere(Vec3::Zero(), 10.0);
  for (const Vec3& v : ball.vertices) ball.colors.push_back(v.z() > 6.0 ? Vec3(1, 0, 0) : Vec3(1, 1, 1));
  const MeshConstraint constraint(ball, {}, 0.4);
  const Paint red;
  const std::vector<std::vector<Vec3>> starts = {constraint.sample_surface(1, &red),
                                                 constraint.sample_intersection({make_open_can(Vec3(0, 0, 5), 2.0, 10.0)}, 1)};
  for (const std::vector<Vec3>& seeds : starts) {
    DlaOptions o;
    o.particles = 3000;
    o.spacing = 0.4;
    o.spawn = SpawnMode::surface;
    o.seeds = seeds;
    ScratchDir dir;
    expect_framed_render(grow(o, constraint), dir, &constraint.mesh());
  }
}

TEST(Render, PovRayShowsGrowthInText) {
  TextOptions words;
  words.text = "DLA";
  const TextMesh text = text_mesh(words);
  const MeshConstraint constraint(text.mesh, {}, 1.0);
  DlaOptions o;
  o.particles = 6000;
  o.spawn = SpawnMode::surface;
  o.seeds = text.glyph_seeds;
  PovOptions upright;
  upright.up = Axis::y;
  ScratchDir dir;
  expect_framed_render(grow(o, constraint), dir, &constraint.mesh(), upright);
}

// Frost over a ball: a shell of three spacings outside it.
TEST(Render, PovRayShowsGrowthOverASurface) {
  ConstraintOptions frost;
  frost.side = Side::outside;
  frost.shell = 3.0;
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 10.0), frost, 0.4);
  DlaOptions o;
  o.particles = 4000;
  o.spacing = 0.4;
  o.spawn = SpawnMode::inside;
  o.seeds = constraint.place_seeds(1, 1);
  ScratchDir dir;
  expect_framed_render(grow(o, constraint), dir, &constraint.mesh());
}

// Bourke's rotation, growth until a ball is filled, and the ball's whole surface as the start.
TEST(Render, PovRayShowsRotationFillAndSurfaceSeeds) {
  DlaOptions turning;
  turning.particles = 2000;
  turning.spawn = SpawnMode::disk;
  turning.spawn_axis = Axis::x;
  turning.rotate_axis = Axis::z;
  turning.rotate_degrees = 90.0;
  ScratchDir spiral;
  expect_framed_render(grow(turning), spiral);

  const MeshConstraint ball(make_sphere(Vec3::Zero(), 10.0), {}, 0.5);
  DlaOptions filling;
  filling.particles = 100000;
  filling.spacing = 0.5;
  filling.spawn = SpawnMode::inside;
  filling.fill = 0.3;
  filling.seeds = ball.place_seeds(1, 1);
  DlaStats stats;
  const Cluster filled = grow(filling, ball, {}, nullptr, &stats);
  EXPECT_GE(stats.filled, 0.3);
  ScratchDir full;
  expect_framed_render(filled, full, &ball.mesh());

  ConstraintOptions around;
  around.side = Side::outside;
  const MeshConstraint skin(make_sphere(Vec3::Zero(), 10.0), around, 0.5);
  DlaOptions furry;
  furry.particles = 3000;
  furry.spacing = 0.5;
  furry.seeds = skin.sample_surface(1);
  ScratchDir fur;
  expect_framed_render(grow(furry, skin), fur, &skin.mesh());
}

// POV-Ray's epsilons are absolute and it drops what lies beyond 10^7: a tiny or a huge spacing,
// or a structure far from the origin, is written scaled and shifted, and renders the same.
TEST(Render, PovRayShowsStructuresAtUnusualScales) {
  const struct {
    double spacing;
    Vec3 seed;
    const char* declares;
  } cases[] = {
      {1e-6, Vec3::Zero(), "#declare DLA_Scale = 1e+06;"},
      {1e6, Vec3::Zero(), "#declare DLA_Scale = 1e-06;"},
      {1.0, Vec3(1e8, -3e7, 5e5), "#declare DLA_Shift = <999999"},  // the structure's centre
  };
  for (const auto& c : cases) {
    SCOPED_TRACE("spacing " + std::to_string(c.spacing));
    ScratchDir dir;
    DlaOptions o;
    o.particles = 1500;
    o.spacing = c.spacing;
    o.seeds = {c.seed * c.spacing};
    expect_framed_render(grow(o), dir);
    EXPECT_NE(read_file(dir / "scene.pov").find(c.declares), std::string::npos) << read_file(dir / "scene.pov");
  }
}

TEST(Render, PovRayShowsTheStructurePlanar) {
  ScratchDir dir;
  DlaOptions o;
  o.particles = 1500;
  o.dimensions = 2;
  o.seeds = {Vec3(10, -5, 0)};
  expect_framed_render(grow(o), dir);
}

// The Eden model's clusters, on a plane lattice and a cubic one, render framed.
TEST(Render, PovRayShowsEdenClusters) {
  for (const Lattice lattice : {Lattice::hex, Lattice::cubic26}) {
    SCOPED_TRACE(std::string(to_string(lattice)));
    ScratchDir dir;
    EdenOptions o;
    o.lattice = lattice;
    o.sites = 3000;
    expect_framed_render(eden(o), dir);
  }
}

TEST(Render, PovRayShowsDropAndBallisticAggregates) {
  ScratchDir dir;
  DropOptions drops;
  drops.particles = 3000;
  drops.bias = parse_drop_bias("circle");
  expect_framed_render(drop(drops), dir);
  BallisticOptions lines;
  lines.particles = 3000;
  expect_framed_render(ballistic(lines), dir);
}

// Links are branches in the scene: they add to the picture, the growth frames draw them as the
// whole scene does once their later particle is shown, and the blob look renders them.
TEST(Render, LinksShowInTheSceneAndInItsGrowth) {
  DlaOptions o;
  o.particles = 2000;
  o.dimensions = 2;
  Cluster c = grow(o);
  const auto count = [](const std::vector<bool>& pixels) { return std::count(pixels.begin(), pixels.end(), true); };
  const auto lit_at = [&](const Cluster& cluster, const char* show, const char* style) {
    ScratchDir dir;
    PovOptions options;
    options.style = parse_word<PovStyle>(style);
    write_pov(cluster, dir / "scene", options);
    std::string pov = read_file(dir / "scene.pov");
    set("DLA_Show", show)(pov);
    std::ofstream(dir / "scene.pov") << pov;
    return structure_pixels(render(dir, "-A"));
  };
  const std::vector<bool> tree = lit_at(c, "1", "branches");
  c.links = neighbour_links(c, parse_links("4,3"));
  ASSERT_GT(c.links.size(), 50u);
  const std::vector<bool> linked = lit_at(c, "1", "branches"), grown = lit_at(c, "0.99999", "branches");
  EXPECT_GT(count(linked), count(tree) + 50) << "the links add to the picture";
  std::size_t differ = 0;
  for (std::size_t i = 0; i < linked.size(); ++i) differ += linked[i] != grown[i];
  EXPECT_LT(differ, linked.size() / 500) << "PREFIX_growth.inc draws the links PREFIX.inc does";
  EXPECT_LT(count(lit_at(c, "0.3", "branches")), count(linked) * 3 / 4);
  EXPECT_GT(count(lit_at(c, "1", "blob")), count(lit_at(c, "0.5", "blob")));
}

}  // namespace
}  // namespace dla
