// build_solid(): the union of a structure's tapered capsules (or spheres, cubes) as a
// narrow-band signed distance field on OpenVDB's sparse grid, meshed watertight (solid.h).
//
// Every voxel near a piece gets the exact signed distance to it, and the minimum over pieces
// is the exact distance to the union outside it and on its surface. The grid is filled one
// leaf (8^3 voxels) at a time: the pieces that reach a leaf, in particle order, so each voxel
// sees the same pieces in the same order on any number of threads, and leaves deep inside one
// piece become a single tile.

#include "solid_grid.h"

#include "dla/core/memory.h"
#include "dla/core/errors.h"
#include "dla/index/detail/nanoflann.h"

#include <Eigen/Geometry>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/ValueTransformer.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <malloc.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <numeric>
#include <string>
#include <thread>

namespace dla {

namespace detail {

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

}  // namespace detail

namespace {

using Point = Eigen::Vector3d;

//! The narrow band's half width, in voxels, on either side of the surface: OpenVDB's own.
constexpr double kBandVoxels = 3.0;
//! A branch thinner than this many voxels across is drawn at it, so it cannot break apart.
constexpr double kThinnestVoxels = 1.5;
//! Voxels across the thinnest branch, by default.
constexpr double kVoxelsAcross = 3.0;
//! What a leaf of 8^3 voxels costs as the build goes: its values and masks, the meshing's
//! working grids and its share of the triangles (measured peaks over the test set, rounded up).
constexpr double kBytesPerLeaf = 6e3;
//! What a leaf and a piece cost to build, mesh and write as STL on two threads (fitted to 2x10^4
//! and 10^5 particles at the default voxel and 10^6 at a voxel of a spacing: within 10%).
constexpr double kSecondsPerLeaf = 18e-6, kSecondsPerPiece = 15e-6;
//! A print must be this many of its thinnest walls long.
constexpr double kPrintSizeWalls = 10.0;
//! The share of a build's progress that filling the grid takes (about its share of the time).
constexpr double kFillShare = 0.5;
constexpr int kLeafLog2 = 3, kLeafSide = 1 << kLeafLog2;
//! Two pieces' surfaces meet in a crease where their normals part by more than about 25 degrees.
constexpr double kCreaseCosine = 0.9;

//! One piece of the union, in the mesh's units: the convex hull of two spheres (a tapered
//! capsule, or one sphere when a = b), or an axis-aligned cube of half side ra.
struct Piece {
  Point a, b;
  double ra = 0.0, rb = 0.0;
  bool cube = false;

  Point low() const { return cube ? Point(a.array() - ra) : Point(a.cwiseMin(b).array() - std::max(ra, rb)); }
  Point high() const { return cube ? Point(a.array() + ra) : Point(a.cwiseMax(b).array() + std::max(ra, rb)); }

