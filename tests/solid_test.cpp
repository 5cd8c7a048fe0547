// The solid (solid.h) against brute force: every voxel's value is the analytic distance to the
// union of tapered capsules, the mesh's volume is a Monte Carlo estimate's, every particle lies
// inside it, every vertex on the analytic surface; the mesh is closed, oriented and free of
// self-intersections, with one shell a tree; print sizing, refusals and determinism.
#include "mesh_util.h"
#include "solid_check.h"
#include "test_util.h"
#include "tree_check.h"
#include "tube_check.h"

#include "dla/io/mesh_writers.h"
#include "dla/core/random.h"
#include "dla/io/solid_writers.h"
#include "dla/look/look.h"
#include "dla/look/solid.h"
#include "dla/models/colonization.h"
#include "dla/models/dla.h"
#include "dla/models/eden.h"
#include "look/solid_grid.h"

#include <openvdb/tools/Interpolation.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

//! The distance from p to the union of balls along a..b, radii ra..rb: the round cone, by a
//! ternary search over the ball's place (|p - c(t)| - r(t) is convex in t), not by solid.cpp's
//! closed form.
double cone_distance(const Vec3& p, const Vec3& a, const Vec3& b, double ra, double rb) {
  const auto f = [&](double t) { return (p - (a + t * (b - a))).norm() - (ra + t * (rb - ra)); };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 64; ++i) {  // (2/3)^64 of the axis: below 1e-11
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    (f(m1) <= f(m2) ? hi : lo) = f(m1) <= f(m2) ? m2 : m1;
  }
  return std::min({f(lo), f(0.0), f(1.0)});
}

//! The signed distance to the union of a structure's capsules, in scene units, each radius
//! widened by chord_depth() for the voxel (0: not widened): the minimum over every branch, by
//! brute force.
struct Union {
  struct Capsule {
    Vec3 a, b;
    double ra, rb;
  };
  std::vector<Capsule> capsules;

  Union(const Cluster& c, const std::vector<float>& radii, double voxel = 0.0) {
    for (std::size_t i = 0; i < c.particles.size(); ++i) {
      const Particle& q = c.particles[i];
      const auto parent = q.parent >= 0 ? static_cast<std::size_t>(q.parent) : i;
      const bool sphere = parent == i;
      const auto widened = [&](std::size_t k) {
        const double radius = static_cast<double>(radii[k]) * c.spacing;
        return voxel > 0 ? radius + chord_depth(voxel, radius, sphere) : radius;
      };
      capsules.push_back({q.position, c.particles[parent].position, widened(i), widened(parent)});
    }
  }
  double distance(const Capsule& k, const Vec3& p) const { return cone_distance(p, k.a, k.b, k.ra, k.rb); }
  double operator()(const Vec3& p) const {
    double d = std::numeric_limits<double>::infinity();
    for (const Capsule& k : capsules) {
      // The distance to a capsule's box is no more than to the capsule: a box that p is outside
      // of, farther than the nearest so far, cannot hold a nearer capsule.
      const Eigen::AlignedBox3d b = box(k);
      const double outside = b.exteriorDistance(p);
      if (outside > 0.0 && outside >= d) continue;
      d = std::min(d, distance(k, p));
    }
    return d;
  }
  //! Whether the union's distance at p is at least `d` > 0: only the capsules whose box is
  //! nearer than d are measured.
  bool at_least(const Vec3& p, double d) const {
    for (const Capsule& k : capsules)
      if (box(k).exteriorDistance(p) < d && distance(k, p) < d) return false;
    return true;
  }
  //! Whether the union's distance at p is at most `d` < 0: some capsule holds p that deep.
  bool at_most(const Vec3& p, double d) const {
    for (const Capsule& k : capsules)
      if (box(k).contains(p) && distance(k, p) <= d) return true;
    return false;
  }
  Eigen::AlignedBox3d box(const Capsule& k) const {
    const double r = std::max(k.ra, k.rb);
    Eigen::AlignedBox3d b(Vec3(k.a.cwiseMin(k.b).array() - r), Vec3(k.a.cwiseMax(k.b).array() + r));
    return b;
  }
  //! The union's volume by Monte Carlo, a capsule at a time (Karp and Luby): the points of
  //! capsule i's box inside it and inside no earlier capsule, `samples` a capsule. Returns the
  //! estimate and its standard error.
  std::pair<double, double> volume(int samples, std::uint64_t seed) const {
    Rng rng(seed);
    double total = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < capsules.size(); ++i) {
      const Eigen::AlignedBox3d bi = box(capsules[i]);
      int hits = 0;
      for (int s = 0; s < samples; ++s) {
        const Vec3 p = bi.min() + Vec3(rng.uniform(), rng.uniform(), rng.uniform()).cwiseProduct(bi.sizes());
        if (distance(capsules[i], p) >= 0.0) continue;
        bool earlier = false;
        for (std::size_t j = 0; j < i && !earlier; ++j)
          earlier = box(capsules[j]).contains(p) && distance(capsules[j], p) < 0.0;
        hits += !earlier;
      }
      const double f = static_cast<double>(hits) / samples;
      total += bi.volume() * f;
      variance += bi.volume() * bi.volume() * f * (1.0 - f) / samples;
    }
    return {total, std::sqrt(variance)};
  }
};

