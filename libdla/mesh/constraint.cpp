#include "dla/mesh/constraint.h"

#include "dla/mesh/mesh_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

namespace dla {

double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (p - closest_point_on_triangle(p, a, b, c)).norm();
}

namespace {

bool solid(Side side) { return side == Side::inside || side == Side::outside; }

TriangleMesh repaired(const TriangleMesh& mesh, Side side, RepairReport& report) {
  RepairOptions options;
  options.close_holes = solid(side);
  TriangleMesh out = repair_mesh(mesh, options, &report);
  if (solid(side) && !report.closed)
    throw InvalidInput("the mesh does not bound a volume even after hole filling (" + report.summary() +
                       "), so it has no inside: use `side` both to take it as a wall");
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
      hits_(mesh_),
      surface_(mesh_) {
  if (solid(options.side)) {
    const Region wrong = options.side == Side::inside ? Region::outside : Region::inside;
    lost_cells_ = BrickBits(inside_.grid(), [&](std::size_t cell) { return inside_.cell_region(cell) == wrong; });
    if (inside_.closed()) offset_sides_ = std::vector<std::atomic<Offset>>(mesh_.triangles.size());
  }
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
  // The guide: where the search for each of as many equal slices of the total area starts.
  const std::size_t slices = area_prefix_.size();
  area_guide_.resize(slices + 1);
  for (std::size_t j = 0; j <= slices; ++j)
    area_guide_[j] = static_cast<std::uint32_t>(
        std::upper_bound(area_prefix_.begin(), area_prefix_.end(), slice_start(j)) - area_prefix_.begin());
  const double layers = options.side == Side::surface && options.shell == 0.0 ? kShellSpacings : options.shell;
  if (layers != 0.0) {
    detail::require_in("`shell`", layers, 1.0, 1000.0);
    shell_thickness_ = layers * spacing;
    // Voxels of half a spacing: walkers stray at most 0.43 spacings past the layer.
    const Layer layer = options.side == Side::inside ? Layer::inside : options.side == Side::outside ? Layer::outside
                                                                                                      : Layer::both;
    shell_ = std::make_unique<ShellBand>(mesh_, inside_, layer, shell_thickness_, 0.5 * spacing);
    if (shell_->voxel_count() == 0)
      throw InvalidInput("the shell, " + detail::format_number(shell_thickness_) + " thick, holds no voxel of the " +
                         detail::format_number(shell_->cell_size()) + " the mesh's size allows: use a larger spacing");
  }
}

bool MeshConstraint::in_shell(const Vec3& p) const {
  if (surface_.distance(p) > shell_thickness_) return false;
  switch (options_.side) {
    case Side::inside: return inside_.contains(p);
    case Side::outside: return !inside_.contains(p);
    default: return true;
  }
}

bool MeshConstraint::on_growth_side(const Vec3& p) const {
  if (shell_) return in_shell(p);
  switch (options_.side) {
    case Side::inside: return inside_.contains(p);
    case Side::outside: return !inside_.contains(p);
    case Side::both:
    case Side::surface: return true;
  }
  return true;
}

BranchCheck MeshConstraint::check_branch(const Vec3& from, const Vec3& to) const {
  const double length = (to - from).norm();
  // Looking a gap past the end also refuses an end that float rounding in Embree would put on
  // the surface.
  const double margin = gap_ / length;
  const double t = hits_.first_hit(from, to, 0.0, 1.0 + margin);
  if (t < 0.0) return {!shell_ || in_shell(to), false, to};
  if (options_.mode == ConstraintMode::reject) return {false, false, to};
  const double end = t - margin;
  // A stub shorter than half a spacing would pile particles onto one another at the surface.
  if (end * length < 0.5 * spacing_) return {false, false, to};
  const Vec3 clipped = from + end * (to - from);
  return {!shell_ || in_shell(clipped), true, clipped};
}

bool MeshConstraint::encloses(const Vec3& p) const {
  const Region region = inside_.region(p);
  return region == Region::inside || (region == Region::surface && inside_.contains(p));
}

Vec3 MeshConstraint::draw_inside(Rng& rng) const {
  if (shell_) return shell_->draw(rng);
  constexpr int max_draws = 1'000'000;
  for (int draw = 0; draw < max_draws; ++draw) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box_.min[a] + (box_.max[a] - box_.min[a]) * rng.uniform();
    if (encloses(p)) return p;
  }
  throw GrowthError("no point inside the mesh in a million draws: it encloses no volume");
}

Vec3 MeshConstraint::surface_point(Rng& rng, Vec3* normal, std::uint32_t* triangle) const {
  const double target = rng.uniform() * area_prefix_.back();
  // The first prefix past the target, searched for only within the target's slice.
  const std::size_t slices = area_prefix_.size();
  auto first = area_prefix_.begin(), last = area_prefix_.end();
  const double fraction = target / area_prefix_.back();
  if (fraction >= 0.0 && fraction < 1.0) {  // else an area too large for a double: search it all
    std::size_t j = std::min(static_cast<std::size_t>(fraction * static_cast<double>(slices)), slices - 1);
    if (j > 0 && target < slice_start(j)) --j;  // the division may round across a slice's start
    if (j + 1 < slices && target >= slice_start(j + 1)) ++j;
    first = area_prefix_.begin() + area_guide_[j];
    last = area_prefix_.begin() + std::min<std::size_t>(area_guide_[j + 1] + 1, slices);
  }
  const std::size_t t = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(first, last, target) - area_prefix_.begin()), slices - 1);
  const auto& tri = mesh_.triangles[t];
  const Vec3 &a = mesh_.vertices[tri[0]], &b = mesh_.vertices[tri[1]], &c = mesh_.vertices[tri[2]];
  double u = rng.uniform(), v = rng.uniform();
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  if (normal) *normal = (b - a).cross(c - a).normalized();
  if (triangle) *triangle = static_cast<std::uint32_t>(t);
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
    std::uint32_t triangle;
    const Vec3 s = surface_point(rng, &normal, &triangle);
    const Vec3 p = beside(s, normal, rng, triangle);
    if (p.allFinite()) return p;  // else a degenerate triangle
  }
  throw GrowthError("no start beside the mesh surface in a million draws");
}

