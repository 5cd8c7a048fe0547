// MSTM's sphere-position file and DDSCAT's shape file (dla/io/scattering_writers.h): the MSTM
// lines are the spheres, radius first, read back exactly; the shape file's dipoles are every
// lattice point inside a sphere, each once, against a brute-force scan of the whole lattice box;
// a shape file past its cap is refused in one line that names a resolution that fits.
// `dla3d analyze` reads sphere lists back and measures their D_f and k_f.

#include "cli_util.h"
#include "test_util.h"

#include "dla/core/analysis.h"
#include "dla/core/memory.h"
#include "dla/io/scattering_writers.h"
#include "dla/models/aggregate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace {

using dla::Cluster;
using dla::testing::ScratchDir;

//! Sintered, lognormal soot: spheres of their own radii that overlap their neighbours.
Cluster soot() {
  dla::AggregateOptions o;
  o.mode = dla::AggregateMode::tuned;
  o.monomers = 40;
  o.sizes = dla::MonomerSizes::lognormal;
  o.spread = 1.3;
  o.overlap = 0.2;
  o.monomer_radius = 2.5;
  return dla::aggregate(o);
}

TEST(ScatteringWriters, MstmLinesAreTheSpheresRadiusFirst) {
  ScratchDir dir;
  const Cluster cluster = soot();
  const dla::Look look = dla::make_look(cluster, {});
  const std::string path = dir / "soot_mstm.pos";
  dla::write_mstm_positions(cluster, look, path);
  std::ifstream in(path);
  std::size_t i = 0;
  for (std::string line; std::getline(in, line); ++i) {
    ASSERT_LT(i, cluster.particles.size());
    EXPECT_LE(line.size(), 128u) << "MSTM 3 reads a line into 128 characters";
    std::istringstream fields(line);
    double r, x, y, z;
    fields >> r >> x >> y >> z;
    ASSERT_FALSE(fields.fail()) << line;
    std::string more;
    EXPECT_FALSE(fields >> more) << "four numbers a line: " << line;
    EXPECT_EQ(r, cluster.radii[i]);
    EXPECT_EQ(x, cluster.particles[i].position.x());
    EXPECT_EQ(y, cluster.particles[i].position.y());
    EXPECT_EQ(z, cluster.particles[i].position.z());
  }
  EXPECT_EQ(i, cluster.particles.size());
}

TEST(ScatteringWriters, DdscatDipolesAreEveryLatticePointInASphereOnce) {
  ScratchDir dir;
  const Cluster cluster = soot();
  const dla::Look look = dla::make_look(cluster, {});
  const int resolution = 3;
  const std::string path = dir / "soot_ddscat.dat";
  dla::write_ddscat_shape(cluster, look, resolution, path);

  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind(" >", 0), 0u) << line;
  std::size_t nat = 0;
  in >> nat;
  std::getline(in, line);
  EXPECT_EQ(line, " = NAT");
  std::array<std::string, 4> header;
  for (std::string& h : header) std::getline(in, h);
  EXPECT_EQ(header[0], "1 0 0 = A_1 vector");
  EXPECT_EQ(header[1], "0 1 0 = A_2 vector");
  EXPECT_EQ(header[2].rfind("1 1 1 = lattice spacings", 0), 0u);
  EXPECT_EQ(header[3].rfind("0 0 0 = lattice offset", 0), 0u);
  std::getline(in, line);
  EXPECT_EQ(line, "JA IX IY IZ ICOMP(x,y,z)");
  std::set<std::array<long, 3>> written;
  std::array<long, 3> previous{};
  long ja = 0, ix, iy, iz, c1, c2, c3;
  for (long expected = 1; in >> ja >> ix >> iy >> iz >> c1 >> c2 >> c3; ++expected) {
    ASSERT_EQ(ja, expected);
    EXPECT_EQ(c1 + c2 + c3, 3);
    const std::array<long, 3> zyx{iz, iy, ix};
    if (expected > 1) {
      ASSERT_LT(previous, zyx) << "in order of IZ, IY, IX, each once";
    }
    previous = zyx;
    written.insert({ix, iy, iz});
  }
  EXPECT_EQ(written.size(), nat);

  // Brute force: every lattice point of the spheres' box, against every sphere.
  const double d = dla::dipole_lattice(cluster, look, resolution).spacing;
  double mean = 0.0;
  for (const double r : cluster.radii) mean += r;
  EXPECT_DOUBLE_EQ(d, mean / static_cast<double>(cluster.radii.size()) / resolution);
  dla::Vec3 low = dla::Vec3::Constant(1e300), high = dla::Vec3::Constant(-1e300);
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    low = low.cwiseMin(cluster.particles[i].position - dla::Vec3::Constant(cluster.radii[i]));
    high = high.cwiseMax(cluster.particles[i].position + dla::Vec3::Constant(cluster.radii[i]));
  }
  std::size_t inside = 0;
  for (long z = std::lround(low.z() / d) - 1; z <= std::lround(high.z() / d) + 1; ++z)
    for (long y = std::lround(low.y() / d) - 1; y <= std::lround(high.y() / d) + 1; ++y)
      for (long x = std::lround(low.x() / d) - 1; x <= std::lround(high.x() / d) + 1; ++x) {
        const dla::Vec3 p(static_cast<double>(x) * d, static_cast<double>(y) * d, static_cast<double>(z) * d);
        bool in_sphere = false;
        for (std::size_t i = 0; i < cluster.particles.size() && !in_sphere; ++i) {
          const double r = cluster.radii[i] / d;
          in_sphere = (p / d - cluster.particles[i].position / d).squaredNorm() <= r * r;
        }
        EXPECT_EQ(written.count({x, y, z}), in_sphere ? 1u : 0u) << x << ' ' << y << ' ' << z;
        inside += in_sphere;
      }
  EXPECT_EQ(inside, nat);
  // The count is the spheres' volume over d^3, less what they share.
  EXPECT_LT(static_cast<double>(nat), dla::dipole_lattice(cluster, look, resolution).estimated_dipoles * 1.05);
  EXPECT_GT(static_cast<double>(nat), 0.5 * dla::dipole_lattice(cluster, look, resolution).estimated_dipoles);
}

