// Loops: links between neighbours against a brute-force search, Eden's lattice graph against
// every pair of sites, closed venation against a brute-force rescan node for node, the cycle
// count, and the links in the CSV, the PLY and the tubes.

#include "dla/core/analysis.h"
#include "dla/io/csv_reader.h"
#include "dla/io/csv_writer.h"
#include "dla/io/ply_writer.h"
#include "dla/look/tubes.h"
#include "dla/models/colonization.h"
#include "dla/models/dla.h"
#include "dla/models/eden.h"
#include "dla/models/links.h"
#include "dla/look/solid.h"
#include "colonization_rescan.h"
#include "solid_check.h"
#include "test_util.h"
#include "tube_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

using namespace dla;
using dla::testing::tree_steps;

namespace {

Cluster dla_tree(std::size_t n, int dimensions, std::uint64_t seed = 3) {
  DlaOptions o;
  o.particles = n;
  o.dimensions = dimensions;
  o.rng_seed = seed;
  return grow(o);
}

//! The links by brute force: each particle against every earlier one, nearest first (ties: the
//! lower id), skipping those fewer than `steps` tree steps away, K at most.
std::vector<Link> brute_links(const Cluster& c, double distance, std::size_t most, int steps) {
  std::vector<Link> links;
  const double r2 = std::pow(distance * c.spacing, 2);
  for (std::size_t i = 0; i < c.particles.size(); ++i) {
    std::vector<std::pair<double, std::int32_t>> near;
    for (std::size_t j = 0; j < i; ++j) {
      const double d2 = (c.particles[i].position - c.particles[j].position).squaredNorm();
      if (d2 <= r2) near.emplace_back(d2, static_cast<std::int32_t>(j));
    }
    std::sort(near.begin(), near.end());
    std::size_t made = 0;
    for (const auto& [d2, j] : near) {
      if (made == most) break;
      if (tree_steps(c, static_cast<std::int32_t>(i), j) < steps) continue;
      links.push_back({j, static_cast<std::int32_t>(i)});
      ++made;
    }
  }
  return links;
}

//! What every structure's links keep to: two particles, earlier first, in order of the later,
//! none repeating a tree edge or another link.
void expect_valid_links(const Cluster& c) {
  std::set<std::pair<std::int32_t, std::int32_t>> seen;
  std::int32_t last = -1;
  for (const Link& link : c.links) {
    ASSERT_GE(link.earlier, 0);
    ASSERT_LT(link.earlier, link.later);
    ASSERT_LT(static_cast<std::size_t>(link.later), c.particles.size());
    ASSERT_GE(link.later, last) << "links are in order of the later particle";
    last = link.later;
    EXPECT_NE(c.particles[static_cast<std::size_t>(link.later)].parent, link.earlier) << "a link repeats a tree edge";
    EXPECT_TRUE(seen.insert({link.earlier, link.later}).second) << "a link repeats another";
  }
}

}  // namespace

TEST(Links, MatchABruteForceSearchAndKeepTheirRules) {
  for (const int dimensions : {2, 3}) {
    const Cluster tree = dla_tree(dimensions == 2 ? 3000 : 4000, dimensions);
    for (const auto& [distance, most] : {std::pair<double, std::size_t>{1.5, 1}, {2.5, 3}, {4.0, 8}}) {
      SCOPED_TRACE(std::to_string(dimensions) + "D, links " + std::to_string(distance) + "," + std::to_string(most));
      LinkOptions o;
      o.distance = distance;
      o.most = most;
      Cluster linked = tree;
      linked.links = neighbour_links(tree, o);
      const std::vector<Link> want = brute_links(tree, distance, most, kLoopSteps);
      ASSERT_EQ(linked.links.size(), want.size());
      for (std::size_t k = 0; k < want.size(); ++k) ASSERT_EQ(linked.links[k], want[k]) << "link " << k;
      ASSERT_GT(linked.links.size(), 0u);
      expect_valid_links(linked);
      std::map<std::int32_t, std::size_t> own;
      for (const Link& link : linked.links) {
        const double d = (tree.particles[static_cast<std::size_t>(link.earlier)].position -
                          tree.particles[static_cast<std::size_t>(link.later)].position).norm();
        EXPECT_LE(d, distance * tree.spacing * (1 + 1e-12));
        EXPECT_GE(tree_steps(tree, link.earlier, link.later), kLoopSteps);
        EXPECT_LE(++own[link.later], most);
      }
      // One seed's tree: every link closes a loop.
      EXPECT_EQ(cycle_count(linked), linked.links.size());
    }
  }
}