namespace {

//! Points no two closer than the spacing, thrown one after another (dart throwing): a
//! candidate checks the accepted points in the 27 cells of a spacing about its own.
class Darts {
 public:
  explicit Darts(double spacing) : spacing_(spacing) {}

  void throw_at(const Vec3& p) {
    if (!p.allFinite()) return;
    std::array<std::int64_t, 3> c;
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>(std::floor(p[a] / spacing_));
    for (std::int64_t z = c[2] - 1; z <= c[2] + 1; ++z)
      for (std::int64_t y = c[1] - 1; y <= c[1] + 1; ++y)
        for (std::int64_t x = c[0] - 1; x <= c[0] + 1; ++x) {
          const auto found = cells_.find(key(x, y, z));
          if (found == cells_.end()) continue;
          for (const std::uint32_t j : found->second)
            if ((points[j] - p).norm() < spacing_) return;
        }
    cells_[key(c[0], c[1], c[2])].push_back(static_cast<std::uint32_t>(points.size()));
    points.push_back(p);
  }

  std::vector<Vec3> points;

 private:
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) & 0x1fffff) | (static_cast<std::uint64_t>(y) & 0x1fffff) << 21 |
           (static_cast<std::uint64_t>(z) & 0x1fffff) << 42;
  }

  double spacing_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

//! Throws unless at most 500,000 seeds' worth of surface or curve is asked for.
void require_seedable(double measure, const char* unit, const char* option) {
  constexpr double max_measure = 500'000.0;
  if (!(measure <= max_measure))
    throw InvalidInput(std::string("there are ") + detail::format_count(static_cast<std::uint64_t>(measure)) + " " +
                       unit + " to seed and " + option + " places a seed a spacing apart: more than 500,000; " +
                       "use a larger spacing");
}

//! The triangles whose corners' colours could blend to a paint (all of them without one), by
//! cumulative area: points drawn on them are uniform by area over the painted part.
class PaintedArea {
 public:
  struct Point {
    Vec3 at, normal;
    std::uint32_t triangle;
  };