  //! The exact signed distance from p (Quílez's round cone, in double).
  double distance(const Point& p) const {
    if (cube) {
      const Point q = (p - a).cwiseAbs().array() - ra;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    const Point ba = b - a;
    const double l2 = ba.squaredNorm();
    const double rr = ra - rb;
    // One sphere holds the other (or they coincide): the larger alone.
    if (l2 <= rr * rr) return ra >= rb ? (p - a).norm() - ra : (p - b).norm() - rb;
    const double a2 = l2 - rr * rr;
    const Point pa = p - a;
    const double y = pa.dot(ba), z = y - l2;
    const double x2 = (pa * l2 - ba * y).squaredNorm();
    const double y2 = y * y * l2, z2 = z * z * l2;
    const double k = (rr > 0 ? 1.0 : rr < 0 ? -1.0 : 0.0) * rr * rr * x2;
    if ((z > 0 ? 1.0 : z < 0 ? -1.0 : 0.0) * a2 * z2 > k) return std::sqrt(x2 + z2) / l2 - rb;
    if ((y > 0 ? 1.0 : y < 0 ? -1.0 : 0.0) * a2 * y2 < k) return std::sqrt(x2 + y2) / l2 - ra;
    return (std::sqrt(x2 * a2 / l2) + y * rr) / l2 - ra;
  }
  double thinnest() const { return cube ? 2.0 * ra : 2.0 * std::min(ra, rb); }
};

}  // namespace

double chord_depth(double voxel, double radius, bool sphere) {
  // A cylinder's inscribed polygon loses (edge / radius)^2 / 6 of its area, which about a
  // twelfth of voxel^2 / radius restores; curved both ways, a sphere loses more. A fourteenth
  // and an eighth are what keep a straight chain's and a sphere's volume within 1.6% at 3
  // voxels across, and DLA trees' within 1% (docs/dev/solids.md).
  return voxel * voxel / ((sphere ? 8.0 : 14.0) * radius);
}

namespace {

//! Half of what the machine has available, in bytes.
double default_memory_limit() { return available_memory() / 2.0; }

std::string megabytes(double bytes) {
  return bytes >= 1e9 ? detail::format_number(std::ceil(bytes / 1e8) / 10.0) + " GB"
                      : detail::format_number(std::ceil(bytes / 1e6)) + " MB";
}

//! Floor division by the leaf side, for negative coordinates too.
int leaf_of(int voxel) { return voxel >> kLeafLog2; }

struct IndexBox {
  std::array<int, 3> low, high;  // inclusive voxel coordinates
};

//! The voxels whose centres may lie within the band of piece `p`.
IndexBox voxels_near(const Piece& p, double voxel, double band) {
  const Point low = (p.low().array() - band) / voxel, high = (p.high().array() + band) / voxel;
  IndexBox box;
  for (int a = 0; a < 3; ++a) {
    box.low[a] = static_cast<int>(std::floor(low[a]));
    box.high[a] = static_cast<int>(std::ceil(high[a]));
  }
  return box;
}

//! A leaf and a piece that reaches it: sorted, the pieces of each leaf in particle order.
struct LeafPiece {
  std::uint64_t leaf;
  std::uint32_t piece;
  bool operator<(const LeafPiece& o) const { return leaf != o.leaf ? leaf < o.leaf : piece < o.piece; }
};

constexpr int kLeafCoordinateBias = 1 << 20;  // leaf coordinates packed as 3 x 21 bits

std::uint64_t pack_leaf(int x, int y, int z) {
  return (static_cast<std::uint64_t>(x + kLeafCoordinateBias) << 42) |
         (static_cast<std::uint64_t>(y + kLeafCoordinateBias) << 21) | static_cast<std::uint64_t>(z + kLeafCoordinateBias);
}
openvdb::Coord leaf_origin(std::uint64_t key) {
  const auto part = [&](int shift) { return static_cast<int>((key >> shift) & ((1u << 21) - 1)) - kLeafCoordinateBias; };
  return openvdb::Coord(part(42) * kLeafSide, part(21) * kLeafSide, part(0) * kLeafSide);
}

//! What the build can take at most, in bytes, found without allocating: the leaf-piece pairs,
//! and leaves, the fewer of every piece's counted apart and all of their common box's.
struct Bound {
  double pairs = 0.0, leaves = 0.0;
  double bytes(double per_leaf) const { return pairs * sizeof(std::uint64_t) * 2 + leaves * per_leaf; }
};

Bound bound(const std::vector<Piece>& pieces, double voxel, double band) {
  Bound b;
  std::array<int, 3> low{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
  std::array<int, 3> high{std::numeric_limits<int>::min(), std::numeric_limits<int>::min(), std::numeric_limits<int>::min()};
  for (const Piece& p : pieces) {
    const IndexBox box = voxels_near(p, voxel, band);
    double leaves = 1.0;
    for (int a = 0; a < 3; ++a) {
      leaves *= leaf_of(box.high[a]) - leaf_of(box.low[a]) + 1;
      low[a] = std::min(low[a], leaf_of(box.low[a]));
      high[a] = std::max(high[a], leaf_of(box.high[a]));
    }
    b.pairs += leaves;
  }
  double boxed = 1.0;
  for (int a = 0; a < 3; ++a) boxed *= static_cast<double>(high[a]) - low[a] + 1.0;
  b.leaves = std::min(b.pairs, boxed);
  return b;
}

std::vector<LeafPiece> leaf_pieces(const std::vector<Piece>& pieces, double voxel, double band) {
  std::vector<LeafPiece> pairs;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const IndexBox box = voxels_near(pieces[i], voxel, band);
    for (int x = leaf_of(box.low[0]); x <= leaf_of(box.high[0]); ++x)
      for (int y = leaf_of(box.low[1]); y <= leaf_of(box.high[1]); ++y)
        for (int z = leaf_of(box.low[2]); z <= leaf_of(box.high[2]); ++z)
          pairs.push_back({pack_leaf(x, y, z), static_cast<std::uint32_t>(i)});
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::size_t unique_leaves(const std::vector<LeafPiece>& pairs) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) count += i == 0 || pairs[i].leaf != pairs[i - 1].leaf;
  return count;
}

//! What building at `voxel` would take, in bytes, and the pairs it needs: counted, unless the
//! bound is within `limit` or the pairs alone would pass half of it.
struct Estimate {
  double bytes = 0.0;
  double leaves = 0.0;
  std::vector<LeafPiece> pairs;
};

Estimate estimate(const std::vector<Piece>& pieces, double voxel, double band, double per_leaf, double limit) {
  const Bound b = bound(pieces, voxel, band);
  if (b.bytes(per_leaf) > limit && b.pairs * sizeof(LeafPiece) > limit / 2) return {b.bytes(per_leaf), b.leaves, {}};
  Estimate e;
  e.pairs = leaf_pieces(pieces, voxel, band);
  e.leaves = static_cast<double>(unique_leaves(e.pairs));
  e.bytes = static_cast<double>(e.pairs.capacity() * sizeof(LeafPiece)) + e.leaves * per_leaf;
  return e;
}

using FloatTree = openvdb::FloatTree;
using FloatLeaf = FloatTree::LeafNodeType;

//! One leaf's voxels: the minimum over its pieces, clamped to the band. Returns the leaf, or
//! null with `deep` set when every voxel lies deeper inside than the band (a tile).
FloatLeaf* fill_leaf(const openvdb::Coord& origin, const LeafPiece* begin, const LeafPiece* end,
                     const std::vector<Piece>& pieces, double voxel, float band, bool& deep) {
  std::array<float, FloatLeaf::SIZE> values;
  values.fill(band);
  // The leaf, then blocks of 4^3 voxels, then of 2^3: the distance changes by at most a block's
  // half diagonal within it, so a block wholly beyond the band (most of a thin capsule's box) is
  // skipped, and one wholly deep inside is set at once.
  const double half_diagonal = std::sqrt(3.0) / 2.0 * voxel;  // of a block of 2^3 voxel centres
  const Point corner(origin[0], origin[1], origin[2]);
  // The voxels of the block of `side` at `at` (leaf coordinates): returns whether it was settled.
  const auto settle = [&](const Piece& piece, const int at[3], int side) {
    const double d = piece.distance((corner + Point(at[0], at[1], at[2]) + Point::Constant((side - 1) / 2.0)) * voxel);
    const double reach = half_diagonal * (side - 1);
    if (d - reach >= band) return true;
    if (d + reach > -band) return false;
    for (int x = at[0]; x < at[0] + side; ++x)
      for (int y = at[1]; y < at[1] + side; ++y)
        for (int z = at[2]; z < at[2] + side; ++z) values[static_cast<std::size_t>((x << 6) | (y << 3) | z)] = -band;
    return true;
  };
  const int whole[3] = {0, 0, 0};
  for (const LeafPiece* it = begin; it != end; ++it) {
    const Piece& piece = pieces[it->piece];
    if (settle(piece, whole, kLeafSide)) continue;  // the leaf at once: a corner of the piece's box
    const IndexBox box = voxels_near(piece, voxel, band);
    int low[3], high[3];
    for (int a = 0; a < 3; ++a) {
      low[a] = std::max(box.low[a], origin[a]) - origin[a];
      high[a] = std::min(box.high[a], origin[a] + kLeafSide - 1) - origin[a];
    }
    int big[3], small[3];
    for (big[0] = low[0] & ~3; big[0] <= high[0]; big[0] += 4)
      for (big[1] = low[1] & ~3; big[1] <= high[1]; big[1] += 4)
        for (big[2] = low[2] & ~3; big[2] <= high[2]; big[2] += 4) {
          if (settle(piece, big, 4)) continue;
          for (small[0] = big[0]; small[0] < big[0] + 4; small[0] += 2)
            for (small[1] = big[1]; small[1] < big[1] + 4; small[1] += 2)
              for (small[2] = big[2]; small[2] < big[2] + 4; small[2] += 2) {
                if (settle(piece, small, 2)) continue;
                for (int x = small[0]; x < small[0] + 2; ++x)
                  for (int y = small[1]; y < small[1] + 2; ++y)
                    for (int z = small[2]; z < small[2] + 2; ++z) {
                      float& v = values[static_cast<std::size_t>((x << 6) | (y << 3) | z)];
                      v = std::min(v, static_cast<float>(piece.distance((corner + Point(x, y, z)) * voxel)));
                    }
              }
        }
  }
  bool any_active = false, all_deep = true;
  for (float& v : values) {
    v = std::clamp(v, -band, band);
    any_active |= v > -band && v < band;
    all_deep &= v <= -band;
  }
  deep = all_deep;
  if (!any_active) return nullptr;
  auto* leaf = new FloatLeaf(origin, band, false);
  for (openvdb::Index n = 0; n < FloatLeaf::SIZE; ++n) {
    const float v = values[n];
    if (v > -band && v < band) leaf->setValueOn(n, v);
    else leaf->setValueOff(n, v);
  }
  return leaf;
}

//! The grid of `pieces`: their union's narrow-band level set. Leaves are filled on `threads`
//! threads and added in leaf order.
openvdb::FloatGrid::Ptr rasterize(const std::vector<Piece>& pieces, const std::vector<LeafPiece>& pairs, double voxel,
                                  int threads, const StopFlag* stop, const StageProgress& progress) {
  const float band = static_cast<float>(kBandVoxels * voxel);
  // Where each leaf's pieces begin in `pairs`.
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (i == 0 || pairs[i].leaf != pairs[i - 1].leaf) starts.push_back(i);
  starts.push_back(pairs.size());
  const std::size_t leaves = starts.size() - 1;
  std::vector<FloatLeaf*> filled(leaves, nullptr);
  std::vector<char> deep(leaves, 0);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stopped{false};
  // The calling thread reports progress as it takes each chunk of leaves.
  const auto work = [&](bool reports) {
    constexpr std::size_t kChunk = 64;
    for (std::size_t from; (from = next.fetch_add(kChunk)) < leaves;) {
      if (stop && stop->load()) {
        stopped = true;
        return;
      }
      if (reports && progress) progress(kFillShare * static_cast<double>(from) / static_cast<double>(leaves), "filling the grid");
      for (std::size_t l = from; l < std::min(leaves, from + kChunk); ++l) {
        bool is_deep = false;
        filled[l] = fill_leaf(leaf_origin(pairs[starts[l]].leaf), pairs.data() + starts[l],
                              pairs.data() + starts[l + 1], pieces, voxel, band, is_deep);
        deep[l] = is_deep;
      }
    }
  };
  std::vector<std::thread> helpers;
  for (int t = 1; t < threads; ++t) helpers.emplace_back(work, false);
  work(true);
  for (std::thread& t : helpers) t.join();
  auto grid = openvdb::FloatGrid::create(band);
  FloatTree& tree = grid->tree();
  for (std::size_t l = 0; l < leaves; ++l) {
    if (filled[l]) tree.addLeaf(filled[l]);
    else if (deep[l]) tree.addTile(1, leaf_origin(pairs[starts[l]].leaf), -band, false);
  }
  if (stopped) throw Interrupted("the solid was stopped while its grid was filled");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  grid->setName("surface");
  openvdb::tools::pruneLevelSet(grid->tree());
  return grid;
}

//! Bars along a minimum spanning tree of the seeds (Prim's, in seed order), at the smaller of
//! their radii.
std::vector<Piece> seed_bars(const std::vector<Point>& seeds, const std::vector<double>& radii) {
  std::vector<Piece> bars;
  const std::size_t n = seeds.size();
  if (n < 2) return bars;
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> from(n, 0);
  std::vector<char> in(n, 0);
  std::size_t current = 0;
  in[0] = 1;
  for (std::size_t added = 1; added < n; ++added) {
    std::size_t next = n;
    for (std::size_t j = 0; j < n; ++j) {
      if (in[j]) continue;
      const double d = (seeds[j] - seeds[current]).squaredNorm();
      if (d < best[j]) best[j] = d, from[j] = current;
      if (next == n || best[j] < best[next]) next = j;
    }
    in[next] = 1;
    const double r = std::min(radii[next], radii[from[next]]);
    bars.push_back({seeds[from[next]], seeds[next], r, r, false});
    current = next;
  }
  return bars;
}

//! The pieces of the structure in scene units, scaled about `origin` by `scale`, each radius
//! at least `floor` (counted in `thickened`).
std::vector<Piece> make_pieces(const Cluster& cluster, const std::vector<float>& radii, const SolidOptions& o,
                               const Vec3& origin, double scale, double floor, std::size_t& thickened) {
  const auto& ps = cluster.particles;
  std::vector<Piece> pieces;
  pieces.reserve(ps.size());
  std::vector<double> r(ps.size());
  thickened = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double own = static_cast<double>(radii[i]) * cluster.spacing * scale;
    r[i] = std::max(own, floor);
    thickened += own < floor;
  }
  const auto at = [&](std::size_t i) -> Point { return (ps[i].position - origin) * scale; };
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (o.shape == SolidShape::cubes) {
      pieces.push_back({at(i), at(i), std::max(0.5 * cluster.spacing * scale, floor), 0.0, true});
      continue;
    }
    const std::int32_t parent = ps[i].parent;
    if (o.shape == SolidShape::branches && parent >= 0) {
      const auto p = static_cast<std::size_t>(parent);
      pieces.push_back({at(i), at(p), r[i], r[p], false});
    } else {
      pieces.push_back({at(i), at(i), r[i], r[i], false});
    }
  }
  // A link is a branch like any other: the capsule between its particles.
  if (o.shape == SolidShape::branches)
    for (const Link& link : cluster.links) {
      const auto a = static_cast<std::size_t>(link.earlier), b = static_cast<std::size_t>(link.later);
      pieces.push_back({at(b), at(a), r[b], r[a], false});
    }
  if (o.join_seeds) {
    std::vector<Point> seeds;
    std::vector<double> seed_radii;
    for (std::size_t i = 0; i < cluster.seed_count && i < ps.size(); ++i) {
      seeds.push_back(at(i));
      seed_radii.push_back(o.shape == SolidShape::cubes ? pieces[i].ra : r[i]);
    }
    for (const Piece& bar : seed_bars(seeds, seed_radii)) pieces.push_back(bar);
  }
  return pieces;
}

//! The structure's solid's bounding box in scene units, radii scaled so as to be at least
//! floor_mm / scale.
Eigen::AlignedBox3d solid_box(const Cluster& cluster, const std::vector<float>& radii, const SolidOptions& o,
                              double floor_scene) {
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const double own = o.shape == SolidShape::cubes ? 0.5 * cluster.spacing
                                                   : static_cast<double>(radii[i]) * cluster.spacing;
    const double r = std::max(own, floor_scene);
    box.extend(Vec3(cluster.particles[i].position.array() - r));
    box.extend(Vec3(cluster.particles[i].position.array() + r));
  }
  return box;
}