Cluster small_tree(std::size_t particles, std::uint64_t seed, std::vector<Vec3> seeds = {Vec3::Zero()}) {
  DlaOptions o;
  o.particles = particles;
  o.rng_seed = seed;
  o.seeds = std::move(seeds);
  return grow(o);
}

std::vector<float> pipe_radii(const Cluster& c) {
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  return make_look(c, options).radii;
}

TEST(Solid, EveryVoxelHoldsTheDistanceToTheUnionOfCapsules) {
  const Cluster c = small_tree(150, 5);
  const std::vector<float> radii = pipe_radii(c);
  const Solid solid = build_solid(c, radii, {});
  const Union reference(c, radii, solid.measures.voxel);
  const openvdb::FloatGrid& grid = *solid.grid->surface;
  const double band = grid.background();
  EXPECT_NEAR(band, 3.0 * solid.measures.voxel, 1e-6);
  std::size_t checked = 0;
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    const openvdb::Vec3d w = grid.indexToWorld(it.getCoord());
    const double expected = reference(Vec3(w.x(), w.y(), w.z()));
    ASSERT_NEAR(*it, std::clamp(expected, -band, band), 1e-5) << "at " << it.getCoord();
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
  // Every voxel outside the band is off and holds +band outside, -band inside; a tile (a block
  // of voxels of one value) is checked at its corners and centre.
  std::size_t off = 0;
  const auto expect_beyond = [&](const openvdb::Vec3d& w, float value) {
    const Vec3 p(w.x(), w.y(), w.z());
    ASSERT_TRUE(value > 0 ? reference.at_least(p, band - 1e-5) : reference.at_most(p, -band + 1e-5))
        << value << " at " << p.transpose() << ": the union's distance there is " << reference(p);
  };
  for (auto it = grid.cbeginValueOff(); it; ++it) {
    if (it.isVoxelValue()) {
      expect_beyond(grid.indexToWorld(it.getCoord()), *it);
      ++off;
      continue;
    }
    openvdb::CoordBBox tile;
    it.getBoundingBox(tile);
    const openvdb::Coord lo = tile.min(), hi = tile.max();
    for (int corner = 0; corner < 8; ++corner)
      expect_beyond(grid.indexToWorld(openvdb::Coord(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(),
                                                     corner & 4 ? hi.z() : lo.z())),
                    *it);
    expect_beyond(grid.indexToWorld(tile.getCenter()), *it);
  }
  EXPECT_GT(off, 0u);
}