  PaintedArea(const TriangleMesh& mesh, const Paint* paint) : mesh_(mesh), paint_(paint) {
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      if (paint && !paint->may_match(mesh.colors[tri[0]], mesh.colors[tri[1]], mesh.colors[tri[2]])) continue;
      const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
      area_ += 0.5 * (b - a).cross(c - a).norm();
      triangles_.push_back(t);
      prefix_.push_back(area_);
    }
  }

  double area() const { return area_; }

  //! A point uniform by area over the triangles; nothing where the colours there blend to
  //! other than the paint, so that the painted part alone is drawn from.
  std::optional<Point> draw(Rng& rng) const {
    const std::size_t k = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(prefix_.begin(), prefix_.end(), rng.uniform() * area_) - prefix_.begin()),
        triangles_.size() - 1);
    const auto& tri = mesh_.triangles[triangles_[k]];
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
    if (paint_ && !paint_->matches((1 - u - v) * mesh_.colors[tri[0]] + u * mesh_.colors[tri[1]] + v * mesh_.colors[tri[2]]))
      return std::nullopt;
    const Vec3 &a = mesh_.vertices[tri[0]], &b = mesh_.vertices[tri[1]], &c = mesh_.vertices[tri[2]];
    return Point{a + u * (b - a) + v * (c - a), (b - a).cross(c - a).normalized(), triangles_[k]};
  }

 private:
  const TriangleMesh& mesh_;
  const Paint* paint_;
  std::vector<std::uint32_t> triangles_;
  std::vector<double> prefix_;
  double area_ = 0.0;
};

//! "#ffffff on 9,120 vertices, #ff0000 on 310": the most common colours, to say what there is.
std::string colors_used(const std::vector<Vec3>& colors) {
  std::map<std::string, std::size_t> counts;
  for (const Vec3& c : colors) ++counts["#" + hex_digits(c)];
  std::vector<std::pair<std::size_t, std::string>> order;
  for (const auto& [name, n] : counts) order.emplace_back(n, name);
  std::sort(order.begin(), order.end(), std::greater<>());
  std::string text;
  for (std::size_t i = 0; i < order.size() && i < 4; ++i)
    text += (i ? ", " : "") + order[i].second + " on " + detail::format_count(order[i].first) +
            (i ? "" : " vertices");
  return text;
}

}  // namespace

Vec3 MeshConstraint::beside(const Vec3& s, const Vec3& normal, Rng& rng, std::uint32_t triangle) const {
  if (!solid(options_.side)) return s + (rng.uniform() < 0.5 ? 0.5 : -0.5) * spacing_ * normal;  // either side grows
  // The normal's orientation is not trusted: take whichever side is the growing one, trying
  // first the one an outward normal (repair_mesh() turns them out) says it is.
  const double first = options_.side == Side::inside ? -0.5 : 0.5;
  const Offset known = triangle < offset_sides_.size() ? offset_side(triangle, first) : Offset::mixed;
  for (const double side : {first, -first}) {
    const Vec3 p = s + side * spacing_ * normal;
    if (side == first && known == Offset::growing) return p;
    if (side == first && known == Offset::other) continue;
    // Half a spacing off the surface is always in a surface cell of the grid: no look-up.
    if (inside_.contains(p) == (options_.side == Side::inside)) return p;
  }
  return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
}

MeshConstraint::Offset MeshConstraint::offset_side(std::uint32_t t, double side) const {
  Offset known = offset_sides_[t].load(std::memory_order_relaxed);
  if (known != Offset::unknown) return known;
  // The triangle moved as surface_point() and beside() move its points. Where it stays clear of
  // every triangle by the branches' gap (or, far from the origin, a billionth of the
  // coordinates), far beyond rounding, the closed mesh's winding number is one over all of it:
  // one inside test answers for every start off this triangle.
  const auto& tri = mesh_.triangles[t];
  const Vec3 &a = mesh_.vertices[tri[0]], &b = mesh_.vertices[tri[1]], &c = mesh_.vertices[tri[2]];
  const Vec3 shift = side * spacing_ * (b - a).cross(c - a).normalized();
  const double margin = std::max(gap_, 1e-9 * box_.min.cwiseAbs().cwiseMax(box_.max.cwiseAbs()).maxCoeff());
  known = Offset::mixed;
  if (inside_.clear_of_surface(a + shift, b + shift, c + shift, margin))
    known = inside_.contains((a + b + c) / 3.0 + shift) == (options_.side == Side::inside) ? Offset::growing
                                                                                              : Offset::other;
  offset_sides_[t].store(known, std::memory_order_relaxed);
  return known;
}

