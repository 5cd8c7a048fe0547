// The look: attributes against definitions computed the slow way, distances against brute
// force, the radius models' ranges and orderings, tube meshes that are closed, outward and
// untwisted, instancing points that never overlap, and the files built from them.

#include "dla/mesh/constraint.h"
#include "dla/io/csv_reader.h"
#include "dla/io/csv_writer.h"
#include "dla/models/dla.h"
#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/io/mesh_writers.h"
#include "dla/io/ply_writer.h"
#include "dla/io/pov_writer.h"
#include "dla/mesh/shapes.h"
#include "dla/mesh/surface_distance.h"
#include "dla/io/svg_writer.h"
#include "io/glb_limit.h"
#include "mesh_util.h"
#include "test_util.h"
#include "tube_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>

namespace dla {
namespace {

using testing::ScratchDir;
using testing::read_file;

Cluster grown(std::size_t particles, int dimensions = 3, std::vector<Vec3> seeds = {Vec3::Zero()}) {
  DlaOptions o;
  o.particles = particles;
  o.dimensions = dimensions;
  o.seeds = std::move(seeds);
  return grow(o);
}

//! Growth from the centre of a ball of `radius` (a sphere mesh), walkers starting inside it.
struct GrownInBall {
  MeshConstraint ball;
  Cluster cluster;
  GrownInBall(double radius, std::size_t particles)
      : ball(make_sphere(Vec3::Zero(), radius, 12, 24), {}, 1.0), cluster([&] {
          DlaOptions o;
          o.particles = particles;
          o.spawn = SpawnMode::inside;
          return grow(o, ball);
        }()) {}
};

//! `mesh` with vertex colours: red where x > 2, white elsewhere.
TriangleMesh painted_red_past_x2(TriangleMesh mesh) {
  for (const Vec3& v : mesh.vertices) mesh.colors.push_back(v.x() > 2.0 ? Vec3(1, 0, 0) : Vec3(1, 1, 1));
  return mesh;
}

//! A straight chain of `n` particles along x from the origin, a spacing apart.
Cluster chain(std::size_t n) {
  Cluster c;
  c.seed_count = 1;
  for (std::size_t i = 0; i < n; ++i)
    c.particles.push_back({Vec3(static_cast<double>(i), 0, 0), static_cast<std::int32_t>(i) - 1, 0});
  return c;
}

TEST(Attributes, MatchTheirDefinitions) {
  const Cluster c = grown(3000, 3, {Vec3(-8, 0, 0), Vec3(8, 0, 0)});
  const Attributes a = compute_attributes(c);
  const std::size_t n = c.particles.size();
  ASSERT_EQ(a.size(), n);
  std::vector<std::vector<std::size_t>> children(n);
  for (std::size_t i = 0; i < n; ++i)
    if (c.particles[i].parent >= 0) children[static_cast<std::size_t>(c.particles[i].parent)].push_back(i);
  // Strahler's definition, recursively.
  std::function<int(std::size_t)> strahler = [&](std::size_t i) {
    if (children[i].empty()) return 1;
    int highest = 0, times = 0;
    for (std::size_t k : children[i]) {
      const int o = strahler(k);
      if (o > highest) highest = o, times = 1;
      else if (o == highest) ++times;
    }
    return times >= 2 ? highest + 1 : highest;
  };
  std::function<std::size_t(std::size_t)> subtree = [&](std::size_t i) {
    std::size_t size = 0;
    for (std::size_t k : children[i]) size += 1 + subtree(k);
    return size;
  };
  std::vector<int> descendants(n, 0);
  double seed_reach = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    int depth = 0;
    for (std::int32_t j = c.particles[i].parent; j >= 0; j = c.particles[static_cast<std::size_t>(j)].parent) {
      ++depth;
      ++descendants[static_cast<std::size_t>(j)];
    }
    ASSERT_EQ(a.depth[i], depth) << i;
    ASSERT_EQ(a.tip(i), children[i].empty());
    ASSERT_EQ(a.branch_point(i), children[i].size() >= 2);
    ASSERT_EQ(a.strahler(i), strahler(i)) << i;
    const double seed = std::min((c.particles[i].position - c.particles[0].position).norm(),
                                 (c.particles[i].position - c.particles[1].position).norm());
    ASSERT_DOUBLE_EQ(a.seed_distance(c.particles[i].position), seed);
    seed_reach = std::max(seed_reach, seed);
    // Each parent's heaviest child, the earliest of equals, goes on with its strand.
    if (c.particles[i].parent >= 0) {
      const auto& siblings = children[static_cast<std::size_t>(c.particles[i].parent)];
      std::size_t heaviest = siblings.front();
      for (std::size_t k : siblings)
        if (subtree(k) > subtree(heaviest)) heaviest = k;
      ASSERT_EQ(a.continues_strand(i), heaviest == i) << i;
    } else {
      ASSERT_FALSE(a.continues_strand(i));
    }
  }
  EXPECT_DOUBLE_EQ(a.seed_reach, seed_reach);
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(a.descendants[i], descendants[i]);
  EXPECT_EQ(a.age(0), 0.0f);
  EXPECT_EQ(a.age(2), 0.0f);
  EXPECT_EQ(a.age(n - 1), 1.0f);
  EXPECT_GT(a.age(n / 2), 0.4f);
  EXPECT_LT(a.age(n / 2), 0.6f);
  EXPECT_TRUE(a.boundary_distance.empty());
  // The taper runs from 1 at each strand's start to 0 at its tip, one step a particle.
  for (const Strand& strand : decompose_strands(c)) {
    const auto tip = static_cast<std::size_t>(strand.back());
    if (strand.size() > 1) {
      EXPECT_EQ(a.taper(tip), 0.0);
    }
    for (std::size_t k = 1; k + 1 < strand.size(); ++k) {
      const auto here = static_cast<std::size_t>(strand[k]), next = static_cast<std::size_t>(strand[k + 1]);
      EXPECT_GT(a.taper(here), a.taper(next));
      EXPECT_NEAR(a.taper(here), 1.0 - static_cast<double>(k) / static_cast<double>(strand.size() - 1), 1e-5);
    }
  }
}

TEST(Attributes, TheDeepestTreeAChainOf100000IsMeasuredWithoutRecursion) {
  // A chain is the deepest tree: a recursive walk would overflow the stack here (bench/ times
  // the attributes; this only checks what they say of it).
  const Cluster c = chain(100000);
  const Attributes a = compute_attributes(c);
  EXPECT_EQ(a.depth.back(), 99999);
  EXPECT_EQ(a.descendants.front(), 99999);
  EXPECT_EQ(a.strahler(0), 1);
}

// Embree's point queries against a scan of every triangle: far away, near the surface (where
// the floats' rounding matters), from any hint, and on a mesh with a degenerate triangle.
TEST(SurfaceDistance, ClosestPointsMatchBruteForce) {
  TriangleMesh mesh = make_sphere(Vec3(1, 2, 3), 10.0, 12, 24);
  mesh.triangles.push_back({0, 1, 1});  // a degenerate triangle: a segment
  const SurfaceDistance surface(mesh);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-20, 20), unit(0, 1);
  std::uniform_int_distribution<std::uint32_t> any(0, static_cast<std::uint32_t>(mesh.triangles.size() - 1));
  for (int i = 0; i < 600; ++i) {
    Vec3 p(u(rng), u(rng), u(rng));
    if (i % 2) {  // within a millionth of a point of the surface
      const auto& t = mesh.triangles[any(rng) % (mesh.triangles.size() - 1)];
      double a = unit(rng), b = unit(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3 &x = mesh.vertices[t[0]], &y = mesh.vertices[t[1]], &z = mesh.vertices[t[2]];
      p = x + a * (y - x) + b * (z - x) + 1e-6 * (2 * unit(rng) - 1) * (y - x).cross(z - x).normalized();
    }
    const double brute = testing::brute_distance(mesh, p);
    const SurfaceDistance::Closest closest = surface.closest(p);
    ASSERT_NEAR((closest.point - p).norm(), brute, 1e-12 * (1 + brute)) << p.transpose();
    const auto& t = mesh.triangles[closest.triangle];
    EXPECT_NEAR(testing::brute_distance({mesh.vertices, {t}, {}}, closest.point), 0.0, 1e-9);
    // A hint only speeds the search: any triangle, far or near, gives the same point.
    for (const std::uint32_t hint : {any(rng), closest.triangle, SurfaceDistance::kNoHint}) {
      const SurfaceDistance::Closest hinted = surface.closest(p, hint);
      ASSERT_EQ(hinted.triangle, closest.triangle);
      ASSERT_EQ(hinted.point, closest.point);
    }
  }
  // Beyond the range of floats, the scan answers.
  EXPECT_NEAR(surface.distance(Vec3(1e100, 2, 3)), 1e100, 1e86);
  EXPECT_THROW(SurfaceDistance(TriangleMesh{}), InvalidInput);
}

// Where two triangles are equally near, the one listed first is the answer, from every hint.
TEST(SurfaceDistance, TiesGoToTheTriangleListedFirst) {
  const TriangleMesh box = make_box(Vec3::Zero(), Vec3(2, 2, 2));
  const SurfaceDistance surface(box);
  const Vec3 center(1, 1, 1);  // as near to all twelve
  std::uint32_t first = 0;  // the least (squared distance, index)
  double least = std::numeric_limits<double>::infinity();
  for (std::uint32_t t = 0; t < box.triangles.size(); ++t) {
    const auto& tri = box.triangles[t];
    const double d = (closest_point_on_triangle(center, box.vertices[tri[0]], box.vertices[tri[1]], box.vertices[tri[2]]) -
                      center).squaredNorm();
    if (d < least) least = d, first = t;
  }
  EXPECT_NEAR(least, 1.0, 1e-12);
  for (std::uint32_t hint = 0; hint < box.triangles.size(); ++hint) ASSERT_EQ(surface.closest(center, hint).triangle, first);
  EXPECT_EQ(surface.closest(center).triangle, first);
}

TEST(Attributes, BoundaryDistanceIsTheSurfacesOnAnyThreadCount) {
  const GrownInBall grown(20.0, 6000);  // more than 4096: the distances are measured on two threads
  const MeshConstraint& ball = grown.ball;
  const Cluster& c = grown.cluster;
  const SurfaceDistance surface(ball.mesh());
  const Attributes one = compute_attributes(c, {&surface, nullptr, 1});
  const Attributes two = compute_attributes(c, {&surface, nullptr, 2});
  ASSERT_EQ(one.boundary_distance, two.boundary_distance);
  for (std::size_t i = 0; i < c.particles.size(); i += 97)
    ASSERT_NEAR(one.boundary_distance[i], testing::brute_distance(ball.mesh(), c.particles[i].position), 1e-5);
}

TEST(Attributes, ClosestTrianglesMeasuredBeforeAreTakenForTheSameParticlesOnly) {
  const GrownInBall grown(20.0, 6000);
  const Cluster& c = grown.cluster;
  const TriangleMesh painted = painted_red_past_x2(grown.ball.mesh());
  const SurfaceDistance surface(painted);
  const Paint red = parse_paint("red,0.3");
  const AttributeOptions fresh{&surface, nullptr, 2, true, &red, &painted};
  const Attributes expected = compute_attributes(c, fresh);
  // As a run measures them while it grows: the first particles' closest triangles.
  MeasuredClosest before;
  before.surface = &surface;
  for (std::size_t i = 0; i < 2500; ++i) {
    before.triangles.push_back(surface.closest(c.particles[i].position).triangle);
    before.positions_hash = MeasuredClosest::hash_with(before.positions_hash, c.particles[i].position);
  }
  AttributeOptions taking = fresh;
  taking.measured = &before;
  const Attributes taken = compute_attributes(c, taking);
  EXPECT_EQ(taken.boundary_distance, expected.boundary_distance);
  EXPECT_EQ(taken.on_paint, expected.on_paint);
  EXPECT_EQ(taken.boundary_reach, expected.boundary_reach);

  // Taken, not measured again: the farthest triangle in place of one shows.
  const std::size_t k = 1234;
  const Vec3& p = c.particles[k].position;
  std::uint32_t farthest = 0;
  double far = 0.0;
  for (std::uint32_t t = 0; t < painted.triangles.size(); ++t) {
    const auto& corners = painted.triangles[t];
    const double d = (closest_point_on_triangle(p, painted.vertices[corners[0]], painted.vertices[corners[1]],
                                                painted.vertices[corners[2]]) - p).norm();
    if (d > far) far = d, farthest = t;
  }
  MeasuredClosest wrong = before;
  wrong.triangles[k] = farthest;
  taking.measured = &wrong;
  EXPECT_EQ(compute_attributes(c, taking).boundary_distance[k], static_cast<float>(far));
  // Not for particles elsewhere, another surface, or more particles than the cluster has.
  Cluster moved = c;
  moved.particles[10].position.y() += 1e-9;
  EXPECT_EQ(compute_attributes(moved, taking).boundary_distance[k], expected.boundary_distance[k]);
  const SurfaceDistance other(painted);
  MeasuredClosest elsewhere = wrong;
  elsewhere.surface = &other;
  taking.measured = &elsewhere;
  EXPECT_EQ(compute_attributes(c, taking).boundary_distance[k], expected.boundary_distance[k]);
  Cluster fewer = c;
  fewer.particles.resize(2000);
  taking.measured = &wrong;
  EXPECT_EQ(compute_attributes(fewer, taking).boundary_distance[k], expected.boundary_distance[k]);
}

TEST(Attributes, TipGapsAreTheSameOnAnyThreadCount) {
  const Cluster c = grown(16000);  // over 4096 tips: the look-ups are shared by two threads
  const Attributes one = compute_attributes(c, {nullptr, nullptr, 1});
  const Attributes two = compute_attributes(c, {nullptr, nullptr, 2});
  ASSERT_GE(one.tip_gaps.size(), 4096u);
  ASSERT_EQ(one.tip_gaps, two.tip_gaps);
  std::vector<Vec3> tips;
  for (std::size_t i = 0; i < c.particles.size(); ++i)
    if (one.tip(i)) tips.push_back(c.particles[i].position);
  for (std::size_t k = 0; k < tips.size(); k += 211) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < tips.size(); ++j)
      if (j != k) nearest = std::min(nearest, (tips[k] - tips[j]).norm());
    ASSERT_LE(one.tip_gaps[k], 0.5 * nearest) << k;
    ASSERT_NEAR(one.tip_gaps[k], 0.5 * nearest, 1e-4) << k;
  }
}