TEST(Links, AreTheSameOnAnyThreadCount) {
  const Cluster tree = dla_tree(20000, 3, 5);
  LinkOptions o;
  o.distance = 2.0;
  o.most = 2;
  const std::vector<Link> one = neighbour_links(tree, o, 1);
  ASSERT_GT(one.size(), 100u);
  for (const int threads : {2, 3, 7}) EXPECT_EQ(neighbour_links(tree, o, threads), one) << threads << " threads";
}

TEST(Links, OptionsParseAndRefuse) {
  EXPECT_EQ(parse_links("2").distance, 2.0);
  EXPECT_EQ(parse_links("2").most, 1u);
  EXPECT_EQ(parse_links("1.5,4").most, 4u);
  EXPECT_TRUE(parse_links("lattice").lattice);
  EXPECT_EQ(to_string(parse_links("1.5,4")), "1.5,4");
  for (const char* bad : {"", ",", "x", "2,", "2,0", "2,65", "0", "-1", "1e9", "2,3,4", "2;3", "nan"})
    EXPECT_THROW(parse_links(bad), InvalidInput) << bad;
  Cluster tree = dla_tree(100, 3);
  EXPECT_THROW(neighbour_links(tree, parse_links("lattice")), InvalidInput);
}

TEST(Links, CycleCountIsTheCycleRank) {
  // Two seeds, each with a chain of three.
  Cluster c;
  c.seed_count = 2;
  c.particles = {{Vec3(0, 0, 0), -1, 0}, {Vec3(10, 0, 0), -1, 1}, {Vec3(1, 0, 0), 0, 0},
                 {Vec3(11, 0, 0), 1, 1}, {Vec3(2, 0, 0), 2, 0},  {Vec3(12, 0, 0), 3, 1}};
  EXPECT_EQ(cycle_count(c), 0u);
  c.links = {{4, 5}};  // joins the two trees: no loop yet
  EXPECT_EQ(cycle_count(c), 0u);
  c.links.push_back({2, 5});  // now one
  EXPECT_EQ(cycle_count(c), 1u);
  c.links.push_back({0, 4});  // a loop within the first tree
  EXPECT_EQ(cycle_count(c), 2u);
  // The first particles keep the links among them.
  const Cluster part = first_particles(c, 5);
  EXPECT_EQ(part.particles.size(), 5u);
  ASSERT_EQ(part.links.size(), 1u);
  EXPECT_EQ(part.links[0], (Link{0, 4}));
}