TEST(ScatteringWriters, AShapeFilePastItsCapIsRefusedNamingAResolutionThatFits) {
  ScratchDir dir;
  try {
    dla::refuse_dipoles({0.1, 8.0 * dla::kMaxDipoles}, 10, dir / "big_ddscat.dat");
    FAIL() << "not refused";
  } catch (const dla::InvalidInput& e) {
    // Within the cap, where memory and disk hold more than it: the count goes as the cube.
    const std::string said = e.what();
    if (said.find("a shape file may hold") != std::string::npos) {
      EXPECT_NE(said.find("a resolution of 5 fits"), std::string::npos) << said;
    }
    EXPECT_NE(said.find("`ddscat_resolution` 10, past the "), std::string::npos) << said;
  }
  // Up to the cap, if this machine's memory and disk hold it.
  if (dla::available_memory() > 32.0 * dla::kMaxDipoles && dla::free_disk_bytes(dir / "big_ddscat.dat") > 16.0 * dla::kMaxDipoles) {
    EXPECT_NO_THROW(dla::refuse_dipoles({0.1, dla::kMaxDipoles}, 10, dir / "big_ddscat.dat"));
  }
  // Before growth, from the monomers asked for.
  const dla::testing::CliRun run =
      dla::testing::dla3d(dir, "aggregate -n 100000 --formats ddscat --ddscat-resolution 20 -o big");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_EQ(run.err.rfind("dla3d: error: --formats ddscat: about 3,351,032,163 dipoles at --ddscat-resolution 20, "
                          "past the ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find(": a resolution of "), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "big_ddscat.dat"));
}

TEST(ScatteringWriters, TheCliWritesTheSameSpheresToEachFile) {
  ScratchDir dir;
  const dla::testing::CliRun run = dla::testing::dla3d(
      dir, "aggregate -n 60 --sizes lognormal --spread 1.2 -o soot --formats spheres,mstm,ddscat --ddscat-resolution 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream csv(dir / "soot_spheres.csv"), pos(dir / "soot_mstm.pos");
  std::string header;
  std::getline(csv, header);
  std::size_t rows = 0;
  for (std::string a, b; std::getline(csv, a) && std::getline(pos, b); ++rows) {
    double x, y, z, r, r2, x2, y2, z2;
    char c;
    std::istringstream(a) >> x >> c >> y >> c >> z >> c >> r;
    std::istringstream(b) >> r2 >> x2 >> y2 >> z2;
    const std::array<double, 4> listed{x, y, z, r}, positioned{x2, y2, z2, r2};
    EXPECT_EQ(listed, positioned);
  }
  EXPECT_EQ(rows, 60u);
  EXPECT_TRUE(std::filesystem::exists(dir / "soot_ddscat.dat"));
}

// The pair correlation's dimension is the dimension of what the points fill: a line of beads,
// a plane of them, a ball of them.
TEST(ScatteringWriters, PairCorrelationReadsTheDimensionOfLinesPlanesAndBalls) {
  const auto dimension = [](const std::vector<dla::Vec3>& points) {
    const dla::FractalFit fit =
        dla::fractal_dimension_by_pair_correlation(points, 1.0, dla::radius_of_gyration(points));
    EXPECT_EQ(fit.samples, 16u);
    std::printf("pair correlation of %zu points: %.3f\n", points.size(), fit.dimension);
    return fit.dimension;
  };
  std::vector<dla::Vec3> line, plane, ball;
  for (int i = 0; i < 2000; ++i) line.emplace_back(2.0 * i, 0.0, 0.0);
  for (int i = 0; i < 80; ++i)
    for (int j = 0; j < 80; ++j) plane.emplace_back(2.0 * i, 2.0 * j, 0.0);
  for (int i = -25; i <= 25; ++i)
    for (int j = -25; j <= 25; ++j)
      for (int k = -25; k <= 25; ++k)
        if (i * i + j * j + k * k <= 25 * 25) ball.emplace_back(2.0 * i, 2.0 * j, 2.0 * k);
  EXPECT_NEAR(dimension(line), 1.0, 0.1);
  EXPECT_NEAR(dimension(plane), 2.0, 0.15);
  EXPECT_NEAR(dimension(ball), 3.0, 0.3);  // 65,000 points: C(r) from 4,000 of them
  // Too small to fit: R_g under 8 radii.
  EXPECT_EQ(dla::fractal_dimension_by_pair_correlation({{0, 0, 0}, {2, 0, 0}, {4, 0, 0}}, 1.0, 1.63).samples, 0u);
}

//! The value of `key` in `json`, or NaN for null or none.
double json_value(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\": ");
  if (at == std::string::npos || json.compare(at + key.size() + 4, 4, "null") == 0) return NAN;
  return std::atof(json.c_str() + at + key.size() + 4);
}

//! What `dla3d ARGS` prints on stdout in `dir`, after it exits 0.
std::string printed(const ScratchDir& dir, const std::string& args) {
  const std::string command = "cd '" + dir.path().string() + "' && '" DLA3D_PATH "' " + args + " > printed.json";
  EXPECT_EQ(std::system(command.c_str()), 0) << args;
  return dla::testing::read_file(dir / "printed.json");
}

TEST(ScatteringWriters, AnalyzeMeasuresTheLawOfSphereLists) {
  ScratchDir dir;
  std::string lists;
  for (const int n : {300, 600, 1200, 2400}) {
    const std::string prefix = "t" + std::to_string(n);
    ASSERT_EQ(dla::testing::dla3d(dir, "aggregate -q --mode tuned --df 1.8 --kf 1.3 --monomer-radius 3 -n " +
                                           std::to_string(n) + " -o " + prefix + " --formats spheres")
                  .exit_code,
              0);
    lists += " " + prefix + "_spheres.csv";
  }
  const std::string all = printed(dir, "analyze" + lists);
  // By gyration over sizes that span a factor 8: the law they were grown on.
  EXPECT_NEAR(json_value(all, "fractal_dimension_gyration"), 1.8, 1e-6) << all;
  EXPECT_NEAR(json_value(all, "prefactor_gyration"), 1.3, 1e-5) << all;
  EXPECT_NEAR(json_value(all, "fractal_dimension_pair_correlation"), 1.8, 0.12) << all;
  EXPECT_NEAR(json_value(all, "prefactor_pair_correlation"), 1.3, 0.5) << all;
  EXPECT_NEAR(json_value(all, "mean_radius"), 3.0, 1e-9) << all;
  // One aggregate has no law by gyration; a structure CSV among sphere lists is refused.
  const std::string one = printed(dir, "analyze t300_spheres.csv");
  EXPECT_NE(one.find("\"fractal_dimension_gyration\": null"), std::string::npos) << one;
  ASSERT_EQ(dla::testing::dla3d(dir, "-n 100 -q -o tree --formats csv").exit_code, 0);
  for (const auto& [args, message] :
       {std::pair<std::string, std::string>{"analyze t300_spheres.csv tree.csv", "tree.csv: is not a sphere list"},
        {"analyze tree.csv t300_spheres.csv", "analyze measures one structure CSV at a time"}}) {
    const dla::testing::CliRun bad = dla::testing::dla3d(dir, args);
    EXPECT_EQ(bad.exit_code, 2) << args;
    EXPECT_NE(bad.err.find(message), std::string::npos) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
  std::ofstream(dir / "bad_spheres.csv") << "x,y,z,r\n1,2,3,4\n1,2,3,-1\n";
  const dla::testing::CliRun bad = dla::testing::dla3d(dir, "analyze bad_spheres.csv");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad_spheres.csv: line 3 is not a sphere x,y,z,r with r above 0"), std::string::npos) << bad.err;
}

}  // namespace
