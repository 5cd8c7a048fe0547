// dla3d's files in the programs artists open them with: Debian's Blender imports the .glb, the
// .obj and the .ply with the counts and bounds written, and the Khronos glTF-Validator finds no
// error in the .glb, and Chromium opens the web viewer. Each test skips, by name, when its client is missing (tests/clients.h).

#include "cli_util.h"
#include "clients.h"
#include "mesh_util.h"
#include "png_util.h"
#include "dla/mesh/shapes.h"
#include "dla/models/dla.h"
#include "dla/models/links.h"
#include "dla/io/leaf.h"
#include "dla/io/mesh_writers.h"
#include "dla/io/ply_writer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

struct Imported {
  long objects = -1, vertices = -1, edges = -1, faces = -1;
  std::array<double, 3> min{}, max{};
  std::array<double, 4> uv{};  //!< the UV map's u min, v min, u max, v max; NaN without one
  std::string attributes;
};

//! The number after `"key": ` in Blender's JSON line.
double field(const std::string& line, const std::string& key, std::size_t skip = 0) {
  std::size_t at = line.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  at += key.size() + 4;
  if (line[at] == '[') {
    ++at;
    for (std::size_t k = 0; k < skip; ++k) at = line.find(',', at) + 1;
  }
  return std::atof(line.c_str() + at);
}

//! Imports `file` (in `dir`) into Blender and reads back what it made.
Imported blender_import(const ScratchDir& dir, const std::string& file) {
  const std::string command = "cd '" + dir.path().string() + "' && blender -b --factory-startup --python-exit-code 1 "
                              "--python '" TEST_CLIENTS_DIR "/blender_import.py' -- '" + file + "' > blender.txt 2>&1";
  const int status = std::system(command.c_str());
  const std::string log = read_file(dir / "blender.txt");
  EXPECT_EQ(status, 0) << log;
  const std::size_t at = log.find("DLA3D ");
  Imported imported;
  if (at == std::string::npos) {
    ADD_FAILURE() << "Blender printed no result:\n" << log;
    return imported;
  }
  const std::string line = log.substr(at, log.find('\n', at) - at);
  imported.objects = static_cast<long>(field(line, "objects"));
  imported.vertices = static_cast<long>(field(line, "vertices"));
  imported.edges = static_cast<long>(field(line, "edges"));
  imported.faces = static_cast<long>(field(line, "faces"));
  for (std::size_t a = 0; a < 3; ++a) {
    imported.min[a] = field(line, "min", a);
    imported.max[a] = field(line, "max", a);
  }
  for (std::size_t k = 0; k < 4; ++k) imported.uv[k] = field(line, "uv", k);
  imported.attributes = line.substr(line.find("\"attributes\""));
  return imported;
}

struct Tubes {
  std::size_t vertices = 0, triangles = 0, edges = 0;
  Eigen::Vector3f min = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()), max = -min;
  float v_max = 0.0f;  //!< the largest texture v
};

Tubes tubes_of(const Cluster& c, const Look& look) {
  Tubes t;
  for_each_tube(c, look.attributes, look.radii, look.options.tubes, [&](const TubePiece& piece) {
    t.vertices += piece.positions.size();
    t.triangles += piece.triangles.size();
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;  // by index: the seam is an edge twice
    for (const auto& triangle : piece.triangles)
      for (std::size_t k = 0; k < 3; ++k)
        edges.insert(std::minmax(triangle[k], triangle[(k + 1) % 3]));
    t.edges += edges.size();
    for (const Eigen::Vector3f& p : piece.positions) {
      t.min = t.min.cwiseMin(p);
      t.max = t.max.cwiseMax(p);
    }
    for (const Eigen::Vector2f& uv : piece.uvs) t.v_max = std::max(t.v_max, uv.y());
  });
  return t;
}

Cluster sample() {
  DlaOptions o;
  o.particles = 1500;
  o.rng_seed = 3;
  o.seeds = {Vec3(-6, 0, 0), Vec3(6, 0, 0)};
  return grow(o);
}