TEST(Links, EdenLatticeLinksAreEveryPairOfNeighbours) {
  for (const Lattice lattice : {Lattice::square4, Lattice::square8, Lattice::hex, Lattice::cubic6, Lattice::cubic18,
                                Lattice::cubic26}) {
    SCOPED_TRACE(std::string(to_string(lattice)));
    EdenOptions o;
    o.lattice = lattice;
    o.sites = 600;
    o.spacing = 0.7;
    Cluster c = eden(o);
    c.links = lattice_links(c, lattice, 2);
    expect_valid_links(c);
    // Every pair of occupied neighbours is a tree edge or a link, and nothing else is either.
    std::vector<Vec3> steps;
    for (const auto& offset : lattice_neighbours(lattice)) steps.push_back(eden_position(lattice, offset, o.spacing));
    std::set<std::pair<std::int32_t, std::int32_t>> want, have;
    for (std::size_t i = 0; i < c.particles.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        for (const Vec3& step : steps)
          if ((c.particles[i].position - c.particles[j].position - step).norm() < 1e-9 * o.spacing)
            want.insert({static_cast<std::int32_t>(j), static_cast<std::int32_t>(i)});
    for (std::size_t i = 0; i < c.particles.size(); ++i)
      if (c.particles[i].parent >= 0) have.insert({c.particles[i].parent, static_cast<std::int32_t>(i)});
    const std::size_t tree_edges = have.size();
    for (const Link& link : c.links) have.insert({link.earlier, link.later});
    EXPECT_EQ(have.size(), tree_edges + c.links.size());
    // Eden's drop mode may hang a site from a non-neighbour; perimeter growth never does.
    EXPECT_EQ(have, want);
    EXPECT_EQ(cycle_count(c), c.links.size());
  }
}

TEST(Links, ClosedVenationMatchesABruteForceRescanNodeForNode) {
  struct Case {
    const char* name;
    int dimensions;
    std::size_t attractors;
    double influence, kill;
    std::vector<Vec3> roots;
  };
  const std::vector<Case> cases = {
      {"a leaf in the plane, one root", 2, 300, 8, 2, {Vec3(0, -20, 0)}},
      {"the plane, two roots, short reach", 2, 500, 4, 1.5, {Vec3(-10, 0, 0), Vec3(10, 0, 0)}},
      {"a ball in 3D", 3, 400, 6, 2, {Vec3(0, 0, -18)}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    ColonizationOptions o;
    o.dimensions = c.dimensions;
    o.influence = c.influence;
    o.kill_distance = c.kill;
    o.venation = Venation::closed;
    AttractorOptions a;
    a.count = c.attractors;
    a.radius = 20;
    const std::vector<Vec3> sources = scatter_attractors(a, 11, c.dimensions);
    const Cluster fast = colonize(o, sources, c.roots);
    const Cluster slow = dla::testing::colonize_closed_by_rescan(o, sources, c.roots);
    ASSERT_GT(fast.particles.size(), 100u);
    ASSERT_EQ(fast.particles.size(), slow.particles.size());
    for (std::size_t i = 0; i < fast.particles.size(); ++i) {
      ASSERT_EQ(fast.particles[i].position, slow.particles[i].position) << "node " << i;
      ASSERT_EQ(fast.particles[i].parent, slow.particles[i].parent) << "node " << i;
    }
    ASSERT_EQ(fast.links, slow.links);
    EXPECT_GT(fast.links.size(), 0u) << "veins meet";
    expect_valid_links(fast);
    for (const Link& link : fast.links) EXPECT_GE(tree_steps(fast, link.earlier, link.later), kLoopSteps);
  }
}

// Closed venation's reach: the influence given, or 4 kill distances without one.
TEST(Links, ClosedVenationGrowsOtherwiseThanOpenWithinItsReach) {
  ColonizationOptions o;
  o.dimensions = 2;
  o.influence = 8;
  AttractorOptions a;
  a.count = 300;
  a.radius = 20;
  const std::vector<Vec3> sources = scatter_attractors(a, 11, 2);
  const Cluster open = colonize(o, sources, {Vec3(0, -20, 0)});
  EXPECT_TRUE(open.links.empty());
  o.venation = Venation::closed;
  const Cluster closed = colonize(o, sources, {Vec3(0, -20, 0)});
  EXPECT_GT(closed.links.size(), 0u);
  EXPECT_NE(closed.particles.size(), open.particles.size());
  // Without an influence: that of 4 kill distances, the same veins.
  EXPECT_DOUBLE_EQ(influence_of(o), 8.0);
  o.influence = std::numeric_limits<double>::infinity();
  o.kill_distance = 2.0;
  EXPECT_DOUBLE_EQ(influence_of(o), kClosedInfluence * 2.0);
  const Cluster by_default = colonize(o, sources, {Vec3(0, -20, 0)});
  ASSERT_EQ(by_default.particles.size(), closed.particles.size());
  for (std::size_t i = 0; i < closed.particles.size(); ++i)
    ASSERT_EQ(by_default.particles[i].position, closed.particles[i].position) << i;
  EXPECT_EQ(by_default.links.size(), closed.links.size());
  o.venation = Venation::open;
  EXPECT_TRUE(std::isinf(influence_of(o))) << "open venation keeps an unbounded influence";
  EXPECT_EQ(parse_word<Venation>("closed"), Venation::closed);
  EXPECT_THROW(parse_word<Venation>("shut"), InvalidInput);
}

TEST(Links, TravelThroughTheCsvAndThePly) {
  const dla::testing::ScratchDir dir;
  Cluster tree = dla_tree(2000, 3);
  tree.links = neighbour_links(tree, parse_links("2,2"));
  ASSERT_GT(tree.links.size(), 10u);
  const std::string csv = dir / "t.csv";
  write_csv(tree, csv);
  ASSERT_TRUE(std::filesystem::exists(dir.path() / "t_links.csv"));
  EXPECT_EQ(read_csv(csv).links, tree.links);
  // Without links the old file goes: it would be read back with the new tree.
  Cluster plain = tree;
  plain.links.clear();
  write_csv(plain, csv);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "t_links.csv"));
  EXPECT_TRUE(read_csv(csv).links.empty());
  Cluster small = dla_tree(20, 3);
  for (const char* bad : {"a,b\n3,2\n", "a,b\n0,21\n", "x,y\n0,1\n", "a,b\n0,1,2\n", "a,b\n-1,2\n", "a,b\n0.5,2\n"})
    EXPECT_THROW(parse_links_csv(bad, "bad", small), InvalidInput) << bad;

  // The PLY's edges: the tree's with link 0, then the links with link 1.
  write_ply(tree, dir / "t.ply", PlyEncoding::ascii);
  const std::string ply = dla::testing::read_file(dir / "t.ply");
  const std::size_t edges = tree.particles.size() - tree.seed_count + tree.links.size();
  EXPECT_NE(ply.find("element edge " + std::to_string(edges) + "\nproperty int vertex1\nproperty int vertex2\nproperty uchar link\n"),
            std::string::npos);
  const std::string last = std::to_string(tree.links.back().earlier) + " " + std::to_string(tree.links.back().later) + " 1\n";
  EXPECT_EQ(ply.compare(ply.size() - last.size(), last.size(), last), 0);
}