TEST(Solid, VolumeMatchesMonteCarloAndEveryParticleIsInside) {
  for (const auto model : {RadiusModel::pipe, RadiusModel::taper, RadiusModel::uniform}) {
    SCOPED_TRACE(to_string(model));
    const Cluster c = small_tree(80, 9);
    LookOptions options;
    options.radius.model = model;
    const std::vector<float> radii = make_look(c, options).radii;
    const Solid solid = build_solid(c, radii, {});
    const auto [estimate, error] = Union(c, radii).volume(4000, 17);
    EXPECT_LT(error, 0.005 * estimate);
    EXPECT_NEAR(solid.measures.volume, estimate, 0.015 * estimate);
    std::printf("%s: the mesh holds %.4f of the union's volume\n", to_string(model).data(), solid.measures.volume / estimate);
    EXPECT_NEAR(mesh_volume(solid.mesh), solid.measures.volume, 1e-6 * solid.measures.volume);
    for (const Particle& p : c.particles) EXPECT_GT(winding_number(solid.mesh, p.position), 0.5);
  }
}

TEST(Solid, EverySurfaceVertexLiesWithinAVoxelOfTheAnalyticSurface) {
  const Cluster c = small_tree(60, 11);
  const std::vector<float> radii = pipe_radii(c);
  const Solid solid = build_solid(c, radii, {});
  const Union distance(c, radii);  // the union as grown, not widened for meshing
  double worst = 0.0;
  for (std::size_t v = 0; v < solid.mesh.vertices.size(); ++v)
    worst = std::max(worst, std::abs(distance(solid.mesh.vertices[v].cast<double>())));
  EXPECT_LT(worst, solid.measures.voxel);
}

TEST(Solid, IsClosedOrientedFreeOfSelfIntersectionsAndOneShellATree) {
  // Three seeds, three trees; joined by their bars, one piece.
  const Cluster c = small_tree(300, 3, {Vec3(-8, 0, 0), Vec3(8, 0, 0), Vec3(0, 9, 0)});
  const std::vector<float> radii = pipe_radii(c);
  for (const bool join : {false, true}) {
    SCOPED_TRACE(join ? "joined" : "apart");
    SolidOptions o;
    o.join_seeds = join;
    const Solid solid = build_solid(c, radii, o);
    EXPECT_EQ(edge_faults(solid.mesh), "");
    EXPECT_FALSE(self_intersects(solid.mesh));
    EXPECT_EQ(face_components(solid.mesh), join ? 1u : 3u);
    EXPECT_EQ(solid.measures.shells, face_components(solid.mesh));
    EXPECT_GT(solid.measures.volume, 0.0);
  }
}

TEST(Solid, EveryModelAndShapeGivesAClosedSolid) {
  AttractorOptions attractors;
  attractors.count = 400;
  attractors.radius = 15.0;
  const Cluster tree = colonize(ColonizationOptions{}, scatter_attractors(attractors, 4, 3), {Vec3::Zero()});
  EdenOptions options;
  options.sites = 400;
  options.rng_seed = 2;
  const Cluster lattice = eden(options);
  struct Case {
    const char* name;
    const Cluster& cluster;
    SolidShape shape;
    double smooth;
  };
  const Cluster dla = small_tree(200, 8);
  for (const Case& k : {Case{"colonize", tree, SolidShape::branches, 0.0}, Case{"eden cubes", lattice, SolidShape::cubes, 0.0},
                        Case{"eden spheres", lattice, SolidShape::spheres, 0.0},
                        Case{"dla blob", dla, SolidShape::spheres, 0.6}, Case{"dla smooth", dla, SolidShape::branches, 0.5}}) {
    SCOPED_TRACE(k.name);
    SolidOptions o;
    o.shape = k.shape;
    o.smooth = k.smooth;
    LookOptions look;
    look.radius.model = RadiusModel::uniform;
    look.radius.base_radius = 0.6;  // spheres a spacing apart overlap
    const std::vector<float> radii = make_look(k.cluster, look).radii;
    const Solid solid = build_solid(k.cluster, radii, o);
    EXPECT_EQ(edge_faults(solid.mesh), "");
    EXPECT_FALSE(self_intersects(solid.mesh));
    EXPECT_EQ(face_components(solid.mesh), 1u);
    EXPECT_EQ(solid.measures.shells, 1u);
    for (const Particle& p : k.cluster.particles) ASSERT_GT(winding_number(solid.mesh, p.position), 0.5);
  }
}