TEST(RadiusModels, StayInRangeAndOrderAsTheySay) {
  const GrownInBall grown(14.0, 3000);
  const Cluster& c = grown.cluster;
  const SurfaceDistance surface(grown.ball.mesh());
  const Attributes a = compute_attributes(c, {&surface});
  for (const RadiusModel model : {RadiusModel::taper, RadiusModel::pipe, RadiusModel::boundary,
                                  RadiusModel::seed_distance, RadiusModel::uniform}) {
    SCOPED_TRACE(std::string(to_string(model)));
    RadiusOptions r;
    r.model = model;
    r.tip_radius = 0.1;
    r.base_radius = 0.6;
    const std::vector<float> radii = branch_radii(r, c, a);
    for (const float radius : radii) {
      ASSERT_GE(radius, 0.1f - 1e-6f);
      ASSERT_LE(radius, 0.6f + 1e-6f);
    }
    const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
    if (model == RadiusModel::uniform) EXPECT_EQ(*lo, *hi);
    else EXPECT_GT(*hi - *lo, 0.25f) << "the model spans its range";
    for (std::size_t i = 0; i < c.particles.size(); ++i) {
      const auto parent = static_cast<std::size_t>(std::max(c.particles[i].parent, 0));
      if (model == RadiusModel::pipe && c.particles[i].parent >= 0) {
        ASSERT_GE(radii[parent], radii[i]);
      }
      if (model == RadiusModel::boundary && a.boundary_distance[i] > a.boundary_distance[parent]) {
        ASSERT_GE(radii[i], radii[parent]);
      }
      if (model == RadiusModel::seed_distance &&
          a.seed_distance(c.particles[i].position) > a.seed_distance(c.particles[parent].position)) {
        ASSERT_LE(radii[i], radii[parent]);
      }
    }
  }
  RadiusOptions pipe;
  pipe.model = RadiusModel::pipe;
  pipe.tip_radius = 0.1;
  pipe.base_radius = 100;
  pipe.pipe_exponent = 3;
  const std::vector<float> radii = branch_radii(pipe, c, a);
  EXPECT_NEAR(radii[0], 0.1 * std::cbrt(a.descendants[0] + 1.0), 1e-5) << "r = tip (d + 1)^(1/e)";

  RadiusOptions boundary;
  boundary.model = RadiusModel::boundary;
  EXPECT_THROW(branch_radii(boundary, c, compute_attributes(c)), InvalidInput);
  RadiusOptions bad;
  bad.pipe_exponent = 0.5;
  EXPECT_THROW(branch_radii(bad, c, a), InvalidInput);
  EXPECT_EQ(parse_word<RadiusModel>("seed-distance"), RadiusModel::seed_distance);
  EXPECT_THROW(parse_word<RadiusModel>("wavy"), InvalidInput);
}