TEST(Links, TubesAreClosedAndJoinTheirEnds) {
  Cluster tree = dla_tree(1500, 3);
  tree.links = neighbour_links(tree, parse_links("2.5,2"));
  ASSERT_GT(tree.links.size(), 5u);
  const Look look = make_look(tree, {});
  const std::vector<float> radii = look.radii;
  std::size_t strands = 0, pieces = 0, link_tubes = 0;
  for_each_strand(tree, [&](const Strand& strand) { strands += strand.size() >= 2; });
  for_each_tube(tree, look.attributes, radii, {}, [&](const TubePiece& piece) {
    dla::testing::expect_closed(piece);
    dla::testing::expect_texture_frame(piece);
    if (++pieces <= strands) return;  // the strands' tubes come first
    ++link_tubes;
    ASSERT_EQ(piece.positions.size(), link_tube_vertices(8));
    ASSERT_EQ(piece.triangles.size(), link_tube_triangles(8));
    // Its ends are its particles': the ring about each end is that particle's radius around it.
    const Link& link = tree.links[link_tubes - 1];
    for (std::size_t v = 9; v < 27; ++v) {
      const auto owner = static_cast<std::size_t>(piece.particles[v]);
      ASSERT_TRUE(owner == static_cast<std::size_t>(link.earlier) || owner == static_cast<std::size_t>(link.later));
      const double d = (piece.positions[v].cast<double>() - tree.particles[owner].position).norm();
      EXPECT_NEAR(d, radii[owner] * tree.spacing, 1e-4);
    }
  });
  EXPECT_EQ(link_tubes, tree.links.size());
}

// The solid: each link is a capsule like any branch, so loops join the structure into one
// closed shell, with more volume than its tree alone.
TEST(Links, AreBranchesOfTheSolid) {
  Cluster tree = dla_tree(800, 3);
  const std::vector<float> radii = make_look(tree, {}).radii;
  SolidOptions o;
  o.voxel = 0.25;
  const Solid plain = build_solid(tree, radii, o);
  tree.links = neighbour_links(tree, parse_links("3,2"));
  ASSERT_GT(tree.links.size(), 10u);
  const Solid looped = build_solid(tree, radii, o);
  EXPECT_EQ(edge_faults(looped.mesh), "");
  EXPECT_EQ(face_components(looped.mesh), 1u);
  EXPECT_GT(looped.measures.volume, plain.measures.volume * 1.01);
}