TEST(Blender, ImportsTheTubeMeshesAndThePly) {
  DLA_NEED_BLENDER();
  ScratchDir dir;
  const Cluster c = sample();
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  options.color_by = ColorBy::age;
  const Look look = make_look(c, options);
  write_glb(c, look, dir / "tree.glb");
  write_obj(c, look, dir / "tree.obj");
  write_ply(c, look, dir / "tree.ply");
  write_ply(c, look, dir / "tree_text.ply", PlyEncoding::ascii);
  const Tubes t = tubes_of(c, look);
  // glTF and OBJ are y-up and Blender z-up: its importers turn (x, y, z) into (x, -z, y).
  const std::array<double, 3> min = {t.min.x(), -t.max.z(), t.min.y()}, max = {t.max.x(), -t.min.z(), t.max.y()};
  for (const char* file : {"tree.glb", "tree.obj"}) {
    SCOPED_TRACE(file);
    const Imported mesh = blender_import(dir, file);
    EXPECT_EQ(mesh.objects, 1);
    EXPECT_EQ(mesh.vertices, static_cast<long>(t.vertices));
    EXPECT_EQ(mesh.faces, static_cast<long>(t.triangles));
    EXPECT_EQ(mesh.edges, static_cast<long>(t.edges)) << "closed tubes share every edge but the seam's";
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_NEAR(mesh.min[a], min[a], 1e-4);
      EXPECT_NEAR(mesh.max[a], max[a], 1e-4);
    }
    // The UV map: u from 0 to 1 around; v along the strands from 0, flipped into Blender's
    // upward v as 1 - v by both importers.
    EXPECT_NEAR(mesh.uv[0], 0.0, 1e-6);
    EXPECT_NEAR(mesh.uv[2], 1.0, 1e-6);
    EXPECT_NEAR(mesh.uv[1], 1.0 - t.v_max, 1e-4);
    EXPECT_NEAR(mesh.uv[3], 1.0, 1e-6);
  }
  const Imported glb = blender_import(dir, "tree.glb");
  EXPECT_NE(glb.attributes.find("Col"), std::string::npos) << "the vertex colours: " << glb.attributes;

  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (const Particle& p : c.particles) {
    lo = lo.cwiseMin(p.position);
    hi = hi.cwiseMax(p.position);
  }
  for (const char* file : {"tree.ply", "tree_text.ply"}) {
    SCOPED_TRACE(file);
    const Imported ply = blender_import(dir, file);
    EXPECT_EQ(ply.vertices, static_cast<long>(c.particles.size()));
    EXPECT_EQ(ply.edges, static_cast<long>(c.particles.size() - c.seed_count));
    EXPECT_EQ(ply.faces, 0);
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_NEAR(ply.min[a], lo[static_cast<int>(a)], 1e-4);
      EXPECT_NEAR(ply.max[a], hi[static_cast<int>(a)], 1e-4);
    }
  }
}

// The texture artist's check: an image on the bark through the glb's UV map, rendered by Cycles,
// shows both of a checker's colours along the branches. Without texture coordinates every point
// would read one texel, and the picture one colour.
TEST(Blender, RendersAnImageTextureAlongTheBranches) {
  DLA_NEED_BLENDER();
  ScratchDir dir;
  DlaOptions o;
  o.particles = 300;
  o.rng_seed = 5;
  const Cluster c = grow(o);
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  write_glb(c, make_look(c, options), dir / "tree.glb");
  const std::string command = "cd '" + dir.path().string() + "' && blender -b --factory-startup --python-exit-code 1 "
                              "--python '" TEST_CLIENTS_DIR "/blender_texture.py' -- tree.glb tree.png > blender.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_file(dir / "blender.txt");
  EXPECT_NE(read_file(dir / "blender.txt").find("DLA3D {\"uv_maps\": [\"UVMap\"]}"), std::string::npos);
  const testing::Picture picture = testing::read_png(dir / "tree.png");
  ASSERT_EQ(picture.width, 240u);
  std::size_t orange = 0, teal = 0, touching = 0;  // the sky is grey
  for (std::size_t y = 0; y < picture.height; ++y)
    for (std::size_t x = 0; x < picture.width; ++x) {
      const auto [r, g, b] = picture.at(x, y);
      const bool is_orange = r > g + 50 && r > b + 50, is_teal = g > r + 40 && b > r + 40;
      orange += is_orange;
      teal += is_teal;
      const bool border = x == 0 || y == 0 || x + 1 == picture.width || y + 1 == picture.height;
      touching += border && (is_orange || is_teal);
    }
  const std::size_t pixels = picture.width * picture.height;
  EXPECT_GT(orange, pixels / 100) << "the checker's orange";
  EXPECT_GT(teal, pixels / 100) << "the checker's teal";
  EXPECT_EQ(touching, 0u) << "the tree is cut by the frame";
}