//! Every tube is a closed surface (its seam welded) facing outward, with a texture frame.
void expect_closed_and_outward(const TubePiece& piece, const Vec3& inside) {
  double volume = 0.0;
  for (const auto& t : piece.triangles) {
    const Vec3 a = piece.positions[t[0]].cast<double>() - inside, b = piece.positions[t[1]].cast<double>() - inside,
               c = piece.positions[t[2]].cast<double>() - inside;
    volume += a.dot(b.cross(c)) / 6.0;
  }
  testing::expect_closed(piece);
  EXPECT_GT(volume, 0.0) << "faces point inwards";
  for (const Eigen::Vector3f& n : piece.normals) ASSERT_NEAR(n.norm(), 1.0f, 1e-5f);
  testing::expect_texture_frame(piece);
}

TEST(Tubes, AreClosedOutwardAndAsWideAsTheirRadii) {
  const Cluster c = grown(800);
  const Look look = make_look(c, {});
  const std::vector<float> radii = look.radii;
  std::size_t pieces = 0, vertices = 0;
  for_each_tube(c, look.attributes, radii, look.options.tubes, [&](const TubePiece& piece) {
    ++pieces;
    vertices += piece.positions.size();
    const std::size_t rings = (piece.positions.size() - 2) / 9 - 1;  // 8 sides and the seam
    ASSERT_EQ(piece.positions.size(), tube_vertices(rings, 8));
    ASSERT_EQ(piece.triangles.size(), tube_triangles(rings, 8));
    // The start's centre is the strand's first particle, inside the tube.
    const Vec3 start = piece.positions.back().cast<double>();
    expect_closed_and_outward(piece, start);
    // Each ring's vertices lie at the radius from their particle (ring 0 may be finer).
    for (std::size_t j = 1; j < rings; ++j) {
      const auto owner = static_cast<std::size_t>(piece.particles[j * 9]);
      for (std::size_t s = 0; s < 9; ++s) {
        const double d = (piece.positions[j * 9 + s].cast<double>() - c.particles[owner].position).norm();
        ASSERT_NEAR(d, radii[owner], 1e-4);
      }
    }
    // A branch starts inside its parent: ring 0 is no wider than the parent's radius.
    const auto first = static_cast<std::size_t>(piece.particles[0]);
    const std::int32_t parent = c.particles[first].parent;
    if (parent >= 0)
      for (std::size_t s = 0; s < 9; ++s) {
        const double d = (piece.positions[s].cast<double>() - c.particles[static_cast<std::size_t>(parent)].position).norm();
        ASSERT_LE(d, radii[static_cast<std::size_t>(parent)] + 1e-4);
      }
  });
  EXPECT_EQ(pieces, count_strands(c));
}

