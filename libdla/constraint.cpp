#include "dla/mesh/constraint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace dla {

std::string_view to_string(Side side) {
  switch (side) {
    case Side::inside: return "inside";
    case Side::outside: return "outside";
    case Side::both: return "both";
  }
  return "?";
}

std::string_view to_string(ConstraintMode mode) {
  switch (mode) {
    case ConstraintMode::reject: return "reject";
    case ConstraintMode::clip: return "clip";
  }
  return "?";
}

Side parse_side(std::string_view word) {
  constexpr Side values[] = {Side::inside, Side::outside, Side::both};
  return detail::parse_word(word, values, "side");
}

ConstraintMode parse_constraint_mode(std::string_view word) {
  constexpr ConstraintMode values[] = {ConstraintMode::reject, ConstraintMode::clip};
  return detail::parse_word(word, values, "constraint");
}

double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: the closest point by Voronoi regions.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

namespace {

TriangleMesh repaired(const TriangleMesh& mesh, Side side, RepairReport& report) {
  RepairOptions options;
  options.close_holes = side != Side::both;
  TriangleMesh out = repair_mesh(mesh, options, &report);
  if (side != Side::both && !report.closed)
    throw InvalidInput("the mesh does not bound a volume even after hole filling (" + report.summary() +
                       "), so it has no inside: use --side both to take it as a wall");
  return out;
}

}  // namespace

MeshConstraint::MeshConstraint(const TriangleMesh& mesh, const ConstraintOptions& options, double spacing)
    : options_(options),
      spacing_(spacing),
      mesh_(repaired(mesh, options.side, repair_)),
      box_(bounding_box(mesh_)),
      center_(0.5 * (box_.min + box_.max)),
      radius_(0.5 * (box_.max - box_.min).norm()),
      gap_(std::max(1e-4 * spacing, 1e-6 * (box_.max - box_.min).maxCoeff())),
      inside_(mesh_, spacing + gap_, spacing),
      hits_(mesh_) {
  // Cumulative areas, and the volume's centroid by the divergence theorem.
  area_prefix_.reserve(mesh_.triangles.size());
  double area = 0.0, volume = 0.0;
  Vec3 moment = Vec3::Zero();
  for (const auto& t : mesh_.triangles) {
    const Vec3 &a = mesh_.vertices[t[0]], &b = mesh_.vertices[t[1]], &c = mesh_.vertices[t[2]];
    area += 0.5 * (b - a).cross(c - a).norm();
    area_prefix_.push_back(area);
    const double v = a.dot(b.cross(c)) / 6.0;
    volume += v;
    moment += v * (a + b + c) / 4.0;
  }
  centroid_ = volume > 0.0 && std::isfinite(volume) ? Vec3(moment / volume) : center_;
}

bool MeshConstraint::on_growth_side(const Vec3& p) const {
  switch (options_.side) {
    case Side::inside: return inside_.contains(p);
    case Side::outside: return !inside_.contains(p);
    case Side::both: return true;
  }
  return true;
}

BranchCheck MeshConstraint::check_branch(const Vec3& from, const Vec3& to) const {
  const double length = (to - from).norm();
  // Looking a gap past the end also refuses an end that float rounding in Embree would put on
  // the surface.
  const double margin = gap_ / length;
  const double t = hits_.first_hit(from, to, 0.0, 1.0 + margin);
  if (t < 0.0) return {true, false, to};
  if (options_.mode == ConstraintMode::reject) return {false, false, to};
  const double end = t - margin;
  // A stub shorter than half a spacing would pile particles onto one another at the surface.
  if (end * length < 0.5 * spacing_) return {false, false, to};
  return {true, true, from + end * (to - from)};
}

bool MeshConstraint::encloses(const Vec3& p) const {
  const Region region = inside_.region(p);
  return region == Region::inside || (region == Region::surface && inside_.contains(p));
}

Vec3 MeshConstraint::draw_inside(Rng& rng) const {
  constexpr int max_draws = 1'000'000;
  for (int draw = 0; draw < max_draws; ++draw) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box_.min[a] + (box_.max[a] - box_.min[a]) * rng.uniform();
    if (encloses(p)) return p;
  }
  throw GrowthError("no point inside the mesh in a million draws: it encloses no volume");
}

Vec3 MeshConstraint::surface_point(Rng& rng, Vec3* normal) const {
  const double target = rng.uniform() * area_prefix_.back();
  const std::size_t t = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(area_prefix_.begin(), area_prefix_.end(), target) - area_prefix_.begin()),
      mesh_.triangles.size() - 1);
  const auto& tri = mesh_.triangles[t];
  const Vec3 &a = mesh_.vertices[tri[0]], &b = mesh_.vertices[tri[1]], &c = mesh_.vertices[tri[2]];
  double u = rng.uniform(), v = rng.uniform();
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  if (normal) *normal = (b - a).cross(c - a).normalized();
  return a + u * (b - a) + v * (c - a);
}

Vec3 MeshConstraint::draw_radial(Rng& rng) const {
  constexpr int max_draws = 1'000'000;
  for (int draw = 0; draw < max_draws; ++draw) {
    const Vec3 s = surface_point(rng, nullptr);
    const Vec3 p = centroid_ + rng.uniform() * (s - centroid_);
    if (encloses(p)) return p;
  }
  throw GrowthError("no radial start inside the mesh in a million draws");
}