TEST(GltfValidator, FindsNoErrorInTheGlb) {
  DLA_NEED_GLTF_VALIDATOR();
  ScratchDir dir;
  const Cluster c = sample();
  for (const ColorBy color : {ColorBy::none, ColorBy::seed}) {
    for (const int sides : {3, 12}) {
      LookOptions options;
      options.color_by = color;
      options.tubes.sides = sides;
      options.tubes.tolerance = sides == 3 ? 0.3 : 0.0;
      const std::string glb = dir / ("tree_" + std::to_string(sides) + std::string(to_string(color)) + ".glb");
      write_glb(c, make_look(c, options), glb);
      EXPECT_EQ(testing::validate_glb(glb), "") << glb;
    }
  }
  Cluster lone;
  lone.seed_count = 1;
  lone.particles.push_back({Vec3::Zero(), -1, 0});
  write_glb(lone, make_look(lone, {}), dir / "empty.glb");
  EXPECT_EQ(testing::validate_glb(dir / "empty.glb"), "") << "a structure with no branch";
}

// Leaves (--leaf): the validator finds no error nor warning, and Blender makes an object a
// point, all of them sharing the leaf's mesh under the `leaves` empty, each at its point with its
// stem along the point's direction and its scale. Blender turns glTF's Y up to Z up: glTF's
// (x, y, z) is Blender's (x, -z, y).
TEST(Blender, ImportsTheLeavesAtTheInstancingPoints) {
  DLA_NEED_BLENDER();
  DLA_NEED_GLTF_VALIDATOR();
  ScratchDir dir;
  const Cluster c = sample();
  const Look look = make_look(c, {});
  const Leaf leaf = read_leaf(DLA_EXAMPLES_DIR "/leaf.glb");
  write_glb(c, look, dir / "leafy.glb", {0, &leaf, {}});
  const auto [status, report] = testing::validator_report(dir / "leafy.glb");
  EXPECT_EQ(status, 0) << report;
  EXPECT_EQ(report.rfind("errors=0 warnings=0 ", 0), 0u) << report;

  const std::string command = "cd '" + dir.path().string() + "' && blender -b --factory-startup --python-exit-code 1 "
                              "--python '" TEST_CLIENTS_DIR "/blender_leaves.py' -- leafy.glb > blender.txt 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0);
  const std::string log = read_file(dir / "blender.txt");
  const std::size_t at = log.find("DLA3D ");
  ASSERT_NE(at, std::string::npos) << log;
  const nlohmann::json found = nlohmann::json::parse(log.substr(at + 6, log.find('\n', at) - at - 6));
  std::map<std::int32_t, Instance> points;
  for (const Instance& point : instancing_points(c, look.attributes, {})) points.emplace(point.particle, point);
  ASSERT_EQ(found["leaves"].size(), points.size());
  EXPECT_EQ(found["meshes"], 1) << "every leaf object shares one mesh";
  EXPECT_EQ(found["parent"], "leaves");
  const auto gltf_of = [](const nlohmann::json& row, std::size_t from) {
    return Vec3(row[from].get<double>(), row[from + 2].get<double>(), -row[from + 1].get<double>());
  };
  for (const nlohmann::json& row : found["leaves"]) {
    SCOPED_TRACE(row.dump());
    const std::string name = row[0];
    ASSERT_EQ(name.rfind("leaf ", 0), 0u);
    const auto point = points.find(std::stoi(name.substr(5)));
    ASSERT_NE(point, points.end());
    const Instance& p = point->second;
    EXPECT_LT((gltf_of(row, 1) - p.position).norm(), 1e-5 * (1.0 + p.position.norm())) << "at its point";
    EXPECT_GT(gltf_of(row, 4).dot(p.direction), 1.0 - 1e-5) << "the stem along the point's direction";
    EXPECT_NEAR(row[7].get<double>(), p.scale, 1e-5 * p.scale) << "the point's scale";
  }
}