TEST(Tubes, PruneTwigsWithoutLeavingPiecesAfloat) {
  const Cluster c = grown(1500);
  const Attributes a = compute_attributes(c);
  const Look look = make_look(c, {});
  TubeOptions pruned;
  pruned.min_branch = 6;
  std::size_t all = 0, kept = 0;
  std::set<std::int32_t> tubed;  // particles with a ring
  const std::vector<float> radii = look.radii;
  for_each_tube(c, look.attributes, radii, {}, [&](const TubePiece&) { ++all; });
  std::vector<std::size_t> starts;  // each kept tube's first own particle
  for_each_tube(c, look.attributes, radii, pruned, [&](const TubePiece& piece) {
    ++kept;
    const auto own = static_cast<std::size_t>(piece.particles[0]);
    EXPECT_GE(a.descendants[own] + 1, 6) << "a twig kept";
    starts.push_back(own);
    tubed.insert(piece.particles.begin(), piece.particles.end());
  });
  // Each kept tube's branch point belongs to a kept tube, or is a seed.
  for (const std::size_t own : starts) {
    const std::int32_t from = c.particles[own].parent;
    if (from >= 0) {
      EXPECT_TRUE(tubed.count(from) || from < static_cast<std::int32_t>(c.seed_count)) << "afloat";
    }
  }
  EXPECT_LT(kept, all / 2);
  EXPECT_GT(kept, 0u);
}

TEST(Tubes, DoNotTwistAndSimplifyStraightRuns) {
  const Cluster line = chain(20);
  const Attributes a = compute_attributes(line);
  const std::vector<float> radii(20, 0.3f);
  std::vector<Eigen::Vector3f> first;
  for_each_tube(line, a, radii, {}, [&](const TubePiece& piece) {
    ASSERT_EQ(piece.positions.size(), tube_vertices(20, 8));
    // Along a straight strand every ring is the first one moved along x: no twist.
    for (std::size_t j = 1; j < 20; ++j)
      for (std::size_t s = 0; s < 9; ++s) {
        const Eigen::Vector3f moved = piece.positions[s] + Eigen::Vector3f(static_cast<float>(j), 0, 0);
        ASSERT_LT((piece.positions[j * 9 + s] - moved).norm(), 1e-4f);
      }
  });
  TubeOptions coarse;
  coarse.tolerance = 0.1;
  coarse.sides = 6;
  for_each_tube(line, a, radii, coarse, [&](const TubePiece& piece) { EXPECT_EQ(piece.positions.size(), tube_vertices(2, 6)); });
  TubeOptions bad;
  bad.min_branch = 0;
  EXPECT_THROW(for_each_tube(line, a, radii, bad, [](const TubePiece&) {}), InvalidInput);
  bad.min_branch = 1;
  bad.sides = 2;
  EXPECT_THROW(for_each_tube(line, a, radii, bad, [](const TubePiece&) {}), InvalidInput);
}