TEST(Solid, SmoothingOnlyAddsToTheSolid) {
  const Cluster c = small_tree(150, 21);
  const std::vector<float> radii = pipe_radii(c);
  const Solid sharp = build_solid(c, radii, {});
  SolidOptions o;
  o.smooth = 0.5;
  const Solid smooth = build_solid(c, radii, o);
  // A closing holds the set it closes: more volume, every sharp vertex inside or on it.
  EXPECT_GT(smooth.measures.volume, sharp.measures.volume);
  EXPECT_LT(smooth.measures.volume, 1.6 * sharp.measures.volume);
  const double voxel = sharp.measures.voxel;
  const openvdb::FloatGrid& grid = *smooth.grid->surface;
  // Every vertex of the sharp mesh is inside the smooth surface or within a voxel of it: the
  // smooth grid's distance, interpolated at the vertex.
  auto access = grid.getConstAccessor();
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < sharp.mesh.vertices.size(); ++v) {
    const Eigen::Vector3f& p = sharp.mesh.vertices[v];
    const openvdb::Vec3d at = grid.transform().worldToIndex(openvdb::Vec3d(p.x(), p.y(), p.z()));
    const double distance = openvdb::tools::BoxSampler::sample(access, at);
    worst = std::max(worst, distance);
    ASSERT_LT(distance, voxel) << "vertex " << v;
  }
  std::printf("the sharp mesh lies at most %.2f voxels outside the smooth surface\n", worst / voxel);
}

TEST(Solid, PrintSizeGivesTheLongestSideAndTheThinnestWall) {
  const Cluster c = small_tree(400, 13);
  const std::vector<float> radii = pipe_radii(c);
  for (const double size : {40.0, 120.0}) {
    SCOPED_TRACE(size);
    SolidOptions o;
    o.print_size = size;
    o.min_wall = 1.2;
    const Solid solid = build_solid(c, radii, o);
    EXPECT_NEAR(solid.measures.size.maxCoeff(), size, 1e-4 * size);
    EXPECT_EQ(edge_faults(solid.mesh), "");
    // The walls, measured on the mesh: every particle's centre lies at least half min_wall and
    // its own radius deep (within a voxel, where facets cut inside), and the shallowest is
    // half the thinnest wall the measures give.
    const double voxel = solid.measures.voxel, scale = solid.measures.scale;
    TriangleMesh written;
    for (const Eigen::Vector3f& v : solid.mesh.vertices) written.vertices.push_back(v.cast<double>());
    written.triangles = solid.mesh.triangles;
    double shallowest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < c.particles.size(); ++i) {
      const Vec3 at = (c.particles[i].position - solid.origin) * scale;
      ASSERT_GT(winding_number(solid.mesh, at), 0.5) << "particle " << i << " is outside";
      const double depth = testing::brute_distance(written, at);
      shallowest = std::min(shallowest, depth);
      ASSERT_GT(depth, std::max(o.min_wall / 2.0, radii[i] * c.spacing * scale) - voxel) << "particle " << i;
    }
    EXPECT_NEAR(2.0 * shallowest, solid.measures.thinnest_wall, 2.0 * voxel);
    Eigen::AlignedBox3f box;
    for (const Eigen::Vector3f& v : solid.mesh.vertices) box.extend(v);
    EXPECT_NEAR(box.sizes().maxCoeff(), size, 1e-4 * size);
    // At 40 mm the tips (0.25 spacings, a 0.5-spacing wall) are thinner than 1.2 mm.
    if (size == 40.0) {
      EXPECT_GT(solid.measures.thickened, 0u);
    }
  }
}