SolidMesh mesh_of(const openvdb::FloatGrid& grid, double adaptivity) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, 0.0, adaptivity, true);
  malloc_trim(0);  // the meshing's working grids, freed, go back before the triangles are made
  SolidMesh mesh;
  mesh.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : triangles) mesh.triangles.push_back({t[0], t[1], t[2]});
  for (const openvdb::Vec4I& q : quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  quads = {};
  triangles = {};
  // Where the surface passes through a voxel's centre, neighbouring cells make the same point
  // twice: one vertex each place (an open-addressed table of first occurrences), and the
  // triangles that collapse with it left out.
  std::vector<std::uint32_t> same(points.size());
  {
    std::size_t slots = 16;
    while (slots < 2 * points.size()) slots *= 2;
    std::vector<std::uint32_t> table(slots, ~0u);
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      std::uint32_t bits[3];
      std::memcpy(bits, points[i].asPointer(), sizeof bits);
      std::uint64_t h = bits[0] * 0x9E3779B97F4A7C15ull ^ bits[1] * 0xC2B2AE3D27D4EB4Full ^ bits[2] * 0x165667B19E3779F9ull;
      for (std::size_t slot = (h ^ (h >> 29)) & (slots - 1);; slot = (slot + 1) & (slots - 1)) {
        if (table[slot] == ~0u) {
          table[slot] = same[i] = i;
          break;
        }
        if (points[table[slot]] == points[i]) {
          same[i] = table[slot];
          break;
        }
      }
    }
  }
  std::size_t kept = 0;
  for (const auto& t : mesh.triangles) {
    const std::array<std::uint32_t, 3> u = {same[t[0]], same[t[1]], same[t[2]]};
    if (u[0] != u[1] && u[1] != u[2] && u[0] != u[2]) mesh.triangles[kept++] = u;
  }
  mesh.triangles.resize(kept);
  // Only the points the polygons use, in the order they are first used.
  std::vector<std::uint32_t> renumber(points.size(), ~0u);
  for (auto& t : mesh.triangles)
    for (std::uint32_t& v : t) {
      if (renumber[v] == ~0u) {
        renumber[v] = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.emplace_back(points[v].x(), points[v].y(), points[v].z());
      }
      v = renumber[v];
    }
  return mesh;
}