// The texture: u once around each ring, v the path's length from the seed over the scale, a
// branch's v going on from its parent's at the joint; measured here by walking up the parents.
TEST(Tubes, TextureRunsAroundAndAlongFromParentToChild) {
  const Cluster line = chain(20);
  const Attributes a = compute_attributes(line);
  const std::vector<float> radii(20, 0.3f);
  for (const double scale : {0.0, 2.5}) {
    TubeOptions options;
    options.uv_scale = scale;
    const double expected_scale = scale > 0 ? scale : 2 * 3.14159265358979323846 * 0.3 * line.spacing;
    for_each_tube(line, a, radii, options, [&](const TubePiece& piece) {
      testing::expect_texture_frame(piece);
      for (std::size_t j = 0; j < 20; ++j)
        for (std::size_t s = 0; s < 9; ++s) {
          ASSERT_FLOAT_EQ(piece.uvs[j * 9 + s].x(), static_cast<float>(s) / 8.0f);
          ASSERT_NEAR(piece.uvs[j * 9 + s].y(), static_cast<double>(j) * line.spacing / expected_scale, 1e-5);
        }
    });
  }
  for (const double bad : {-1.0, 1e-10, 2e9, std::nan("")}) {
    TubeOptions options;
    options.uv_scale = bad;
    EXPECT_THROW(validate(options), InvalidInput) << bad;
  }

  const Cluster c = grown(1500);
  const Look look = make_look(c, {});
  const std::vector<float> r = look.radii;
  const double scale = 2 * 3.14159265358979323846 * *std::max_element(r.begin(), r.end()) * c.spacing;
  const auto v_at = [&](std::size_t i) {  // the path to the seed, step by step
    double length = 0.0;
    for (; c.particles[i].parent >= 0; i = static_cast<std::size_t>(c.particles[i].parent))
      length += (c.particles[i].position - c.particles[static_cast<std::size_t>(c.particles[i].parent)].position).norm();
    return length / scale;
  };
  std::map<std::int32_t, float> own_v;        // each particle's v on its own ring
  std::vector<std::pair<std::int32_t, float>> first_v;  // each branch's joint and its first ring's v
  std::size_t branches = 0;
  for_each_tube(c, look.attributes, r, look.options.tubes, [&](const TubePiece& piece) {
    const std::size_t rings = (piece.positions.size() - 2) / 9 - 1;
    for (std::size_t j = 1; j < rings; ++j) {
      const std::int32_t owner = piece.particles[j * 9];
      own_v[owner] = piece.uvs[j * 9].y();
      ASSERT_NEAR(piece.uvs[j * 9].y(), v_at(static_cast<std::size_t>(owner)), 1e-4);
    }
    const std::int32_t joint = c.particles[static_cast<std::size_t>(piece.particles[0])].parent;
    if (joint < 0) {
      EXPECT_EQ(piece.uvs[0].y(), 0.0f) << "a seed's strand starts at v = 0";
      own_v[piece.particles[0]] = 0.0f;
      return;
    }
    ++branches;
    first_v.emplace_back(joint, piece.uvs[0].y());
    ASSERT_NEAR(piece.uvs[0].y(), v_at(static_cast<std::size_t>(joint)), 1e-4);
  });
  EXPECT_GT(branches, 50u);
  for (const auto& [joint, v] : first_v) {
    ASSERT_EQ(own_v.count(joint), 1u) << "a joint without a ring in its parent's tube";
    EXPECT_EQ(v, own_v[joint]) << "a branch's v does not go on from its parent's";
  }
}

TEST(Instances, NeverOverlapAndPointAwayFromTheirParents) {
  const Cluster c = grown(2000);
  const Attributes a = compute_attributes(c);
  const std::vector<Instance> tips = instancing_points(c, a, {});
  std::size_t expected = 0;
  for (std::size_t i = 0; i < c.particles.size(); ++i) expected += a.tip(i);
  ASSERT_EQ(tips.size(), expected);
  for (std::size_t i = 0; i < tips.size(); ++i) {
    ASSERT_TRUE(a.tip(static_cast<std::size_t>(tips[i].particle)));
    ASSERT_NEAR(tips[i].direction.norm(), 1.0, 1e-9);
    const Particle& p = c.particles[static_cast<std::size_t>(tips[i].particle)];
    EXPECT_GT(tips[i].direction.dot(p.position - c.particles[static_cast<std::size_t>(p.parent)].position), 0.0);
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < tips.size(); ++j) {
      if (j == i) continue;
      const double d = (tips[i].position - tips[j].position).norm();
      nearest = std::min(nearest, d);
      ASSERT_LE(tips[i].scale + tips[j].scale, d) << "copies overlap";
    }
    // Floats keep the tree small: their rounding, about 1e-6 of the size, is taken off.
    ASSERT_LE(tips[i].scale, 0.5 * nearest);
    ASSERT_NEAR(tips[i].scale, 0.5 * nearest, 1e-4);
  }
  InstanceOptions all;
  all.set = InstanceSet::all;
  EXPECT_EQ(instancing_points(c, a, all).size(), c.particles.size());
  InstanceOptions near;
  near.within = 2.0;
  EXPECT_THROW(instancing_points(c, a, near), InvalidInput) << "no mesh to be near";
}

TEST(Instances, TheSameWhetherTheAttributesHoldTheTipsGapsOrNot) {
  // Over 4096 particles: the scene's tips and strands are formatted in several ranges at once.
  ScratchDir dir;
  const Cluster c = grown(12000);
  const Look with = make_look(c, {}), without = make_look(c, {}, {nullptr, nullptr, 1, false});
  ASSERT_FALSE(with.attributes.tip_gaps.empty());
  ASSERT_TRUE(without.attributes.tip_gaps.empty());
  const std::vector<Instance> measured = instancing_points(c, without.attributes, {});
  const std::vector<Instance> stored = instancing_points(c, with.attributes, {});
  ASSERT_EQ(measured.size(), stored.size());
  for (std::size_t k = 0; k < stored.size(); ++k) {
    ASSERT_EQ(measured[k].particle, stored[k].particle);
    ASSERT_EQ(measured[k].scale, stored[k].scale);
  }
  PovOptions tips;
  tips.tips = true;
  write_pov(c, dir / "with", tips, nullptr, &with);
  write_pov(c, dir / "without", tips, nullptr, &without);
  const std::string inc = read_file(dir / "with_tips.inc");
  ASSERT_EQ(inc, read_file(dir / "without_tips.inc"));
  // Each DLA_Tip line, in order, is the k-th instance: at the tips, and with --instances all
  // (the object fill) at every particle.
  const auto expect_calls = [&](const std::string& text, const std::vector<Instance>& instances) {
    std::istringstream lines(text.substr(text.find("#declare DLA_Tips")));
    std::string line;
    std::size_t k = 0;
    while (std::getline(lines, line)) {
      if (line.rfind("  DLA_Tip(", 0) != 0) continue;
      ASSERT_LT(k, instances.size());
      const double scale = std::stod(line.substr(line.rfind(", ") + 2));
      ASSERT_NEAR(scale, instances[k].scale, 1e-5 * instances[k].scale) << line;
      const double x = std::stod(line.substr(std::strlen("  DLA_Tip(<")));
      ASSERT_NEAR(x, instances[k].position.x(), 0.5e-3 * c.spacing + 1e-9) << line;
      ++k;
    }
    EXPECT_EQ(k, instances.size());
  };
  expect_calls(inc, stored);
  tips.instances.set = InstanceSet::all;
  write_pov(c, dir / "all", tips, nullptr, &with);
  const std::vector<Instance> every = instancing_points(c, with.attributes, tips.instances);
  ASSERT_EQ(every.size(), c.particles.size());
  expect_calls(read_file(dir / "all_tips.inc"), every);
}