std::vector<Vec3> MeshConstraint::sample_surface(std::uint64_t rng_seed, const Paint* paint) const {
  const char* option = paint ? "`seed_paint`" : "`seed_surface`";
  if (options_.side == Side::both && !shell_)
    throw InvalidInput(std::string(option) + " needs a growing side to put the seeds on: `side` inside or outside");
  if (paint) require_paint(*paint, "seed_paint");
  const PaintedArea painted(mesh_, paint);
  require_seedable(painted.area() / (spacing_ * spacing_), "spacings² of surface", option);
  Rng rng(rng_seed, ~std::uint64_t{1});  // a stream no walker and no other seeding uses
  Darts darts(spacing_);
  const auto tries = static_cast<std::size_t>(std::ceil(4.0 * painted.area() / (spacing_ * spacing_))) + 1;
  for (std::size_t i = 0; i < tries; ++i)
    if (const auto point = painted.draw(rng)) darts.throw_at(beside(point->at, point->normal, rng));
  if (darts.points.empty())
    throw InvalidInput("the painted part of the mesh is too small for a seed at a spacing of " +
                       detail::format_number(spacing_) + ": use a smaller spacing or a larger `seed_paint` tolerance");
  return std::move(darts.points);
}

std::vector<Vec3> MeshConstraint::draw_near_paint(std::size_t count, Rng& rng, const Paint& paint,
                                                  const char* option) const {
  require_paint(paint, option);
  const PaintedArea painted(mesh_, &paint);
  constexpr int max_draws = 1'000'000;
  std::vector<Vec3> points;
  points.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    for (int draw = 0;; ++draw) {
      if (draw == max_draws)
        throw InvalidInput(std::string("no point of the part painted for `") + option + "` in a million draws: " +
                           "paint more of the mesh, or give a larger tolerance");
      const auto point = painted.draw(rng);
      if (!point) continue;
      const Vec3 p = beside(point->at, point->normal, rng, point->triangle);
      if (!p.allFinite()) continue;  // a degenerate triangle
      points.push_back(p);
      break;
    }
  return points;
}

void MeshConstraint::require_paint(const Paint& paint, const char* option) const {
  if (mesh_.colors.empty())
    throw InvalidInput(std::string("the mesh has no vertex colours for `") + option +
                       "`: paint it, and save it as PLY, OFF or OBJ with its colours");
  for (const auto& tri : mesh_.triangles)
    if (paint.may_match(mesh_.colors[tri[0]], mesh_.colors[tri[1]], mesh_.colors[tri[2]])) return;
  throw InvalidInput("no part of the mesh is painted within " + detail::format_number(paint.tolerance) + " of " +
                     "#" + hex_digits(paint.color) + " for `" + option + "`; its colours: " + colors_used(mesh_.colors));
}