//! Moves each vertex onto the surface of the union of `pieces`, along the gradient of the
//! closest piece's exact distance (a Newton step, by at most half a voxel). The mesher puts its
//! vertices where the grid's samples interpolate to zero, inside a curved surface (the distance
//! is convex across it): a branch 3 voxels across lost a quarter of its volume that way.
void project_onto(SolidMesh& mesh, const std::vector<Piece>& pieces, const std::vector<LeafPiece>& pairs,
                  double voxel, int threads) {
  const double step = 1e-4 * voxel, reach = voxel / 2.0;
  const auto project = [&](std::size_t from, std::size_t to) {
    // The mesher makes a leaf's vertices together: its pieces are looked up once for them.
    std::uint64_t leaf = ~0ull;
    const LeafPiece *begin = nullptr, *end = nullptr;
    for (std::size_t v = from; v < to; ++v) {
      const Point p = mesh.vertices[v].cast<double>();
      const Eigen::Vector3i at = (p / voxel).array().round().cast<int>();
      const std::uint64_t key = pack_leaf(leaf_of(at.x()), leaf_of(at.y()), leaf_of(at.z()));
      if (key != leaf) {
        leaf = key;
        begin = std::lower_bound(pairs.data(), pairs.data() + pairs.size(), LeafPiece{key, 0});
        for (end = begin; end != pairs.data() + pairs.size() && end->leaf == key;) ++end;
      }
      // The closest piece, and the next closest within half a voxel of it.
      const Piece *closest = nullptr, *next = nullptr;
      double d = std::numeric_limits<double>::infinity(), d_next = d;
      for (const LeafPiece* it = begin; it != end; ++it) {
        const Piece* piece = &pieces[it->piece];
        const double e = piece->distance(p);
        if (e < d) {
          d_next = d, next = closest;
          d = e, closest = piece;
        } else if (e < d_next) {
          d_next = e, next = piece;
        }
      }
      if (!closest) continue;
      const auto gradient = [&](const Piece& piece, double here) {
        Point g;
        for (int a = 0; a < 3; ++a) {
          Point ahead = p;
          ahead[a] += step;
          g[a] = (piece.distance(ahead) - here) / step;
        }
        return g;
      };
      const Point g = gradient(*closest, d);
      const double length = g.squaredNorm();
      if (!(length > 0.25)) continue;  // at a piece's axis or a cube's centre: no direction
      // Where two pieces meet at an angle (a crease), the mesher's vertex stays: moved onto
      // one piece it could cross the facets of the other.
      if (next && d_next - d < reach && gradient(*next, d_next).dot(g) < kCreaseCosine * std::sqrt(length)) continue;
      const Point move = -d * g / length;
      const double norm = move.norm();
      mesh.vertices[v] = (p + (norm > reach ? move * (reach / norm) : move)).cast<float>();
    }
  };
  const std::size_t n = mesh.vertices.size(), parts = static_cast<std::size_t>(threads);
  std::vector<std::thread> helpers;
  for (std::size_t t = 1; t < parts; ++t) helpers.emplace_back(project, n * t / parts, n * (t + 1) / parts);
  project(0, n / parts);
  for (std::thread& t : helpers) t.join();
}