TEST(Instances, OnlyEveryTipTakesTheAttributesGaps) {
  // The run measures the attributes' tip gaps only for a selection of every tip; any other
  // selection must measure its own, whether the attributes hold the tips' gaps or not.
  EXPECT_TRUE(picks_every_tip({}));
  InstanceOptions all, sparse, near, unpainted;
  all.set = InstanceSet::all;
  sparse.every = 3;
  near.within = 2.0;
  unpainted.exclude_paint = Paint{};
  for (const InstanceOptions& other : {all, sparse, near, unpainted}) EXPECT_FALSE(picks_every_tip(other));
  const Cluster c = grown(3000);
  const Look with = make_look(c, {}), without = make_look(c, {}, {nullptr, nullptr, 1, false});
  for (const InstanceOptions& other : {all, sparse}) {
    const std::vector<Instance> from_with = instancing_points(c, with.attributes, other);
    const std::vector<Instance> from_without = instancing_points(c, without.attributes, other);
    ASSERT_EQ(from_with.size(), from_without.size());
    for (std::size_t k = 0; k < from_with.size(); ++k) {
      ASSERT_EQ(from_with[k].particle, from_without[k].particle);
      ASSERT_EQ(from_with[k].scale, from_without[k].scale);
    }
  }
}

TEST(Instances, EveryKthIsKeptAndGrowsIntoTheRoomLeft) {
  const Cluster c = grown(3000);
  const Look look = make_look(c, {});
  const std::vector<Instance> all = instancing_points(c, look.attributes, {});
  for (const int every : {1, 2, 3, 7, 1'000'000}) {
    InstanceOptions thin;
    thin.every = every;
    const std::vector<Instance> kept = instancing_points(c, look.attributes, thin);
    ASSERT_EQ(kept.size(), (all.size() + static_cast<std::size_t>(every) - 1) / static_cast<std::size_t>(every));
    ASSERT_EQ(count_instances(c, look.attributes, thin), kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const Instance& full = all[k * static_cast<std::size_t>(every)];
      ASSERT_EQ(kept[k].particle, full.particle) << "the first, the (every + 1)th, ... in attach order";
      // Half the gap to the nearest point kept: no smaller than among all points.
      ASSERT_GE(kept[k].scale, full.scale);
      for (std::size_t j = 0; j < kept.size(); ++j) {
        if (j == k) continue;
        ASSERT_LE(kept[k].scale + kept[j].scale, (kept[k].position - kept[j].position).norm());
      }
    }
  }
  InstanceOptions everything;
  everything.set = InstanceSet::all;
  everything.every = 4;
  EXPECT_EQ(instancing_points(c, look.attributes, everything).size(), (c.particles.size() + 3) / 4);
  for (const int every : {0, -1, 1'000'001}) {
    InstanceOptions bad;
    bad.every = every;
    EXPECT_THROW(instancing_points(c, look.attributes, bad), InvalidInput) << every;
  }
}

TEST(Instances, NoneWhoseClosestSurfacePointIsPaintedAndAllOthersKept) {
  const GrownInBall grown(10.0, 3000);
  const Cluster& c = grown.cluster;
  const TriangleMesh painted = painted_red_past_x2(grown.ball.mesh());
  const SurfaceDistance surface(painted);
  const Paint red = parse_paint("red,0.3");
  const Attributes a = compute_attributes(c, {&surface, nullptr, 2, true, &red, &painted});
  const Attributes plain = compute_attributes(c, {&surface});
  InstanceOptions options;
  options.exclude_paint = red;
  std::vector<bool> kept(c.particles.size(), false);
  for (const Instance& leaf : instancing_points(c, a, options)) kept[static_cast<std::size_t>(leaf.particle)] = true;
  std::size_t over_paint = 0, elsewhere = 0;
  for (std::size_t i = 0; i < c.particles.size(); ++i) {
    if (!a.tip(i)) {
      ASSERT_FALSE(kept[i]);
      continue;
    }
    // The closest point of every triangle, the first of the nearest, and its colour from the
    // areas of the three triangles it cuts.
    const Vec3& p = c.particles[i].position;
    double best = std::numeric_limits<double>::infinity();
    Vec3 color = Vec3::Zero();
    for (const auto& t : painted.triangles) {
      const Vec3 &x = painted.vertices[t[0]], &y = painted.vertices[t[1]], &z = painted.vertices[t[2]];
      const Vec3 q = closest_point_on_triangle(p, x, y, z);
      const double d = (q - p).norm();
      if (!(d < best)) continue;
      best = d;
      const double whole = (y - x).cross(z - x).norm();
      color = ((y - q).cross(z - q).norm() * painted.colors[t[0]] + (z - q).cross(x - q).norm() * painted.colors[t[1]] +
               (x - q).cross(y - q).norm() * painted.colors[t[2]]) / whole;
    }
    const bool red_here = red.matches(color);
    // A blend on the stroke's edge may round either way.
    if (std::abs((color - red.color).cwiseAbs().maxCoeff() - red.tolerance) < 1e-9) continue;
    ASSERT_EQ(kept[i], !red_here) << "tip " << i << " at " << p.transpose();
    (red_here ? over_paint : elsewhere) += 1;
  }
  EXPECT_GT(over_paint, 20u);
  EXPECT_GT(elsewhere, 20u);
  // With no paint to read, a clear refusal; with no colours on the mesh, another.
  EXPECT_THROW(instancing_points(c, plain, options), InvalidInput);
  EXPECT_THROW(compute_attributes(c, {&surface, nullptr, 1, true, &red, &grown.ball.mesh()}), InvalidInput);
  EXPECT_THROW(grown.ball.require_paint(red, "tips_exclude_paint"), InvalidInput) << "no colours";
  const MeshConstraint colored(painted, {}, 1.0);
  EXPECT_NO_THROW(colored.require_paint(red, "tips_exclude_paint"));
  EXPECT_THROW(colored.require_paint(parse_paint("blue"), "tips_exclude_paint"), InvalidInput);
}