// Levels of detail: the validator passes each, and Blender imports each with the triangles
// written, falling level by level.
TEST(Blender, ImportsTheLevelsOfDetail) {
  DLA_NEED_BLENDER();
  DLA_NEED_GLTF_VALIDATOR();
  ScratchDir dir;
  const Cluster c = sample();
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  const Look look = make_look(c, options);
  const std::vector<std::size_t> triangles = write_glb(c, look, dir / "tree.glb", {3, nullptr, {}}).lod_triangles;
  long before = blender_import(dir, "tree.glb").faces;
  for (std::size_t level = 1; level <= 3; ++level) {
    const std::string file = "tree_lod" + std::to_string(level) + ".glb";
    SCOPED_TRACE(file);
    EXPECT_EQ(testing::validate_glb(dir / file), "");
    const Imported lod = blender_import(dir, file);
    EXPECT_EQ(lod.faces, static_cast<long>(triangles[level - 1]));
    EXPECT_LT(lod.faces, before);
    EXPECT_TRUE(std::isfinite(lod.uv[0]) && lod.uv[0] >= -1e-6 && lod.uv[2] <= 1 + 1e-6) << "the UV map";
    before = lod.faces;
  }
}

// A structure with links: Blender reads the PLY's edges, tree and links, and the glb with a tube
// for each link; the validator passes that glb.
TEST(Blender, ImportsTheLinksOfThePlyAndTheGlb) {
  DLA_NEED_BLENDER();
  ScratchDir dir;
  Cluster c = sample();
  c.links = neighbour_links(c, parse_links("2.5,2"));
  ASSERT_GT(c.links.size(), 20u);
  LookOptions options;
  options.color_by = ColorBy::age;
  const Look look = make_look(c, options);
  write_ply(c, look, dir / "linked.ply");
  write_glb(c, look, dir / "linked.glb");
  const Imported ply = blender_import(dir, "linked.ply");
  EXPECT_EQ(ply.vertices, static_cast<long>(c.particles.size()));
  EXPECT_EQ(ply.edges, static_cast<long>(c.particles.size() - c.seed_count + c.links.size()));
  const Tubes t = tubes_of(c, look);
  const Imported glb = blender_import(dir, "linked.glb");
  EXPECT_EQ(glb.vertices, static_cast<long>(t.vertices));
  EXPECT_EQ(glb.faces, static_cast<long>(t.triangles));
  EXPECT_EQ(glb.edges, static_cast<long>(t.edges)) << "each link's tube is closed but for its seam";
}

TEST(GltfValidator, FindsNoErrorInTheGlbWithLinks) {
  DLA_NEED_GLTF_VALIDATOR();
  ScratchDir dir;
  Cluster c = sample();
  c.links = neighbour_links(c, parse_links("3,3"));
  ASSERT_GT(c.links.size(), 20u);
  for (const ColorBy color : {ColorBy::none, ColorBy::depth}) {
    LookOptions options;
    options.color_by = color;
    const std::string glb = dir / ("linked_" + std::string(to_string(color)) + ".glb");
    write_glb(c, make_look(c, options), glb);
    EXPECT_EQ(testing::validate_glb(glb), "") << glb;
  }
}

// An aggregate's glb (the contact tree, as tubes of each monomer's own radius) and its solid
// (the union of its spheres) pass the validator, written by the command line.
TEST(GltfValidator, FindsNoErrorInAnAggregatesGlbs) {
  DLA_NEED_GLTF_VALIDATOR();
  ScratchDir dir;
  const testing::CliRun run = testing::dla3d(
      dir, "aggregate -n 200 --sizes lognormal --spread 1.3 --overlap 0.1 -o soot --formats glb,solid-glb");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::validate_glb(dir / "soot.glb"), "");
  EXPECT_EQ(testing::validate_glb(dir / "soot_solid.glb"), "");
}

//! Pixels of a screenshot that differ from the viewer's background (#0a0d12) by more than
//! antialiasing's faint edge; with `glass` (a mesh in the page), only the bright ones: the
//! structure uncoloured, not the dim glass.
long structure_pixels(const testing::Picture& shot, bool glass = false) {
  long lit = 0;
  for (std::size_t y = 0; y < shot.height; ++y)
    for (std::size_t x = 0; x < shot.width; ++x) {
      const std::array<int, 3> p = shot.at(x, y);
      lit += glass ? std::max({p[0], p[1], p[2]}) > 150 : std::abs(p[0] - 0x0a) + std::abs(p[1] - 0x0d) + std::abs(p[2] - 0x12) > 30;
    }
  return lit;
}