TEST(Solid, RefusesWhatWouldNotFitAndNamesAVoxelThatDoes) {
  const Cluster c = small_tree(2000, 6);
  const std::vector<float> radii = pipe_radii(c);
  SolidOptions o;
  o.voxel = 0.01;
  o.memory = 50;  // MB
  std::string message;
  try {
    build_solid(c, radii, o);
  } catch (const InvalidInput& e) {
    message = e.what();
  }
  ASSERT_NE(message.find("`solid_voxel` 0.01 spacings would take about"), std::string::npos) << message;
  ASSERT_EQ(message.find('\n'), std::string::npos);
  const std::size_t at = message.rfind("`solid_voxel` ");
  ASSERT_NE(message.find(" fits", at), std::string::npos) << message;
  o.voxel = std::stod(message.substr(at + 14));
  EXPECT_GT(o.voxel, 0.01);
  const Solid solid = build_solid(c, radii, o);  // the named voxel fits under the same limit
  EXPECT_EQ(face_components(solid.mesh), 1u);
  EXPECT_GT(solid.measures.estimated_bytes, 0.0);
  EXPECT_LE(solid.measures.estimated_bytes, o.memory * 1e6);
  EXPECT_GT(solid.measures.estimated_seconds, 0.0);
}

// The bound a run refuses a solid by before growth never passes the plan of a structure it
// describes: whatever it refuses, the plan after growth would have refused too.
TEST(Solid, TheLeastBytesBeforeGrowthNeverPassTheGrownStructuresPlan) {
  EdenOptions sites;
  sites.sites = 1500;
  sites.rng_seed = 3;
  sites.lattice = Lattice::cubic6;
  DlaOptions flat;
  flat.particles = 1500;
  flat.dimensions = 2;
  flat.rng_seed = 4;
  const Cluster lattice = eden(sites), dla = small_tree(1500, 5), plane = grow(flat);
  struct Case {
    const char* name;
    const Cluster& cluster;
    SolidShape shape;
    RadiusModel radius;
  };
  for (const Case& k : {Case{"dla taper", dla, SolidShape::branches, RadiusModel::taper},
                        Case{"dla pipe", dla, SolidShape::branches, RadiusModel::pipe},
                        Case{"dla 2d spheres", plane, SolidShape::spheres, RadiusModel::uniform},
                        Case{"eden cubes", lattice, SolidShape::cubes, RadiusModel::uniform}}) {
    LookOptions look;
    look.radius.model = k.radius;
    const std::vector<float> radii = make_look(k.cluster, look).radii;
    SolidForecast forecast{k.cluster.particles.size() - k.cluster.seed_count, 1.0, 0.0, 0.0};
    forecast.least_radius = std::min(look.radius.tip_radius, look.radius.base_radius);
    forecast.most_radius = std::max(look.radius.tip_radius, look.radius.base_radius);
    for (const double voxel : {0.0, 0.08, 0.2})
      for (const double smooth : {0.0, 0.3}) {
        SCOPED_TRACE(std::string(k.name) + " voxel " + std::to_string(voxel) + " smooth " + std::to_string(smooth));
        SolidOptions o;
        o.shape = k.shape;
        o.voxel = voxel;
        o.smooth = smooth;
        o.memory = 1e9;  // MB: planned, never refused
        const double least = least_solid_bytes(forecast, o);
        EXPECT_GT(least, 0.0);
        EXPECT_LE(least, plan_solid(k.cluster, radii, o).bytes);
      }
  }
  // What promises nothing bounds nothing.
  SolidOptions o;
  EXPECT_EQ(least_solid_bytes({0, 1.0, 0.25, 0.5}, o), 0.0);
  EXPECT_EQ(least_solid_bytes({1000, 0.0, 0.25, 0.5}, o), 0.0);
  o.print_size = 50.0;  // the voxel then follows min_wall, in millimetres the growth sets
  EXPECT_EQ(least_solid_bytes({1000, 1.0, 0.25, 0.5}, o), 0.0);
}