TEST(Instances, NearTheBoundaryStayInsideIt) {
  const GrownInBall grown(10.0, 3000);
  const MeshConstraint& ball = grown.ball;
  const Cluster& c = grown.cluster;
  const SurfaceDistance surface(ball.mesh());
  const Attributes a = compute_attributes(c, {&surface});
  InstanceOptions near;
  near.within = 1.5;
  const std::vector<Instance> leaves = instancing_points(c, a, near);
  ASSERT_FALSE(leaves.empty());
  for (const Instance& leaf : leaves) {
    const double d = ball.distance_to_surface(leaf.position);
    EXPECT_LE(d, 1.5 + 1e-5);
    EXPECT_LE(leaf.scale, d + 1e-5) << "a copy crosses the mesh";
  }
}

TEST(LookFiles, PlyAndCsvCarryTheAttributes) {
  ScratchDir dir;
  const Cluster c = grown(500);
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  const Look look = make_look(c, options);
  write_ply(c, look, dir / "a.ply", PlyEncoding::binary);
  const std::string ply = read_file(dir / "a.ply");
  const std::size_t body = ply.find("end_header\n") + 11;
  EXPECT_NE(ply.find("property float radius\nproperty float age\nproperty int depth\nproperty int descendants\n"
                     "property uchar order\nproperty uchar tip\nproperty int seed\nproperty int parent\n"),
            std::string::npos);
  ASSERT_EQ(ply.size() - body, 38 * c.particles.size() + 8 * (c.particles.size() - 1));
  // The last particle's record, read back.
  const char* record = ply.data() + body + 38 * (c.particles.size() - 1);
  float radius;
  std::int32_t depth, parent;
  std::memcpy(&radius, record + 12, 4);
  std::memcpy(&depth, record + 20, 4);
  std::memcpy(&parent, record + 34, 4);
  EXPECT_EQ(radius, static_cast<float>(look.radius(c, c.particles.size() - 1)));
  EXPECT_EQ(depth, look.attributes.depth.back());
  EXPECT_EQ(parent, c.particles.back().parent);

  write_csv(c, look, dir / "a.csv");
  const std::string csv = read_file(dir / "a.csv");
  EXPECT_EQ(csv.rfind("id,x,y,z,parent,seed,radius,age,depth,descendants,order,tip\n", 0), 0u);
  const Cluster back = read_csv(dir / "a.csv");  // what `dla3d analyze` reads
  ASSERT_EQ(back.particles.size(), c.particles.size());
  EXPECT_EQ(back.particles.back().position, c.particles.back().position);
}

TEST(LookFiles, GlbAndObjHoldEveryTube) {
  ScratchDir dir;
  const Cluster c = grown(5000);
  LookOptions options;
  options.color_by = ColorBy::depth;
  const Look look = make_look(c, options);
  std::size_t vertices = 0, triangles = 0;
  std::vector<TubePiece> pieces;
  for_each_tube(c, look.attributes, look.radii, options.tubes, [&](const TubePiece& piece) {
    vertices += piece.positions.size();
    triangles += piece.triangles.size();
    pieces.push_back(piece);
  });
  // The OBJ writer gathers the pieces' lines in batches of 32,768 and formats them on several
  // threads: the file must still hold the pieces in the walk's order.
  ASSERT_GT(vertices + triangles, 4u * 32768) << "too few lines to span several batches";
  write_glb(c, look, dir / "a.glb");
  const std::string glb = read_file(dir / "a.glb");
  std::uint32_t head[5];
  std::memcpy(head, glb.data(), 20);
  EXPECT_EQ(head[0], 0x46546C67u);
  EXPECT_EQ(head[1], 2u);
  EXPECT_EQ(head[2], glb.size());
  EXPECT_EQ(head[4], 0x4E4F534Au) << "JSON chunk first";
  const std::string json = glb.substr(20, head[3]);
  EXPECT_NE(json.find("\"count\":" + std::to_string(vertices) + ",\"type\":\"VEC3\",\"min\""), std::string::npos);
  EXPECT_NE(json.find("\"count\":" + std::to_string(3 * triangles) + ",\"type\":\"SCALAR\"}]"), std::string::npos);
  EXPECT_NE(json.find("\"TANGENT\":2,\"TEXCOORD_0\":3,\"COLOR_0\":4,\"_AGE\":5"), std::string::npos);
  EXPECT_EQ(glb.size(), 20 + head[3] + 8 + vertices * 76 + triangles * 12) << "76-byte vertices with colour";

  write_obj(c, look, dir / "a.obj");
  const std::string obj = read_file(dir / "a.obj");
  std::size_t v = 0, vn = 0, vt = 0, f = 0;
  std::istringstream lines(obj);
  for (std::string line; std::getline(lines, line);) {
    v += line.rfind("v ", 0) == 0;
    vn += line.rfind("vn ", 0) == 0;
    vt += line.rfind("vt ", 0) == 0;
    f += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(v, vertices);
  EXPECT_EQ(vn, vertices);
  EXPECT_EQ(vt, vertices);
  EXPECT_EQ(f, triangles);
  EXPECT_NE(obj.find("\nf 1/1/1 2/2/2 "), std::string::npos) << "faces name position, texture and normal";
  testing::expect_obj_holds(obj, pieces);

  // No branch at all: still a valid file, with an empty scene.
  Cluster lone;
  lone.seed_count = 1;
  lone.particles.push_back({Vec3::Zero(), -1, 0});
  write_glb(lone, make_look(lone, {}), dir / "lone.glb");
  EXPECT_NE(read_file(dir / "lone.glb").find("\"scenes\":[{}]"), std::string::npos);
}

//! The positions' bounds a glb's JSON gives (its first accessor's min and max) and its triangles
//! (its last accessor's count, over 3).
struct GlbMesh {
  Eigen::Vector3d min, max;
  std::size_t triangles = 0;
};

GlbMesh read_glb_mesh(const std::string& path) {
  const std::string glb = read_file(path);
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const std::string json = glb.substr(20, json_length);
  GlbMesh mesh;
  const auto vector_after = [&](const std::string& key) {
    Eigen::Vector3d v;
    std::sscanf(json.c_str() + json.find(key) + key.size(), "[%lf,%lf,%lf]", &v.x(), &v.y(), &v.z());
    return v;
  };
  mesh.min = vector_after("\"min\":");
  mesh.max = vector_after("\"max\":");
  const std::size_t last = json.rfind("\"count\":");
  mesh.triangles = std::stoul(json.substr(last + 8)) / 3;
  return mesh;
}

// Levels of detail: each about half the one before, twigs first, within the full mesh's bounds
// and no more than a few per cent inside them; their counts are the files'.
TEST(LookFiles, LevelsOfDetailHalveTheTrianglesAndKeepTheShape) {
  ScratchDir dir;
  const Cluster c = grown(5000);
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  const Look look = make_look(c, options);
  const std::vector<std::size_t> triangles = write_glb(c, look, dir / "tree.glb", {3, nullptr, {}}).lod_triangles;
  ASSERT_EQ(triangles.size(), 3u);
  const GlbMesh full = read_glb_mesh(dir / "tree.glb");
  const double diagonal = (full.max - full.min).norm();
  std::size_t before = full.triangles;
  for (std::size_t level = 1; level <= 3; ++level) {
    SCOPED_TRACE(level);
    const GlbMesh lod = read_glb_mesh(dir / ("tree_lod" + std::to_string(level) + ".glb"));
    EXPECT_EQ(lod.triangles, triangles[level - 1]);
    EXPECT_LT(lod.triangles, before * 3 / 4) << "not about half the level before";
    EXPECT_GT(lod.triangles, before / 4);
    before = lod.triangles;
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(lod.min[a], full.min[a] - 1e-6) << "outside the full mesh";
      EXPECT_LE(lod.max[a], full.max[a] + 1e-6) << "outside the full mesh";
      EXPECT_LT(lod.min[a] - full.min[a], 0.05 * diagonal) << "shrunk";
      EXPECT_LT(full.max[a] - lod.max[a], 0.05 * diagonal) << "shrunk";
    }
  }
  EXPECT_TRUE(write_glb(c, look, dir / "none.glb").lod_triangles.empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "none_lod1.glb"));
  EXPECT_THROW(write_glb(c, look, dir / "many.glb", {kMaxLods + 1, nullptr, {}}), InvalidInput);
  EXPECT_THROW(write_glb(c, look, dir / "few.glb", {-1, nullptr, {}}), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dir / "many.glb")) << "refused before writing";
}