//! Each vertex's shell: the connected pieces of the mesh, numbered from 0 in vertex order.
std::vector<std::uint32_t> shells_of(const SolidMesh& mesh, std::size_t& shells) {
  std::vector<std::uint32_t> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : mesh.triangles) {
    const std::uint32_t a = find(t[0]);
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t b = find(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::uint32_t> shell(mesh.vertices.size());
  shells = 0;
  for (std::uint32_t v = 0; v < parent.size(); ++v) shell[v] = find(v) == v ? static_cast<std::uint32_t>(shells++) : shell[find(v)];
  return shell;
}

double signed_volume(const SolidMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                        c = mesh.vertices[t[2]].cast<double>();
  return a.dot(b.cross(c)) / 6.0;
}

//! Turns the mesh outward and leaves out the voids the union encloses (the shells that face
//! in), which a print would fill anyway and a slicer counts as parts, any piece inside a void,
//! and specks of less than `least` volume: every piece of the union holds a whole particle's
//! sphere, so a smaller one is the closing's or the sampling's, not the structure's.
struct Filled {
  std::size_t shells = 0;  //!< kept
  double volume = 0.0;     //!< of the kept shells, summed in the order of their triangles
};
Filled orient_and_fill(SolidMesh& mesh, double least) {
  // Each triangle's signed volume once: the whole's, the shells' and the kept ones' sums.
  std::vector<double> signed_volumes(mesh.triangles.size());
  double volume = 0.0;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) volume += signed_volumes[k] = signed_volume(mesh, mesh.triangles[k]);
  if (volume < 0.0) {  // turned outward: every signed volume changes sign exactly
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    for (double& v : signed_volumes) v = -v;
  }
  std::size_t shells = 0;
  const std::vector<std::uint32_t> shell = shells_of(mesh, shells);
  std::vector<double> volumes(shells, 0.0);
  std::vector<Eigen::AlignedBox3f> boxes(shells);
  std::vector<std::uint32_t> first(shells, ~0u);
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
    boxes[shell[v]].extend(mesh.vertices[v]);
    if (first[shell[v]] == ~0u) first[shell[v]] = v;
  }
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) volumes[shell[mesh.triangles[k][0]]] += signed_volumes[k];
  std::vector<char> keep(shells);
  for (std::size_t s = 0; s < shells; ++s) keep[s] = volumes[s] > least;
  // A piece inside a void: its first vertex is inside the void's shell (by its winding number).
  for (std::size_t s = 0; s < shells; ++s) {
    if (!keep[s]) continue;
    for (std::size_t v = 0; v < shells && keep[s]; ++v) {
      if (volumes[v] >= 0.0 || !boxes[v].contains(boxes[s])) continue;  // not a void around it
      const Eigen::Vector3d p = mesh.vertices[first[s]].cast<double>();
      double winding = 0.0;
      for (const auto& t : mesh.triangles) {
        if (shell[t[0]] != v) continue;
        const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>() - p, b = mesh.vertices[t[1]].cast<double>() - p,
                              c = mesh.vertices[t[2]].cast<double>() - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        winding += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
      }
      if (std::abs(winding) > 2.0 * M_PI) keep[s] = 0;  // |winding number| above 1/2
    }
  }
  Filled kept;
  kept.shells = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
    if (keep[shell[mesh.triangles[k][0]]]) kept.volume += signed_volumes[k];
  if (kept.shells == shells) return kept;
  SolidMesh filled;
  std::vector<std::uint32_t> renumber(mesh.vertices.size(), ~0u);
  for (const auto& t : mesh.triangles) {
    if (!keep[shell[t[0]]]) continue;
    std::array<std::uint32_t, 3> kept_triangle;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& to = renumber[t[k]];
      if (to == ~0u) {
        to = static_cast<std::uint32_t>(filled.vertices.size());
        filled.vertices.push_back(mesh.vertices[t[k]]);
      }
      kept_triangle[k] = to;
    }
    filled.triangles.push_back(kept_triangle);
  }
  mesh = std::move(filled);
  return kept;
}

}  // namespace