Vec3 MeshConstraint::draw_near_surface(Rng& rng) const {
  constexpr int max_draws = 1'000'000;
  for (int draw = 0; draw < max_draws; ++draw) {
    Vec3 normal;
    const Vec3 s = surface_point(rng, &normal);
    if (!normal.allFinite()) continue;  // a degenerate triangle
    // The normal's orientation is not trusted: take whichever side is the growing one.
    for (const double side : {0.5, -0.5}) {
      const Vec3 p = s + side * spacing_ * normal;
      if (encloses(p) == (options_.side == Side::inside)) return p;
    }
  }
  throw GrowthError("no start beside the mesh surface in a million draws");
}

std::vector<Vec3> MeshConstraint::sample_surface(std::uint64_t rng_seed) const {
  if (options_.side == Side::both)
    throw InvalidInput("--seed-surface needs a growing side to put the seeds on: --side inside or outside");
  const double area = area_prefix_.back() / (spacing_ * spacing_);
  constexpr double max_area = 500'000.0;
  if (!(area <= max_area))
    throw InvalidInput("the surface is " + detail::format_count(static_cast<std::uint64_t>(area)) +
                       " spacings² and --seed-surface places a seed a spacing²: more than 500,000; use a larger spacing");
  Rng rng(rng_seed, ~std::uint64_t{1});  // a stream no walker and no other seeding uses
  // Accepted points by cell of a spacing: a candidate checks the 27 cells about its own.
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  const auto cell_of = [&](const Vec3& p) {
    std::array<std::int64_t, 3> c;
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>(std::floor(p[a] / spacing_));
    return c;
  };
  const auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) & 0x1fffff) | (static_cast<std::uint64_t>(y) & 0x1fffff) << 21 |
           (static_cast<std::uint64_t>(z) & 0x1fffff) << 42;
  };
  std::vector<Vec3> seeds;
  const auto tries = static_cast<std::size_t>(std::ceil(4.0 * area)) + 1;
  for (std::size_t i = 0; i < tries; ++i) {
    const Vec3 p = draw_near_surface(rng);
    const auto c = cell_of(p);
    bool free = true;
    for (std::int64_t z = c[2] - 1; z <= c[2] + 1 && free; ++z)
      for (std::int64_t y = c[1] - 1; y <= c[1] + 1 && free; ++y)
        for (std::int64_t x = c[0] - 1; x <= c[0] + 1 && free; ++x) {
          const auto found = cells.find(key(x, y, z));
          if (found == cells.end()) continue;
          for (const std::uint32_t j : found->second)
            if ((seeds[j] - p).norm() < spacing_) free = false;
        }
    if (!free) continue;
    cells[key(c[0], c[1], c[2])].push_back(static_cast<std::uint32_t>(seeds.size()));
    seeds.push_back(p);
  }
  return seeds;
}

double MeshConstraint::distance_to_surface(const Vec3& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh_.triangles)
    best = std::min(best, distance_to_triangle(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]));
  return best;
}

std::vector<Vec3> MeshConstraint::place_seeds(std::size_t count, std::uint64_t rng_seed) const {
  if (count == 0) throw InvalidInput("--seeds 0: at least one seed is needed");
  if (options_.side == Side::both)
    throw InvalidInput("seeds cannot be placed automatically with --side both: place them with --seed-at");
  if (count > 1000) throw InvalidInput("--seeds " + std::to_string(count) + " is more than 1000");
  // Candidates from a stream no walker uses; the best by a greedy farthest-point rule.
  Rng rng(rng_seed, ~std::uint64_t{0});
  const std::size_t candidates = std::min<std::size_t>(4096, 64 + 64 * count);
  std::vector<Vec3> points;
  std::vector<double> depth;  // distance to the surface
  for (std::size_t i = 0; i < candidates; ++i) {
    Vec3 p;
    if (options_.side == Side::inside) {
      p = draw_inside(rng);
    } else {
      Vec3 normal;
      p = surface_point(rng, &normal);
      p += 2.0 * spacing_ * normal;
      if (!normal.allFinite() || inside_.contains(p)) continue;
    }
    const double d = distance_to_surface(p);
    if (d >= 1.5 * spacing_) {
      points.push_back(p);
      depth.push_back(d);
    }
  }
  std::vector<Vec3> seeds;
  std::vector<double> score(points.size());
  for (std::size_t k = 0; k < count; ++k) {
    // Inside: deep first, then far from the others and still deep. Outside: far apart.
    for (std::size_t i = 0; i < points.size(); ++i) {
      double apart = std::numeric_limits<double>::infinity();
      for (const Vec3& s : seeds) apart = std::min(apart, 0.5 * (points[i] - s).norm());
      score[i] = options_.side == Side::inside ? std::min(depth[i], apart) : (seeds.empty() ? -double(i) : apart);
    }
    const auto best = std::max_element(score.begin(), score.end());
    if (best == score.end() || (!seeds.empty() && *best < spacing_))
      throw InvalidInput("cannot place " + std::to_string(count) + " seeds " + std::string(to_string(options_.side)) +
                         " the mesh, each 1.5 spacings from the surface and 2 from the others: too many for a spacing of " +
                         detail::format_number(spacing_));
    seeds.push_back(points[static_cast<std::size_t>(best - score.begin())]);
  }
  return seeds;
}

}  // namespace dla