// A solid that no structure of the count fits is refused with a voxel that the bound lets
// through, and that voxel is not refused.
TEST(Solid, ASolidThatCannotFitIsRefusedBeforeGrowthWithAVoxelThatMay) {
  const SolidForecast forecast{1'000'000, 1.0, 0.25, 0.5};
  SolidOptions o;
  o.voxel = 0.002;
  o.memory = 1000;  // MB
  std::string message;
  try {
    refuse_solid_before_growth(forecast, o);
  } catch (const InvalidInput& e) {
    message = e.what();
  }
  ASSERT_EQ(message.rfind("the solid of 1,000,000 particles at `solid_voxel` 0.002 spacings would take at least ", 0), 0u)
      << message;
  ASSERT_EQ(message.find('\n'), std::string::npos);
  const std::size_t at = message.rfind("`solid_voxel` ");
  ASSERT_NE(message.find(" or more", at), std::string::npos) << message;
  o.voxel = std::stod(message.substr(at + 14));
  EXPECT_GT(o.voxel, 0.002);
  EXPECT_NO_THROW(refuse_solid_before_growth(forecast, o));
  EXPECT_LE(least_solid_bytes(forecast, o), o.memory * 1e6);
}

TEST(Solid, BadOptionsAreRefusedByName) {
  const std::map<std::string, SolidOptions> cases = [] {
    std::map<std::string, SolidOptions> m;
    m["`solid_voxel`"].voxel = -1;
    m["`solid_smooth`"].smooth = 1e9;
    m["`solid_adaptivity`"].adaptivity = 2;
    m["`print_size`"].print_size = -5;
    m["`min_wall`"].min_wall = std::nan("");
    m["`solid_memory`"].memory = 0.5;
    return m;
  }();
  for (const auto& [name, options] : cases) {
    SCOPED_TRACE(name);
    try {
      validate(options);
      ADD_FAILURE() << "accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST(Solid, ObjHoldsTheMeshOverManyBatches) {
  // The solid is one piece, larger than the OBJ writer's batches of 32,768 lines: it is split
  // over several, formatted on several threads.
  const Cluster c = small_tree(500, 31);
  const Look look = make_look(c, {});
  const Solid solid = build_solid(c, look.radii, {});
  ASSERT_GT(solid.mesh.vertices.size() + solid.mesh.triangles.size(), 3u * 32768) << "too small to span batches";
  ScratchDir dir;
  write_solid_obj(solid, c, look, dir / "s.obj");
  TubePiece piece;
  piece.positions = solid.mesh.vertices;
  piece.triangles = solid.mesh.triangles;
  testing::expect_obj_holds(read_file(dir / "s.obj"), {piece});
}

TEST(Solid, TheSameFilesOnAnyThreadCount) {
  const Cluster c = small_tree(500, 31);
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  options.color_by = ColorBy::age;
  const Look look = make_look(c, options);
  ScratchDir dir;
  std::map<std::string, std::string> first;
  for (const int threads : {1, 2, 3}) {
    SolidOptions o;
    o.threads = threads;
    const Solid solid = build_solid(c, look.radii, o);
    write_stl(solid, dir / "s.stl");
    write_3mf(solid, dir / "s.3mf");
    write_vdb(solid, c, look, dir / "s.vdb");
    write_solid_glb(solid, c, look, dir / "s.glb");
    write_solid_obj(solid, c, look, dir / "s.obj");
    for (const char* file : {"s.stl", "s.3mf", "s.vdb", "s.glb", "s.obj"}) {
      const std::string bytes = read_file(dir / file);
      ASSERT_GT(bytes.size(), 1000u) << file;
      if (threads == 1) first[file] = bytes;
      else EXPECT_TRUE(bytes == first[file]) << file << " differs on " << threads << " threads";
    }
  }
  // The closing goes through OpenVDB's own threaded rebuilds.
  for (const int threads : {1, 2}) {
    SolidOptions o;
    o.threads = threads;
    o.smooth = 0.4;
    const Solid solid = build_solid(c, look.radii, o);
    write_stl(solid, dir / "smooth.stl");
    const std::string bytes = read_file(dir / "smooth.stl");
    if (threads == 1) first["smooth"] = bytes;
    else EXPECT_TRUE(bytes == first["smooth"]) << "the smoothed solid differs on 2 threads";
  }
}

}  // namespace
}  // namespace dla
