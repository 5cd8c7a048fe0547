// The files: CSV reads back exactly, PLY is self-consistent, the same seed gives the same
// bytes, and a file that cannot be written fails cleanly with nothing left behind.

#include "dla/io/mesh_writers.h"
#include "dla/io/csv_writer.h"
#include "dla/models/dla.h"
#include "dla/io/ply_writer.h"
#include "dla/io/png_writer.h"
#include "dla/io/pov_writer.h"
#include "dla/io/run_report.h"
#include "dla/run/run.h"
#include "dla/mesh/shapes.h"
#include "dla/mesh/surface_distance.h"
#include "mesh_util.h"
#include "png_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <sstream>
#include <thread>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

Cluster small_cluster(std::uint64_t seed = 1) {
  DlaOptions o;
  o.particles = 1500;
  o.rng_seed = seed;
  return grow(o);
}

void write_all(const Cluster& c, const std::string& prefix) {
  write_csv(c, prefix + ".csv");
  write_ply(c, prefix + ".ply");
  write_pov(c, prefix);
  write_run_report(c, ModelRecord{"dla", 1}, LookOptions{}, PovOptions{}, RunRecord{}, prefix + ".json");
}

TEST(Csv, ReadsBackExactly) {
  ScratchDir dir;
  const Cluster c = small_cluster();
  write_csv(c, dir / "a.csv");
  std::istringstream in(read_file(dir / "a.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "id,x,y,z,parent,seed");
  std::size_t row = 0;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    std::size_t id;
    double x, y, z;
    int parent, seed;
    fields >> id >> x >> y >> z >> parent >> seed;
    ASSERT_EQ(id, row);
    const Particle& p = c.particles[row];
    ASSERT_EQ(x, p.position.x());
    ASSERT_EQ(y, p.position.y());
    ASSERT_EQ(z, p.position.z());
    ASSERT_EQ(parent, p.parent);
    ASSERT_EQ(seed, p.seed);
    ++row;
  }
  EXPECT_EQ(row, c.particles.size());
}

TEST(Ply, HeaderCountsMatchTheBody) {
  ScratchDir dir;
  const Cluster c = small_cluster();
  write_ply(c, dir / "a.ply", PlyEncoding::ascii);
  std::istringstream in(read_file(dir / "a.ply"));
  std::string line;
  std::size_t vertices = 0, edges = 0;
  while (std::getline(in, line) && line != "end_header") {
    std::sscanf(line.c_str(), "element vertex %zu", &vertices);
    std::sscanf(line.c_str(), "element edge %zu", &edges);
  }
  EXPECT_EQ(vertices, c.particles.size());
  EXPECT_EQ(edges, c.particles.size() - 1);
  std::size_t body = 0;
  while (std::getline(in, line)) ++body;
  EXPECT_EQ(body, vertices + edges);
}

// The binary PLY holds the ASCII one's values: the same header but the format, then each
// vertex as three floats and two ints, each edge as two ints, little-endian.
TEST(Ply, BinaryHoldsTheSameValues) {
  ScratchDir dir;
  const Cluster c = small_cluster();
  write_ply(c, dir / "text.ply", PlyEncoding::ascii);
  write_ply(c, dir / "binary.ply");
  const std::string text = read_file(dir / "text.ply"), binary = read_file(dir / "binary.ply");
  const std::size_t text_body = text.find("end_header\n") + 11, binary_body = binary.find("end_header\n") + 11;
  std::string header = text.substr(0, text_body);
  header.replace(header.find("ascii"), 5, "binary_little_endian");
  EXPECT_EQ(binary.substr(0, binary_body), header);
  const std::size_t n = c.particles.size(), edges = n - c.seed_count;
  ASSERT_EQ(binary.size() - binary_body, 38 * n + 8 * edges);
  std::istringstream values(text.substr(text_body));
  const char* at = binary.data() + binary_body;
  for (std::size_t i = 0; i < n; ++i) {
    float x, y, z, radius, age;
    std::int32_t depth, descendants, seed, parent;
    std::uint8_t order, tip;
    std::memcpy(&x, at, 4), std::memcpy(&y, at + 4, 4), std::memcpy(&z, at + 8, 4);
    std::memcpy(&radius, at + 12, 4), std::memcpy(&age, at + 16, 4);
    std::memcpy(&depth, at + 20, 4), std::memcpy(&descendants, at + 24, 4);
    order = static_cast<std::uint8_t>(at[28]), tip = static_cast<std::uint8_t>(at[29]);
    std::memcpy(&seed, at + 30, 4), std::memcpy(&parent, at + 34, 4);
    at += 38;
    float tx, ty, tz, tradius, tage;
    long tdepth, tdescendants, torder, ttip, tseed, tparent;
    values >> tx >> ty >> tz >> tradius >> tage >> tdepth >> tdescendants >> torder >> ttip >> tseed >> tparent;
    // Both hold the float nearest the position: the text as the shortest decimal that reads
    // back as that float.
    const Vec3& p = c.particles[i].position;
    EXPECT_EQ(x, static_cast<float>(p.x()));
    EXPECT_EQ(y, static_cast<float>(p.y()));
    EXPECT_EQ(z, static_cast<float>(p.z()));
    EXPECT_EQ(tx, x);
    EXPECT_EQ(ty, y);
    EXPECT_EQ(tz, z);
    EXPECT_EQ(tradius, radius);
    EXPECT_EQ(tage, age);
    EXPECT_EQ(depth, tdepth);
    EXPECT_EQ(descendants, tdescendants);
    EXPECT_EQ(order, torder);
    EXPECT_EQ(tip, ttip);
    EXPECT_EQ(parent, tparent);
    EXPECT_EQ(seed, tseed);
  }
  for (std::size_t e = 0; e < edges; ++e) {
    std::int32_t from, to;
    std::memcpy(&from, at, 4), std::memcpy(&to, at + 4, 4);
    at += 8;
    long tfrom, tto;
    values >> tfrom >> tto;
    EXPECT_EQ(from, tfrom);
    EXPECT_EQ(to, tto);
  }
}

TEST(Pov, GeometryIsSphereSweepsWithPositiveRadii) {
  ScratchDir dir;
  const Cluster c = small_cluster();
  write_pov(c, dir / "scene");
  const std::string pov = read_file(dir / "scene.pov"), inc = read_file(dir / "scene.inc");
  EXPECT_NE(pov.find("#include \"scene.inc\""), std::string::npos) << "include by file name";
  EXPECT_NE(pov.find("#declare DLA_BaseRadius = 0.5;"), std::string::npos);
  EXPECT_NE(inc.find("sphere_sweep { linear_spline, "), std::string::npos);
  EXPECT_EQ(inc.find("b_spline"), std::string::npos);
  EXPECT_EQ(inc.find("DLA_R(-"), std::string::npos) << "no negative radius";
  LookOptions bad;
  bad.radius.tip_radius = -0.1;
  EXPECT_THROW(make_look(c, bad), InvalidInput);
}

TEST(Writers, SameSeedSameBytes) {
  ScratchDir dir;
  write_all(small_cluster(7), dir / "a");
  write_all(small_cluster(7), dir / "b");
  write_all(small_cluster(8), dir / "c");
  for (const char* ext : {".csv", ".ply", ".inc"}) {
    EXPECT_EQ(read_file(dir / (std::string("a") + ext)), read_file(dir / (std::string("b") + ext))) << ext;
    EXPECT_NE(read_file(dir / (std::string("a") + ext)), read_file(dir / (std::string("c") + ext))) << ext;
  }
  EXPECT_EQ(read_file(dir / "a.json"), read_file(dir / "b.json"));
}

TEST(Writers, UnwritablePathFailsCleanly) {
  ScratchDir dir;
  const Cluster c = small_cluster();
  try {
    write_csv(c, dir / "missing/a.csv");
    FAIL() << "no error";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "nothing half-written";
}

TEST(RunReport, RecordsOptionsSeedAndCounts) {
  ScratchDir dir;
  DlaRunOptions o;
  o.particles = 500;
  o.growth.rng_seed = 99;
  o.growth.stickiness = 0.5;
  const auto run = prepare_run(o);
  const Cluster c = run->grow({}, nullptr);
  RunRecord record;
  record.grow_seconds = 1.0;
  record.write_seconds = 0.5;
  write_run_report(c, run->record(), LookOptions{}, PovOptions{}, record, dir / "r.json");
  const std::string json = read_file(dir / "r.json");
  for (const char* expected : {"\"model\": \"grow\"", "\"rng_seed\": 99", "\"stickiness\": 0.5", "\"attached\": 500",
                               "\"complete\": true", "\"grow_seconds\": 1", "\"particles_per_second\": 500",
                               "\"walkers\": 500", "\"fractal_dimension_gyration\": "})
    EXPECT_NE(json.find(expected), std::string::npos) << expected;
}

TEST(GrowRecorded, MeasuresTheDistancesToTheMeshAsItGrowsAndTheFilesStayTheSame) {
  ScratchDir dir;
  write_stl(make_sphere(Vec3::Zero(), 12.0, 12, 24), dir / "ball.stl");
  DlaRunOptions o;
  o.stl = dir / "ball.stl";
  o.particles = 3000;
  o.growth.rng_seed = 5;
  const auto run = prepare_run(o);
  RunRecord record;
  const Cluster c = grow_recorded(*run, {}, nullptr, record);
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "no core to spare: nothing is measured as it grows";
  ASSERT_NE(run->measured_while_growing, nullptr);
  const MeasuredClosest& measured = *run->measured_while_growing;
  ASSERT_LE(measured.triangles.size(), c.particles.size());
  const TriangleMesh& mesh = run->constraint->mesh();
  for (std::size_t i = 0; i < measured.triangles.size(); i += 7) {
    const Vec3& p = c.particles[i].position;
    const auto& t = mesh.triangles[measured.triangles[i]];
    const Vec3 q = closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    ASSERT_NEAR((q - p).norm(), testing::brute_distance(mesh, p), 1e-9) << i;
  }
  OutputOptions files = run->files;
  files.output = dir / "taken";
  write_run(*run, c, files, record);
  run->measured_while_growing = nullptr;
  files.output = dir / "measured";
  write_run(*run, c, files, record);
  EXPECT_EQ(read_file(dir / "taken.inc"), read_file(dir / "measured.inc"));
}

using testing::Picture;
using testing::read_png;

TEST(Png, EveryParticleIsADotInItsBandOnTheBackground) {
  DlaOptions o;
  o.particles = 800;
  o.dimensions = 2;
  o.spacing = 0.5;
  const Cluster cluster = grow(o);
  ScratchDir dir;
  PngOptions options;
  options.pixels_per_spacing = 3;
  options.bands = 2;
  write_png(cluster, dir / "dla.png", options);
  const Picture picture = read_png(dir / "dla.png");
  const auto [width, height] = png_size(cluster, options);
  ASSERT_EQ(picture.width, static_cast<std::size_t>(width));
  ASSERT_EQ(picture.height, static_cast<std::size_t>(height));
  // The corner is background; each particle's centre pixel holds a band's colour (white,
  // grey or black).
  const auto pixel = [&](std::size_t x, std::size_t y) {
    const std::uint8_t* p = &picture.rgb[(y * picture.width + x) * 3];
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(pixel(0, 0), (std::array<int, 3>{0x38, 0x40, 0x4c}));
  Vec3 min = cluster.particles[0].position;
  for (const Particle& p : cluster.particles) min = min.cwiseMin(p.position);
  const double scale = options.pixels_per_spacing / cluster.spacing;
  std::size_t lit = 0;
  for (std::size_t y = 0; y < picture.height; ++y)
    for (std::size_t x = 0; x < picture.width; ++x) lit += pixel(x, y) != pixel(0, 0);
  EXPECT_GT(lit, cluster.particles.size()) << "each dot is several pixels";
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const Vec3& p = cluster.particles[i].position;
    const auto x = static_cast<std::size_t>(options.margin + 1.5 + (p.x() - min.x()) * scale);
    const auto y = picture.height - 1 - static_cast<std::size_t>(options.margin + 1.5 + (p.y() - min.y()) * scale);
    const std::array<int, 3> c = pixel(x, y);
    ASSERT_TRUE(c == (std::array<int, 3>{255, 255, 255}) || c == (std::array<int, 3>{0x90, 0x90, 0x90}) ||
                c == (std::array<int, 3>{0, 0, 0}))
        << "particle " << i;
  }
  // The same structure, the same bytes; 3D is refused; a structure too wide for the scale
  // is drawn smaller, within 8,192 pixels.
  write_png(cluster, dir / "again.png", options);
  EXPECT_EQ(read_file(dir / "dla.png"), read_file(dir / "again.png"));
  Cluster solid = cluster;
  solid.dimensions = 3;
  EXPECT_THROW(write_png(solid, dir / "solid.png"), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dir / "solid.png"));
  options.pixels_per_spacing = 64;
  Cluster wide = cluster;
  for (Particle& p : wide.particles) p.position *= 100.0;
  write_png(wide, dir / "wide.png", options);
  const Picture fitted = read_png(dir / "wide.png");
  EXPECT_LE(std::max(fitted.width, fitted.height), 8192u);
  EXPECT_GT(std::max(fitted.width, fitted.height), 8000u);
  options.bands = 0;
  EXPECT_THROW(write_png(cluster, dir / "none.png", options), InvalidInput);
}

}  // namespace
}  // namespace dla