void validate(const SolidOptions& o) {
  require_in_ranges(solid_option_table(), o);
  if (o.print_size != 0.0 && o.print_size < kPrintSizeWalls * o.min_wall)
    throw InvalidInput("`print_size` " + detail::format_number(o.print_size) + " mm leaves no room for branches `min_wall` " +
                       detail::format_number(o.min_wall) + " mm thick: give at least " +
                       detail::format_number(kPrintSizeWalls * o.min_wall) + " mm, or a thinner `min_wall`");
  if (o.threads < 0 || o.threads > 256) throw InvalidInput("solid threads " + std::to_string(o.threads) + " is not in 0-256");
}

namespace detail {

//! What plan_solid() found and build_solid() builds from, in the mesh's units.
struct SolidWork {
  SolidOptions options;
  std::vector<Piece> pieces;      // widened for meshing, and by the blend radius
  std::vector<LeafPiece> pairs;   // each leaf's pieces, sorted
  Vec3 origin = Vec3::Zero();
  double scale = 1.0, voxel = 0.0, smooth = 0.0, thinnest = 0.0;
  std::size_t thickened = 0;
  bool printing = false;
};

}  // namespace detail

double least_solid_bytes(const SolidForecast& f, const SolidOptions& o) {
  validate(o);
  if (f.particles == 0 || !(f.separation > 0.0)) return 0.0;
  // In spacings. Every particle's ball of radius r (a cube's: its inscribed ball) lies in the
  // solid, and those of radius half the separation are disjoint.
  const bool cubes = o.shape == SolidShape::cubes;
  const double least_radius = cubes ? 0.5 : f.least_radius, most_radius = cubes ? 0.5 : f.most_radius;
  // The voxel, or the largest it can be when derived: a third of the thinnest diameter.
  double voxel = o.voxel;
  if (voxel == 0.0) {
    if (o.print_size > 0.0) return 0.0;  // the thinnest is min_wall, in units the growth sets
    voxel = 2.0 * most_radius / kVoxelsAcross;
  }
  if (!(voxel > 0.0)) return 0.0;
  const double r = std::min(least_radius, f.separation / 2.0);
  const double ball = 4.0 / 3.0 * M_PI;
  const double volume = static_cast<double>(f.particles) * ball * r * r * r;
  // The band outside a body of that volume is at least a ball's: (V^1/3 + b (4 pi/3)^1/3)^3 - V.
  const double band = kBandVoxels * voxel;
  const double outer = std::pow(std::cbrt(volume) + band * std::cbrt(ball), 3.0) - volume;
  // Every leaf of 8^3 voxels that the band touches is stored, and they cover it.
  const double leaf = kLeafSide * voxel;
  const double smooth_factor = o.smooth > 0.0 ? 3.0 + 2.0 * o.smooth / voxel : 1.0;
  return outer / (leaf * leaf * leaf) * kBytesPerLeaf * smooth_factor;
}

void refuse_solid_before_growth(const SolidForecast& f, const SolidOptions& o) {
  const double least = least_solid_bytes(f, o);
  const double limit = o.memory > 0.0 ? o.memory * 1e6 : default_memory_limit();
  if (least <= limit) return;
  const bool derived = o.voxel == 0.0;
  SolidOptions coarser = o;
  coarser.voxel = derived ? 2.0 * (o.shape == SolidShape::cubes ? 0.5 : f.most_radius) / kVoxelsAcross : o.voxel;
  for (int tries = 0; tries < 200 && coarser.voxel < 100.0 && least_solid_bytes(f, coarser) > limit; ++tries)
    coarser.voxel = std::min(100.0, coarser.voxel * 1.25);
  const std::string voxel = derived ? "its voxel, a third of the thinnest branch," : "`solid_voxel` " + detail::format_number(o.voxel) + " spacings";
  throw InvalidInput("the solid of " + detail::format_count(f.particles) + " particles at " + voxel +
                     " would take at least " + megabytes(least) + ", more than the " + megabytes(limit) +
                     " it may use (`solid_memory`): give `solid_voxel` " +
                     detail::format_number(std::ceil(coarser.voxel * 1000.0) / 1000.0) +
                     " or more, or fewer `particles`");
}