std::vector<Vec3> MeshConstraint::sample_intersection(const std::vector<TriangleMesh>& others,
                                                      std::uint64_t rng_seed) const {
  if (options_.side == Side::both && !shell_)
    throw InvalidInput("`seed_mesh` needs a growing side to put the seeds on: `side` inside or outside");
  // Every piece, weighed by length (curves) or area over a spacing (patches): seeds per spacing.
  struct Piece {
    Vec3 a, b, c;  // c == a for a segment
    bool patch;
    Vec3 normal;
  };
  std::vector<Piece> pieces;
  std::vector<double> prefix;
  double measure = 0.0;
  const auto normal_of = [&](std::uint32_t t) {
    const auto& tri = mesh_.triangles[t];
    const Vec3 &a = mesh_.vertices[tri[0]], &b = mesh_.vertices[tri[1]], &c = mesh_.vertices[tri[2]];
    return Vec3((b - a).cross(c - a).normalized());
  };
  for (const TriangleMesh& other : others) {
    const SurfaceIntersection shared = intersect_surfaces(mesh_, other);
    for (const auto& s : shared.segments) {
      measure += (s.b - s.a).norm() / spacing_;
      pieces.push_back({s.a, s.b, s.a, false, normal_of(s.triangle)});
      prefix.push_back(measure);
    }
    for (const auto& p : shared.patches) {
      measure += 0.5 * (p.b - p.a).cross(p.c - p.a).norm() / (spacing_ * spacing_);
      pieces.push_back({p.a, p.b, p.c, true, normal_of(p.triangle)});
      prefix.push_back(measure);
    }
  }
  if (!(measure > 0.0)) throw InvalidInput("no `seed_mesh` meets the mesh's surface, so there is nowhere to seed");
  require_seedable(measure, "spacings of curve", "`seed_mesh`");
  Rng rng(rng_seed, ~std::uint64_t{2});  // a stream of its own
  Darts darts(spacing_);
  const auto tries = static_cast<std::size_t>(std::ceil(4.0 * measure)) + 1;
  for (std::size_t i = 0; i < tries; ++i) {
    const std::size_t k = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(prefix.begin(), prefix.end(), rng.uniform() * measure) - prefix.begin()),
        pieces.size() - 1);
    const Piece& piece = pieces[k];
    double u = rng.uniform(), v = piece.patch ? rng.uniform() : 0.0;
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
    darts.throw_at(beside(piece.a + u * (piece.b - piece.a) + v * (piece.c - piece.a), piece.normal, rng));
  }
  return std::move(darts.points);
}

std::vector<Vec3> farthest_apart(const std::vector<Vec3>& points, std::size_t count) {
  if (count > 1000)
    throw InvalidInput("`seeds` " + std::to_string(count) + " is more than 1000; `seeds` all covers the part at the spacing");
  if (points.size() < count)
    throw InvalidInput("`seeds` " + std::to_string(count) + ": only " + std::to_string(points.size()) +
                       " seeds fit there a spacing apart");
  if (count == 0) return {};
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p / static_cast<double>(points.size());
  std::vector<double> apart(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) apart[i] = -(points[i] - mean).norm();
  std::vector<Vec3> taken;
  while (taken.size() < count) {
    const auto best = static_cast<std::size_t>(std::max_element(apart.begin(), apart.end()) - apart.begin());
    taken.push_back(points[best]);
    for (std::size_t i = 0; i < points.size(); ++i)
      apart[i] = std::min(taken.size() == 1 ? std::numeric_limits<double>::infinity() : apart[i],
                          (points[i] - points[best]).norm());
  }
  return taken;
}

double MeshConstraint::distance_to_surface(const Vec3& p) const { return surface_.distance(p); }

std::vector<Vec3> MeshConstraint::place_seeds(std::size_t count, std::uint64_t rng_seed) const {
  if (count == 0) throw InvalidInput("`seeds` 0: at least one seed is needed");
  if (shell_) {
    // In a layer, depth means nothing: points half a spacing off the surface, far apart.
    Rng rng(rng_seed, ~std::uint64_t{0});
    std::vector<Vec3> candidates;
    for (std::size_t i = 0; i < std::min<std::size_t>(4096, 64 + 64 * count); ++i) candidates.push_back(draw_near_surface(rng));
    std::vector<Vec3> seeds = farthest_apart(candidates, count);
    for (std::size_t i = 1; i < seeds.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((seeds[i] - seeds[j]).norm() < 2.0 * spacing_)
          throw InvalidInput("cannot place " + std::to_string(count) + " seeds on the surface 2 spacings apart");
    return seeds;
  }
  if (options_.side == Side::both)
    throw InvalidInput("seeds cannot be placed automatically with `side` both: place them with `seed_at`");
  if (count > 1000) throw InvalidInput("`seeds` " + std::to_string(count) + " is more than 1000");
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