//! Opens PAGE in Chromium (view_page.mjs) and returns its JSON line; screenshots go to `dir`.
std::string open_page(const ScratchDir& dir, const std::string& page) {
  const std::string command = "node '" + testing::page_viewer() + "' '" + (dir / page) + "' '" +
                              dir.path().string() + "' > chromium.txt 2>&1";
  const std::string run = "cd '" + dir.path().string() + "' && " + command;
  EXPECT_EQ(std::system(run.c_str()), 0) << read_file(dir / "chromium.txt");
  const std::string out = read_file(dir / "chromium.txt");
  const std::size_t at = out.find("DLA3D ");
  return at == std::string::npos ? "" : out.substr(at);
}

// The web viewer in a real browser, offline: the page loads with no console error or request,
// shows the structure, shows less of it at a quarter of the slider (the count the page gives is
// exact), replays it with Play, and hides the mesh with its box. Lines for a larger structure,
// tubes and a mesh for a small one.
TEST(Chromium, OpensTheWebViewerAndReplaysGrowth) {
  DLA_NEED_CHROMIUM();
  ScratchDir dir;
  write_stl(make_sphere(Vec3::Zero(), 12.0, 12, 24), dir / "ball.stl");
  // With links: lines and tubes of them too, revealed with their later particle.
  ASSERT_EQ(testing::dla3d(dir, "-n 25000 -q -o lines --formats html --color-by age --links 2").exit_code, 0);
  ASSERT_EQ(testing::dla3d(dir, "-n 2000 -q -o tubes --formats html --stl ball.stl --spacing 0.4 --links 2").exit_code, 0);
  for (const auto& [page, particles, seeds] : {std::tuple{"lines", 25001, 1}, std::tuple{"tubes", 2001, 1}}) {
    SCOPED_TRACE(page);
    const std::string line = open_page(dir, std::string(page) + ".html");
    ASSERT_FALSE(line.empty());
    EXPECT_NE(line.find("\"messages\":[]"), std::string::npos) << "console errors or warnings: " << line;
    EXPECT_NE(line.find("\"refused\":[]"), std::string::npos) << "the page asked the network: " << line;
    const auto with_commas = [](long n) {
      std::string s = std::to_string(n);
      for (int at = static_cast<int>(s.size()) - 3; at > 0; at -= 3) s.insert(static_cast<std::size_t>(at), ",");
      return s;
    };
    const long quarter = seeds + std::lround(0.25 * (particles - seeds));
    EXPECT_NE(line.find("\"full\":\"" + with_commas(particles) + " of "), std::string::npos) << line;
    EXPECT_NE(line.find("\"quarter\":\"" + with_commas(quarter) + " of "), std::string::npos) << line;
    EXPECT_NE(line.find(" links\""), std::string::npos) << "the page counts its links: " << line;
    const auto shown = [&](const std::string& key) {
      const std::size_t at = line.find("\"" + key + "\":\"");
      std::string digits;
      for (std::size_t i = at + key.size() + 4; at != std::string::npos && i < line.size() && line[i] != ' '; ++i)
        if (line[i] != ',') digits += line[i];
      return digits.empty() ? -1L : std::atol(digits.c_str());
    };
    EXPECT_GT(shown("playing"), quarter) << "Play did not replay on from the slider: " << line;
    const bool glass = std::string(page) == "tubes";
    const long full = structure_pixels(testing::read_png(dir / "full.png"), glass);
    const long part = structure_pixels(testing::read_png(dir / "quarter.png"), glass);
    EXPECT_GT(full, 640 * 400 / 100) << "the canvas is (nearly) blank";
    EXPECT_GT(part, 100);
    EXPECT_LT(part, full * 3 / 4) << "a quarter grown shows as much";
    if (glass) {
      EXPECT_NE(line.find("\"mesh_toggles\":true"), std::string::npos) << line;
      EXPECT_GT(structure_pixels(testing::read_png(dir / "full.png")),
                structure_pixels(testing::read_png(dir / "no_mesh.png")) + 640 * 400 / 20)
          << "the mesh's box does not hide the glass";
    }
  }
}

}  // namespace
}  // namespace dla