SolidPlan plan_solid(const Cluster& cluster, const std::vector<float>& radii, const SolidOptions& o) {
  validate(o);
  if (radii.size() != cluster.particles.size())
    throw InvalidInput("the solid needs one radius a particle: " + std::to_string(radii.size()) + " for " +
                       std::to_string(cluster.particles.size()));
  SolidPlan plan;
  if (cluster.particles.empty()) return plan;

  // The scale: the solid's longest side is print_size, with every branch at least min_wall
  // thick at that scale (thickening widens the box, so the scale settles in a few rounds).
  const bool printing = o.print_size > 0.0;
  double scale = 1.0;
  Vec3 origin = Vec3::Zero();
  const double wall = printing ? o.min_wall : 0.0;
  if (printing) {
    for (int round = 0; round < 50; ++round) {
      const Eigen::AlignedBox3d box = solid_box(cluster, radii, o, wall / 2.0 / scale);
      const double next = o.print_size / box.sizes().maxCoeff();
      const bool settled = std::abs(next - scale) <= 1e-12 * scale;
      scale = next;
      origin = box.min();
      if (settled && round > 0) break;
    }
  }
  // The voxel: a third of the thinnest branch's diameter, unless given.
  std::size_t thickened = 0;
  std::vector<Piece> pieces = make_pieces(cluster, radii, o, origin, scale, wall / 2.0, thickened);
  double thinnest = std::numeric_limits<double>::infinity();
  for (const Piece& p : pieces) thinnest = std::min(thinnest, p.thinnest());
  double voxel = o.voxel > 0.0 ? o.voxel * cluster.spacing * scale : thinnest / kVoxelsAcross;
  const double smooth = o.smooth * cluster.spacing * scale;
  // Branches thinner than kThinnestVoxels voxels would break apart: drawn at that. A printed
  // wall gets a margin for the last rescaling, which may shrink it by up to two voxels in
  // print_size.
  const double print_margin = printing ? (o.print_size + 2.0 * voxel) / o.print_size : 1.0;
  const double floor = std::max(wall / 2.0 * print_margin, kThinnestVoxels * voxel / 2.0);
  if (floor > wall / 2.0) pieces = make_pieces(cluster, radii, o, origin, scale, floor, thickened);
  thinnest = std::numeric_limits<double>::infinity();
  for (const Piece& p : pieces) thinnest = std::min(thinnest, p.thinnest());
  // The mesh's facets are chords of the curved surface: each radius gains their mean depth,
  // so that the mesh holds the union's volume, not a few per cent less.
  for (Piece& p : pieces) {
    if (p.cube) continue;
    const bool sphere = p.a == p.b;
    p.ra += chord_depth(voxel, p.ra, sphere);
    p.rb += chord_depth(voxel, p.rb, sphere);
  }
  if (smooth > 0.0)  // the closing: dilate by the blend radius, then erode by it
    for (Piece& p : pieces) p.ra += smooth, p.rb += p.cube ? 0.0 : smooth;

  // Estimate first: refuse with a voxel that fits rather than run out of memory.
  const double limit = o.memory > 0.0 ? o.memory * 1e6 : default_memory_limit();
  const double smooth_factor = smooth > 0.0 ? 3.0 + 2.0 * smooth / voxel : 1.0;  // the closing's wider bands
  const double per_leaf = kBytesPerLeaf * smooth_factor;
  Estimate e = estimate(pieces, voxel, kBandVoxels * voxel, per_leaf, limit);
  if (e.bytes > limit) {
    // The coarser voxel the bound alone lets through: found in a moment, and sure to fit.
    double fits = voxel;
    for (int tries = 0; tries < 200; ++tries) {
      fits *= 1.25;
      // A coarser voxel thickens thin branches to kThinnestVoxels of it: its band reaches further.
      const double pad = std::max(0.0, kThinnestVoxels * fits / 2.0 - thinnest / 2.0);
      if (bound(pieces, fits, kBandVoxels * fits + pad).bytes(per_leaf) <= limit / 1.5) break;
    }
    const double per_spacing = cluster.spacing * scale;
    throw InvalidInput("the solid at `solid_voxel` " + detail::format_number(voxel / per_spacing) +
                       " spacings would take about " + megabytes(e.bytes) + ", more than the " + megabytes(limit) +
                       " it may use (`solid_memory`); `solid_voxel` " +
                       detail::format_number(std::ceil(fits / per_spacing * 1000.0) / 1000.0) + " fits");
  }
  auto work = std::make_shared<detail::SolidWork>();
  work->options = o;
  work->pieces = std::move(pieces);
  work->pairs = std::move(e.pairs);
  work->origin = origin;
  work->scale = scale;
  work->voxel = voxel;
  work->smooth = smooth;
  work->thinnest = thinnest;
  work->thickened = thickened;
  work->printing = printing;
  plan.bytes = e.bytes;
  const double threads = o.threads > 0 ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  // The closing's two rebuilds mesh and fill its wider bands again: about thrice their memory's
  // share of time (measured on a 3,000-particle tree at a blend radius of 3 voxels).
  plan.seconds = (e.leaves * kSecondsPerLeaf * (smooth > 0.0 ? 3.0 * smooth_factor : 1.0) +
                  static_cast<double>(work->pieces.size()) * kSecondsPerPiece) * 2.0 / std::min(2.0, threads);
  plan.voxel = voxel;
  plan.work = std::move(work);
  return plan;
}