// A glb's lengths are 32-bit: tubes past 4.29 GB are refused in one line before the file is
// made, not written with a length that wraps. A comb of 240,000 teeth at 64 sides is 4.5 GB.
TEST(LookFiles, AGlbPastItsFourGigabytesIsRefusedBeforeItIsWritten) {
  ScratchDir dir;
  Cluster comb;
  comb.seed_count = 1;
  constexpr int kSpine = 1000;
  for (int i = 0; i < kSpine; ++i) comb.particles.push_back({Vec3(i, 0, 0), i - 1, 0});
  for (int tooth = 0; tooth < 240000; ++tooth) {
    const int root = tooth % kSpine;
    const double angle = 0.001 * tooth;
    comb.particles.push_back({Vec3(root, std::cos(angle), std::sin(angle)), root, 0});
  }
  LookOptions options;
  options.tubes.sides = 64;
  const Look look = make_look(comb, options);
  try {
    write_glb(comb, look, dir / "huge.glb");
    ADD_FAILURE() << "a glb past 4.29 GB was written";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("`formats` glb: the tubes would take 4."), std::string::npos) << message;
    EXPECT_NE(message.find("past a glb's 4.29 GB"), std::string::npos) << message;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "huge.glb"));
}

// The solid's glb shares the check, and its message names the solid's options, not the tubes'.
TEST(LookFiles, AGlbTooLargeNamesTheOptionsOfWhatItHolds) {
  EXPECT_NO_THROW(detail::require_glb_fits(std::numeric_limits<std::uint32_t>::max(), detail::GlbContent::solid));
  const auto message = [](detail::GlbContent content) {
    try {
      detail::require_glb_fits(std::uint64_t{5'000'000'000}, content);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "5 GB passed";
    return std::string();
  };
  const std::string solid = message(detail::GlbContent::solid), tubes = message(detail::GlbContent::tubes);
  EXPECT_EQ(solid.rfind("`formats` solid-glb: the solid would take 5 GB, past a glb's 4.29 GB", 0), 0u) << solid;
  EXPECT_NE(solid.find("`solid_voxel`"), std::string::npos) << solid;
  EXPECT_EQ(solid.find("tube"), std::string::npos) << solid;
  EXPECT_EQ(tubes.rfind("`formats` glb: the tubes would take 5 GB", 0), 0u) << tubes;
  EXPECT_NE(tubes.find("`tube_sides`"), std::string::npos) << tubes;
}

TEST(LookFiles, SvgDrawsEveryBranchOf2DGrowth) {
  ScratchDir dir;
  const Cluster flat = grown(600, 2);
  LookOptions options;
  options.radius.model = RadiusModel::pipe;
  options.color_by = ColorBy::age;
  const Look look = make_look(flat, options);
  write_svg(flat, look, dir / "a.svg");
  const std::string svg = read_file(dir / "a.svg");
  std::size_t lines = 0;
  for (std::size_t at = svg.find("<line "); at != std::string::npos; at = svg.find("<line ", at + 1)) ++lines;
  EXPECT_EQ(lines, 600u);
  EXPECT_NE(svg.find("stroke=\"#"), std::string::npos);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  const Cluster solid = grown(50);
  EXPECT_THROW(write_svg(solid, make_look(solid, {}), dir / "b.svg"), InvalidInput);
}

}  // namespace
}  // namespace dla