Solid build_solid(const SolidPlan& plan, const StopFlag* stop, const StageProgress& progress) {
  detail::initialize_openvdb();
  Solid solid;
  solid.nearest = std::make_shared<detail::SolidNearest>();
  if (!plan.work) return solid;
  const detail::SolidWork& w = *plan.work;
  const SolidOptions& o = w.options;
  const std::vector<Piece>& pieces = w.pieces;
  const std::vector<LeafPiece>& pairs = w.pairs;
  const bool printing = w.printing;
  const double smooth = w.smooth;
  double voxel = w.voxel, scale = w.scale, thinnest = w.thinnest;
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // OpenVDB's own work (meshing, smoothing) on as many of them as TBB may use here: more would
  // only print TBB's warning.
  tbb::task_arena arena(std::min(threads, tbb::info::default_concurrency()));
  const auto report = [&](double fraction, std::string_view stage) {
    if (progress) progress(fraction, stage);
  };
  openvdb::FloatGrid::Ptr grid = rasterize(pieces, pairs, voxel, threads, stop, progress);
  if (smooth > 0.0) {
    report(kFillShare, "smoothing");
    arena.execute([&] {
      const float inside = static_cast<float>(smooth / voxel + kBandVoxels + 1.0);
      grid = openvdb::tools::levelSetRebuild(*grid, 0.0f, static_cast<float>(kBandVoxels), inside);
      if (stop && stop->load()) throw Interrupted("the solid was stopped while it was smoothed");
      grid = openvdb::tools::levelSetRebuild(*grid, static_cast<float>(-smooth), static_cast<float>(kBandVoxels),
                                             static_cast<float>(kBandVoxels));
    });
    grid->setName("surface");
  }
  if (stop && stop->load()) throw Interrupted("the solid was stopped before it was meshed");
  report(smooth > 0.0 ? 0.65 : kFillShare, "meshing");
  arena.execute([&] { solid.mesh = mesh_of(*grid, o.adaptivity); });
  if (stop && stop->load()) throw Interrupted("the solid was stopped while it was meshed");
  report(0.8, "fitting the surface");
  if (smooth == 0.0) project_onto(solid.mesh, pieces, pairs, voxel, threads);

  // Half the thinnest sphere's volume: the mesh's facets cut inside a little.
  const Filled filled = orient_and_fill(solid.mesh, M_PI / 12.0 * thinnest * thinnest * thinnest);
  const std::size_t shells = filled.shells;
  double volume = filled.volume, area = 0.0;
  for (const auto& t : solid.mesh.triangles) {
    const Eigen::Vector3d a = solid.mesh.vertices[t[0]].cast<double>(), b = solid.mesh.vertices[t[1]].cast<double>(),
                          c = solid.mesh.vertices[t[2]].cast<double>();
    area += (b - a).cross(c - a).norm() / 2.0;
  }
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& v : solid.mesh.vertices) box.extend(v);
  if (printing && !solid.mesh.vertices.empty()) {
    // The mesh's own box, within a voxel of the union's, to exactly print_size.
    const double exact = o.print_size / static_cast<double>(box.sizes().maxCoeff());
    for (Eigen::Vector3f& v : solid.mesh.vertices) v = (v.cast<double>() * exact).cast<float>();
    box = Eigen::AlignedBox3f();
    for (const Eigen::Vector3f& v : solid.mesh.vertices) box.extend(v);
    volume *= exact * exact * exact;
    area *= exact * exact;
    thinnest *= exact;
    scale *= exact;
    voxel *= exact;
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    openvdb::tools::foreach(grid->beginValueAll(), [exact](const openvdb::FloatGrid::ValueAllIter& it) {
      it.setValue(static_cast<float>(*it * exact));
    });
    grid->tree().root().setBackground(static_cast<float>(grid->background() * exact), false);
  }

  SolidMeasures& m = solid.measures;
  m.volume = volume;
  m.area = area;
  m.shells = shells;
  m.thinnest_wall = thinnest;
  m.thickened = w.thickened;
  m.estimated_bytes = plan.bytes;
  m.estimated_seconds = plan.seconds;
  m.voxel = voxel;
  m.scale = scale;
  m.active_voxels = grid->activeVoxelCount();
  m.size = solid.mesh.vertices.empty() ? Eigen::Vector3d::Zero() : box.sizes().cast<double>().eval();
  solid.origin = w.origin;
  report(1.0, "built");
  auto owned = std::make_shared<detail::SolidGrid>();
  owned->surface = grid;
  solid.grid = std::move(owned);
  return solid;
}

namespace {

//! Float points as nanoflann reads them.
struct KdPoints {
  std::vector<Eigen::Vector3f> at;
  std::size_t kdtree_get_point_count() const { return at.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t axis) const { return at[i][static_cast<int>(axis)]; }
  template <class Bbox>
  bool kdtree_get_bbox(Bbox&) const { return false; }
};

}  // namespace

struct detail::SolidNearest {
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, KdPoints>, KdPoints, 3,
                                                   std::uint32_t>;
  std::once_flag built;
  KdPoints particles;  // in the mesh's units
  std::unique_ptr<Tree> tree;
};

std::vector<std::int32_t> nearest_particles(const Cluster& cluster, const Solid& solid,
                                            const std::vector<Eigen::Vector3f>& points) {
  if (!solid.nearest) throw std::logic_error("nearest_particles of a solid that build_solid did not build");
  detail::SolidNearest& look_up = *solid.nearest;
  std::call_once(look_up.built, [&] {
    look_up.particles.at.reserve(cluster.particles.size());
    for (const Particle& p : cluster.particles)
      look_up.particles.at.push_back(((p.position - solid.origin) * solid.measures.scale).cast<float>());
    if (look_up.particles.at.empty()) return;
    look_up.tree = std::make_unique<detail::SolidNearest::Tree>(3, look_up.particles,
                                                                nanoflann::KDTreeSingleIndexAdaptorParams(16));
    look_up.tree->buildIndex();
  });
  std::vector<std::int32_t> nearest(points.size(), -1);
  if (!look_up.tree) return nearest;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint32_t index = 0;
    float d2 = 0.0f;
    look_up.tree->knnSearch(points[i].data(), 1, &index, &d2);
    nearest[i] = static_cast<std::int32_t>(index);
  }
  return nearest;
}

}  // namespace dla
