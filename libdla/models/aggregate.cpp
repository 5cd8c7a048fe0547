// Cluster-cluster aggregation (aggregate.h): monomers in a periodic box that join as their
// clusters diffuse or fly into one another (dlca, rlca, ballistic), clusters that join as often
// as the bonds they offer (rlca's reaction-limited limit), or clusters joined two at a time on a
// fractal law (tuned).

#include "dla/models/aggregate.h"

#include "dla/core/errors.h"
#include "dla/core/random.h"
#include "dla/models/model_shell.h"
#include "crew.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace dla {

namespace {
//! The box's volume fraction at least: clusters a monomer radius a step take about 1/fraction
//! times as long to meet, 100 times DLCA's 4.5 s for 10^4 monomers here.
constexpr double kLeastVolumeFraction = 1e-4;
}  // namespace

const OptionTable<AggregateOptions>& aggregate_option_table() {
  using O = AggregateOptions;
  static const OptionTable<O> table{
      word("mode", &O::mode, "Aggregate",
           "how clusters meet: dlca (they diffuse and stick at first contact), rlca (reaction-limited: two join as "
           "often as the bonds they offer, at a contact drawn at random), ballistic (they fly straight) or tuned "
           "(joined two at a time on the law N = kf (Rg/a)^df)"),
      with_short_name(integer("monomers", &O::monomers, closed(1, kMaxMonomers), "monomers", "Aggregate",
                              "N, the monomers of the aggregate"),
                      "n"),
      real("monomer_radius", &O::monomer_radius, closed(1e-6, 1e6), "scene units", "Monomers",
           "a, the monomers' mean radius (lognormal sizes: their geometric mean)"),
      word("sizes", &O::sizes, "Monomers",
           "the monomers' radii: one (all a), lognormal (geometric standard deviation: the spread, cut at 4 of "
           "them) or normal (standard deviation: the spread times a, cut at 0.1 a)"),
      real("spread", &O::spread, closed(0, 2), "", "Monomers",
           "lognormal: the geometric standard deviation, at least 1 (1: none); normal: the standard deviation "
           "over the mean"),
      real("overlap", &O::overlap, closed(0, 0.5), "", "Monomers",
           "how far touching monomers sinter into one another: their centres are (1 - overlap)(r_i + r_j) apart; "
           "0: point contacts"),
      real("volume_fraction", &O::volume_fraction, closed(kLeastVolumeFraction, kMaxVolumeFraction), "", "Box",
           "dlca, ballistic, and rlca with a stick probability above 0: the monomers' share of the periodic box's "
           "volume"),
      real("stick_probability", &O::stick_probability, closed(0, 1), "", "Box",
           "rlca: 0, the reaction-limited limit: no box, and two clusters join as often as the monomers they offer "
           "to bond (N_i + N_j), at a contact drawn at random over all the ways they can touch; above 0: they "
           "diffuse in the box, and a contact sticks where it is made with this chance, else at a random contact "
           "(1: dlca)"),
      real("mobility_exponent", &O::mobility_exponent, closed(-3, 0), "", "Box",
           "dlca, ballistic, and rlca above stick probability 0: a cluster of N monomers moves as often as N to "
           "this power (-1/2: Stokes-Einstein "
           "with a radius that grows as N^(1/2), and the speed of a gas's clusters of equal energy)"),
      real("df", &O::df, closed(1, 3), "", "Tuned", "tuned: the fractal dimension D_f of N = kf (Rg/a)^df"),
      real("kf", &O::kf, open_closed(0, 10), "", "Tuned", "tuned: the prefactor k_f of N = kf (Rg/a)^df"),
      speed_only(integer("threads", &O::threads, closed(1, 256), "", "Aggregate",
                         "the box: threads that test the moves of clusters of 512 monomers or more; the aggregate "
                         "does not depend on it")),
  };
  return table;
}

namespace {

//! The largest R_g / a that N monomers reach (a straight chain of touching spheres, centres 2a
//! apart), and the smallest (a ball of them packed at random close packing, 0.64).
double chain_radius(double n) { return 2.0 * std::sqrt((n * n - 1.0) / 12.0); }
double packed_radius(double n) { return std::sqrt(3.0 / 5.0) * std::cbrt(n / 0.64); }

//! rlca's reaction-limited limit: clusters that meet without a box (KineticAggregation).
bool reaction_limited(const AggregateOptions& o) {
  return o.mode == AggregateMode::rlca && o.stick_probability == 0.0;
}

//! R_g / a of the tuned law at N monomers.
double law_radius(const AggregateOptions& o, double n) { return std::pow(n / o.kf, 1.0 / o.df); }

}  // namespace

void validate(const AggregateOptions& o) {
  require_in_ranges(aggregate_option_table(), o);
  if (o.sizes == MonomerSizes::lognormal && o.spread < 1.0)
    throw InvalidInput("`spread` " + detail::format_number(o.spread) +
                       " is below 1: a lognormal's geometric standard deviation is at least 1 (1: one size)");
  if (o.sizes == MonomerSizes::normal && o.spread > 1.0)
    throw InvalidInput("`spread` " + detail::format_number(o.spread) +
                       " is above 1: a normal spread of radii is at most the mean (try lognormal)");
  if (o.mode != AggregateMode::rlca && o.stick_probability != AggregateOptions{}.stick_probability)
    throw InvalidInput("`stick_probability` is for `mode` rlca");
  const bool tuned = o.mode == AggregateMode::tuned;
  const AggregateOptions unset;
  if (!tuned && (o.df != unset.df || o.kf != unset.kf)) throw InvalidInput("`df` and `kf` are for `mode` tuned");
  if ((tuned || reaction_limited(o)) &&
      (o.volume_fraction != unset.volume_fraction || o.mobility_exponent != unset.mobility_exponent))
    throw InvalidInput(std::string("`volume_fraction` and `mobility_exponent` are for the box: dlca, ballistic, and rlca with ") +
                       "a `stick_probability` above 0" + (tuned ? "" : " (at 0, rlca's clusters meet without a box)"));
  if (tuned && o.monomers >= 16 && o.sizes == MonomerSizes::one && o.overlap == 0.0) {
    // The law at N must lie between a straight chain and a packed ball of N monomers.
    const double n = static_cast<double>(o.monomers), rg = law_radius(o, n);
    if (rg > chain_radius(n))
      throw InvalidInput("`df` " + detail::format_number(o.df) + " and `kf` " + detail::format_number(o.kf) +
                         " ask " + std::to_string(o.monomers) + " monomers for R_g " + detail::format_number(rg) +
                         " a, beyond a straight chain's " + detail::format_number(chain_radius(n)) +
                         " a: raise df or kf");
    if (rg < packed_radius(n))
      throw InvalidInput("`df` " + detail::format_number(o.df) + " and `kf` " + detail::format_number(o.kf) +
                         " ask " + std::to_string(o.monomers) + " monomers for R_g " + detail::format_number(rg) +
                         " a, denser than spheres pack (" + detail::format_number(packed_radius(n)) +
                         " a): lower df or kf");
  }
}

FractalLaw fit_fractal_law(const std::vector<std::pair<double, double>>& sizes_and_radii) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, n = 0.0;
  for (const auto& [size, radius] : sizes_and_radii) {
    if (!(size > 0.0 && radius > 0.0)) continue;
    const double x = std::log(radius), y = std::log(size);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    n += 1.0;
  }
  const double spread = n * sxx - sx * sx;
  if (n < 2.0 || spread <= 0.0) return {};
  const double slope = (n * sxy - sx * sy) / spread;
  return {slope, std::exp((sy - slope * sx) / n)};
}

FractalLaw fit_joins(const AggregateStats& stats, double least) {
  std::vector<std::pair<double, double>> large;
  for (const auto& join : stats.joins)
    if (join.first >= least && join.second <= stats.crowded) large.push_back(join);
  return fit_fractal_law(large);
}

namespace {

//! R_g of monomers' centres (`members` of `x`), unweighted.
double gyration_of(const std::vector<std::int32_t>& members, const std::vector<Vec3>& x) {
  Vec3 sum = Vec3::Zero();
  double sum2 = 0.0;
  for (const std::int32_t m : members) {
    sum += x[static_cast<std::size_t>(m)];
    sum2 += x[static_cast<std::size_t>(m)].squaredNorm();
  }
  const double n = static_cast<double>(members.size());
  return std::sqrt(std::max(0.0, sum2 / n - (sum / n).squaredNorm()));
}

//! A standard normal number (Box-Muller: one of the pair, so that each draw takes two uniforms).
double standard_normal(Rng& rng) {
  const double u = 1.0 - rng.uniform();  // in (0, 1]
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * rng.uniform());
}

//! The monomers' radii, drawn as `sizes` says.
std::vector<double> monomer_radii(const AggregateOptions& o, Rng& rng) {
  std::vector<double> radii(o.monomers, o.monomer_radius);
  if (o.sizes == MonomerSizes::one || o.spread == (o.sizes == MonomerSizes::lognormal ? 1.0 : 0.0)) return radii;
  for (double& r : radii) {
    if (o.sizes == MonomerSizes::lognormal) {
      double z;
      do z = standard_normal(rng);
      while (std::abs(z) > 4.0);
      r = o.monomer_radius * std::pow(o.spread, z);
    } else {
      do r = o.monomer_radius * (1.0 + o.spread * standard_normal(rng));
      while (r < 0.1 * o.monomer_radius || r > (2.0 + 4.0 * o.spread) * o.monomer_radius);
    }
  }
  return radii;
}

//! The aggregate's structure from its monomers and the contacts that joined them: breadth-first
//! from the monomer nearest the centroid, centred on it.
Cluster assemble(const std::vector<std::int32_t>& members, const std::vector<Vec3>& positions,
                 const std::vector<double>& radii, const std::vector<std::pair<std::int32_t, std::int32_t>>& contacts,
                 double mean_radius) {
  std::unordered_map<std::int32_t, std::int32_t> local;  // monomer -> its place in `members`
  local.reserve(members.size() * 2);
  for (std::size_t k = 0; k < members.size(); ++k) local.emplace(members[k], static_cast<std::int32_t>(k));
  std::vector<std::vector<std::int32_t>> touching(members.size());
  for (const auto& [a, b] : contacts) {
    const auto ia = local.find(a), ib = local.find(b);
    if (ia == local.end() || ib == local.end()) continue;
    touching[static_cast<std::size_t>(ia->second)].push_back(ib->second);
    touching[static_cast<std::size_t>(ib->second)].push_back(ia->second);
  }
  Vec3 centroid = Vec3::Zero();
  for (const std::int32_t m : members) centroid += positions[static_cast<std::size_t>(m)];
  centroid /= static_cast<double>(members.size());
  std::size_t root = 0;
  for (std::size_t k = 1; k < members.size(); ++k)
    if ((positions[static_cast<std::size_t>(members[k])] - centroid).squaredNorm() <
        (positions[static_cast<std::size_t>(members[root])] - centroid).squaredNorm())
      root = k;

  Cluster out;
  out.spacing = 2.0 * mean_radius;
  out.dimensions = 3;
  out.seed_count = 1;
  out.particles.reserve(members.size());
  out.radii.reserve(members.size());
  std::vector<std::int32_t> order(members.size(), -1);  // local -> place in the output
  std::deque<std::size_t> queue{root};
  order[root] = 0;
  const auto add = [&](std::size_t k, std::int32_t parent) {
    const auto m = static_cast<std::size_t>(members[k]);
    out.particles.push_back({positions[m] - centroid, parent, 0});
    out.radii.push_back(radii[m]);
  };
  add(root, -1);
  while (!queue.empty()) {
    const std::size_t k = queue.front();
    queue.pop_front();
    for (const std::int32_t next : touching[k]) {
      const auto n = static_cast<std::size_t>(next);
      if (order[n] >= 0) continue;
      order[n] = static_cast<std::int32_t>(out.particles.size());
      add(n, order[k]);
      queue.push_back(n);
    }
  }
  return out;
}

//! The clusters left, by id, in no order: each taken out in O(1), the last put in its place.
class ClustersLeft {
 public:
  //! Clusters 0 to n - 1: every monomer its own.
  explicit ClustersLeft(std::size_t n) : ids_(n), place_of_(n) {
    std::iota(ids_.begin(), ids_.end(), 0);
    std::iota(place_of_.begin(), place_of_.end(), 0);
  }
  std::size_t size() const { return ids_.size(); }
  //! One drawn uniformly.
  std::int32_t draw(Rng& rng) const { return ids_[static_cast<std::size_t>(rng() % ids_.size())]; }
  void take_out(std::int32_t id) {
    const std::int32_t place = place_of_[static_cast<std::size_t>(id)];
    ids_[static_cast<std::size_t>(place)] = ids_.back();
    place_of_[static_cast<std::size_t>(ids_.back())] = place;
    ids_.pop_back();
  }

 private:
  std::vector<std::int32_t> ids_, place_of_;
};

//! The growth loop of the cluster modes: `step()` until one cluster is left or growth is
//! stopped, with progress every `steps_per_look` steps; `largest()` is the largest cluster so
//! far, what progress sees and a stop keeps (marked incomplete).
template <class Step, class Largest>
Cluster join_until_one(const ClustersLeft& left, const ProgressFn& progress, const StopFlag* stop,
                       std::uint32_t steps_per_look, Step&& step, Largest&& largest) {
  detail::ModelShell shell(progress, stop, steps_per_look);
  bool stopped = false;
  while (left.size() > 1) {
    if (!shell.go_on_making(largest)) {
      stopped = true;
      break;
    }
    step();
  }
  Cluster out = largest();
  out.complete = !stopped;
  if (!stopped) shell.finish(out);
  return out;
}

// ---------------------------------------------------------------------------------------------
// The box: dlca, rlca, ballistic.

//! Monomers in a periodic box of side `side`, binned in cells at least `reach` wide, each in a
//! doubly linked list of its cell's monomers, so that a move re-bins only those that change cell.
//! At most about 8 cells a monomer: a dilute box's cells are wider, not more.
class PeriodicGrid {
 public:
  PeriodicGrid(double side, double reach, std::size_t monomers)
      : side_(side),
        cells_(std::max<std::int64_t>(1, std::min(static_cast<std::int64_t>(side / reach),
                                                  static_cast<std::int64_t>(std::cbrt(8.0 * static_cast<double>(monomers)))))) {
    if (cells_ < 3) cells_ = 1;  // too few to tell neighbours apart: one cell, every image looked at
    width_ = side_ / static_cast<double>(cells_);
    head_.assign(static_cast<std::size_t>(cells_ * cells_ * cells_), -1);
    next_.assign(monomers, -1);
    previous_.assign(monomers, -1);
    cell_.assign(monomers, -1);
  }

  double side() const { return side_; }
  //! Whether each monomer has one image within reach of another (else every image is looked at).
  bool one_image() const { return cells_ >= 3; }

  Vec3 wrap(const Vec3& p) const {
    Vec3 w;
    for (int a = 0; a < 3; ++a) w[a] = p[a] - side_ * std::floor(p[a] / side_);
    return w;
  }
  //! The shortest of `d`'s periodic images.
  Vec3 nearest_image(Vec3 d) const {
    for (int a = 0; a < 3; ++a) d[a] -= side_ * std::round(d[a] / side_);
    return d;
  }

  std::array<std::int64_t, 3> cell_of(const Vec3& wrapped) const {
    std::array<std::int64_t, 3> c;
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(wrapped[a] / width_), 0, cells_ - 1);
    return c;
  }
  std::int64_t index(std::int64_t x, std::int64_t y, std::int64_t z) const {
    const auto wrap_cell = [this](std::int64_t c) { return ((c % cells_) + cells_) % cells_; };
    return (wrap_cell(z) * cells_ + wrap_cell(y)) * cells_ + wrap_cell(x);
  }

  void place(std::int32_t m, const Vec3& wrapped) {
    const auto c = cell_of(wrapped);
    const std::int64_t cell = index(c[0], c[1], c[2]);
    const auto mi = static_cast<std::size_t>(m);
    if (cell_[mi] == cell) return;
    if (cell_[mi] >= 0) {  // unlink from the old cell
      if (previous_[mi] >= 0) next_[static_cast<std::size_t>(previous_[mi])] = next_[mi];
      else head_[static_cast<std::size_t>(cell_[mi])] = next_[mi];
      if (next_[mi] >= 0) previous_[static_cast<std::size_t>(next_[mi])] = previous_[mi];
    }
    cell_[mi] = cell;
    previous_[mi] = -1;
    next_[mi] = head_[static_cast<std::size_t>(cell)];
    if (next_[mi] >= 0) previous_[static_cast<std::size_t>(next_[mi])] = m;
    head_[static_cast<std::size_t>(cell)] = m;
  }

  //! Calls visit(q) for each monomer in the cells around `wrapped`'s (its own and the 26 beside).
  template <class Visit>
  void around(const Vec3& wrapped, Visit&& visit) const {
    if (cells_ == 1) {
      for (std::int32_t q = head_[0]; q >= 0; q = next_[static_cast<std::size_t>(q)]) visit(q);
      return;
    }
    const auto c = cell_of(wrapped);
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx)
          for (std::int32_t q = head_[static_cast<std::size_t>(index(c[0] + dx, c[1] + dy, c[2] + dz))]; q >= 0;
               q = next_[static_cast<std::size_t>(q)])
            visit(q);
  }

 private:
  double side_, width_ = 1.0;
  std::int64_t cells_;
  std::vector<std::int32_t> head_, next_, previous_;
  std::vector<std::int64_t> cell_;
};

//! The first time t in [0, limit) at which a sphere moving by t * d from `gap` = q - p away comes
//! within `contact` of q; `limit` if it does not.
double first_contact(const Vec3& gap, const Vec3& d, double contact, double limit) {
  const double b = gap.dot(d);
  if (b <= 0.0) return limit;  // moving away, or alongside
  const double c = gap.squaredNorm() - contact * contact;
  if (c <= 0.0) return 0.0;  // touching already (rounding): it may not come closer
  const double a = d.squaredNorm(), disc = b * b - a * c;
  if (disc < 0.0) return limit;
  const double t = c / (b + std::sqrt(disc));  // the smaller root, without cancellation
  return t < limit ? t : limit;
}

//! A rotation uniform over all rotations: a unit quaternion of four normal numbers, drawn one
//! a statement (the order of a call's arguments is the compiler's, and the same seed must give
//! the same aggregate whichever compiled it).
Eigen::Matrix3d random_rotation(Rng& rng) {
  const double w = standard_normal(rng), x = standard_normal(rng), y = standard_normal(rng), z = standard_normal(rng);
  return Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
}

//! A rotation taking the unit vector `from` to the unit vector `to`, then turned by `spin` about `to`.
Eigen::Matrix3d rotation(const Vec3& from, const Vec3& to, double spin) {
  const Eigen::Matrix3d align = Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
  return Eigen::AngleAxisd(spin, to).toRotationMatrix() * align;
}

//! A unit vector at right angles to `axis` (a unit vector), turned by `angle` about it.
Vec3 perpendicular(const Vec3& axis, double angle) {
  const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = axis.cross(helper).normalized(), v = axis.cross(u);
  return std::cos(angle) * u + std::sin(angle) * v;
}

//! Monomers of one cluster binned for the overlap test of another's placements against them.
class OverlapGrid {
 public:
  //! `largest`: the largest radius of any monomer binned or tested.
  OverlapGrid(const std::vector<std::int32_t>& members, const std::vector<Vec3>& x, const std::vector<double>& radii,
              double overlap, double largest)
      : x_(x), radii_(radii), keep_(1.0 - overlap), width_(2.0 * keep_ * largest), largest_(largest) {
    for (const std::int32_t m : members) add(m);
  }
  //! Bins monomer m where it is now.
  void add(std::int32_t m) { cells_[key(x_[static_cast<std::size_t>(m)])].push_back(m); }
  //! Whether a monomer of radius r at p stays clear of the monomers binned, but `touching`,
  //! which it is to touch.
  bool clear(const Vec3& p, double r, std::int32_t touching) const {
    const double span = keep_ * (r + largest_);
    const auto lo = cell(p - Vec3::Constant(span)), hi = cell(p + Vec3::Constant(span));
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t xx = lo[0]; xx <= hi[0]; ++xx) {
          const auto found = cells_.find(pack({xx, y, z}));
          if (found == cells_.end()) continue;
          for (const std::int32_t q : found->second) {
            if (q == touching) continue;
            const double c = keep_ * (r + radii_[static_cast<std::size_t>(q)]) * (1.0 - 1e-9);
            if ((x_[static_cast<std::size_t>(q)] - p).squaredNorm() < c * c) return false;
          }
        }
    return true;
  }

 private:
  std::array<std::int64_t, 3> cell(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / width_)), static_cast<std::int64_t>(std::floor(p.y() / width_)),
            static_cast<std::int64_t>(std::floor(p.z() / width_))};
  }
  static std::uint64_t pack(const std::array<std::int64_t, 3>& c) {
    const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
    return part(c[0]) | part(c[1]) << 21 | part(c[2]) << 42;
  }
  std::uint64_t key(const Vec3& p) const { return pack(cell(p)); }

  const std::vector<Vec3>& x_;
  const std::vector<double>& radii_;
  double keep_, width_, largest_;
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> cells_;
};

//! A point `radius` from `centre` and `reach` from the point `distance` from it along the unit
//! vector `axis`, at a random angle on the circle of all such points (the distances must allow one).
Vec3 on_two_spheres(const Vec3& centre, const Vec3& axis, double distance, double radius, double reach, Rng& rng) {
  const double along = (distance * distance + radius * radius - reach * reach) / (2.0 * distance);
  const double across = std::sqrt(std::max(0.0, radius * radius - along * along));
  return centre + along * axis + across * perpendicular(axis, 2.0 * M_PI * rng.uniform());
}

//! Places the monomers at random in the box, none overlapping another (random sequential
//! addition), largest first so that the last, small ones find room.
void scatter(std::vector<Vec3>& positions, const std::vector<double>& radii, double side, double keep,
             double volume_fraction, Rng& rng) {
  std::vector<std::size_t> order(radii.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return radii[a] > radii[b]; });
  const double largest = radii.empty() ? 0.0 : radii[order[0]];
  PeriodicGrid grid(side, 2.0 * keep * largest, radii.size());
  std::vector<Vec3> wrapped(radii.size());
  std::vector<bool> placed(radii.size(), false);
  for (const std::size_t m : order) {
    for (std::size_t attempt = 0;; ++attempt) {
      if (attempt > 100000)
        throw InvalidInput("`volume_fraction` " + detail::format_number(volume_fraction) +
                           ": a monomer found no room in the box after 100,000 tries; a lower one leaves more");
      // One draw a statement: the order of a call's arguments is the compiler's.
      const double x = rng.uniform(), y = rng.uniform(), z = rng.uniform();
      const Vec3 p = side * Vec3(x, y, z);
      bool free = true;
      grid.around(p, [&](std::int32_t q) {
        const auto qi = static_cast<std::size_t>(q);
        if (!free || !placed[qi]) return;
        const double contact = keep * (radii[m] + radii[qi]);
        if (grid.one_image()) {
          free = grid.nearest_image(wrapped[qi] - p).squaredNorm() >= contact * contact;
        } else {
          for (int z = -1; z <= 1 && free; ++z)
            for (int y = -1; y <= 1 && free; ++y)
              for (int x = -1; x <= 1 && free; ++x)
                free = (grid.nearest_image(wrapped[qi] - p) + side * Vec3(x, y, z)).squaredNorm() >= contact * contact;
        }
      });
      if (!free) continue;
      positions[m] = wrapped[m] = p;
      placed[m] = true;
      grid.place(static_cast<std::int32_t>(m), p);
      break;
    }
  }
}

class BoxAggregation {
 public:
  BoxAggregation(const AggregateOptions& o, std::vector<double> radii, Rng& rng, AggregateStats& stats)
      : o_(o), rng_(rng), stats_(stats), radii_(std::move(radii)), step_(o.monomer_radius),
        largest_radius_(*std::max_element(radii_.begin(), radii_.end())),
        grid_(box_side(o, radii_), reach(o, radii_), radii_.size()), left_(radii_.size()), crew_(o.threads) {
    stats_.box = grid_.side();
    stats_.crowded = 0.25 * grid_.side() / o.monomer_radius;
    const std::size_t n = radii_.size();
    positions_.resize(n);
    scatter(positions_, radii_, grid_.side(), 1.0 - o.overlap, o.volume_fraction, rng_);
    wrapped_.resize(n);
    owner_.resize(n);
    clusters_.resize(n);
    for (std::size_t m = 0; m < n; ++m) {
      const auto id = static_cast<std::int32_t>(m);
      owner_[m] = id;
      clusters_[m].members = {id};
      clusters_[m].heading = random_direction(rng_, 3);
      place(id);
    }
    sizes_[1] = n;
  }

  //! Joins every monomer into one cluster, or stops early; returns the largest cluster.
  Cluster grow(const ProgressFn& progress, const StopFlag* stop) {
    return join_until_one(left_, progress, stop, 1024, [&] { move(pick()); }, [&] { return largest_so_far(); });
  }

 private:
  //! The largest cluster so far, as the structure: what a progress call sees, and what a stop
  //! keeps.
  Cluster largest_so_far() const {
    return assemble(clusters_[static_cast<std::size_t>(largest_)].members, positions_, radii_, contacts_, o_.monomer_radius);
  }

  struct Group {
    std::vector<std::int32_t> members;
    Vec3 heading = Vec3::UnitX();  //!< ballistic: the direction it flies
    double flown = 0.0;            //!< ballistic: how far it has flown that way
  };

  static double box_side(const AggregateOptions& o, const std::vector<double>& radii) {
    double volume = 0.0;
    for (const double r : radii) volume += 4.0 / 3.0 * M_PI * r * r * r;
    return std::cbrt(volume / o.volume_fraction);
  }
  //! A cell's width: the farthest a monomer's centre can be from one it meets in a step.
  static double reach(const AggregateOptions& o, const std::vector<double>& radii) {
    return 2.0 * (1.0 - o.overlap) * *std::max_element(radii.begin(), radii.end()) + o.monomer_radius;
  }

  void place(std::int32_t m) {
    const auto mi = static_cast<std::size_t>(m);
    wrapped_[mi] = grid_.wrap(positions_[mi]);
    grid_.place(m, wrapped_[mi]);
  }

  //! A cluster, chosen as often as its size to the mobility exponent against the smallest's.
  std::int32_t pick() {
    const double smallest = static_cast<double>(sizes_.begin()->first);
    while (true) {
      const std::int32_t c = left_.draw(rng_);
      if (o_.mobility_exponent == 0.0) return c;
      const double size = static_cast<double>(clusters_[static_cast<std::size_t>(c)].members.size());
      if (size == smallest || rng_.uniform() < std::pow(size / smallest, o_.mobility_exponent)) return c;
    }
  }

  void move(std::int32_t c) {
    Group& group = clusters_[static_cast<std::size_t>(c)];
    ++stats_.moves;
    Vec3 d;
    if (o_.mode == AggregateMode::ballistic) {
      // A gas's clusters fly straight until something turns them: here a box length.
      if (group.flown >= grid_.side()) {
        group.heading = random_direction(rng_, 3);
        group.flown = 0.0;
      }
      d = step_ * group.heading;
      group.flown += step_;
    } else {
      d = step_ * random_direction(rng_, 3);
    }
    // The first contact of the step. A large cluster's monomers are split among the crew in
    // runs, each keeping its first; the earliest run's wins a tie, so the contact is the one a
    // single thread finds.
    const std::size_t members = group.members.size();
    const std::size_t runs = crew_.size() > 1 && members >= kSplitFrom ? std::min(members / 128, 8 * crew_.size()) : 1;
    Contact first;
    if (runs == 1) {
      first = first_contact_of(group.members, 0, members, c, d);
    } else {
      firsts_.resize(runs);
      crew_.run(runs, [&](std::size_t run) {
        firsts_[run] = first_contact_of(group.members, members * run / runs, members * (run + 1) / runs, c, d);
      });
      for (const Contact& f : firsts_)
        if (f.t < first.t) first = f;
    }
    const double t = first.t;
    const std::int32_t hit_p = first.p, hit_q = first.q;
    if (hit_p >= 0) ++stats_.contacts;
    if (hit_p >= 0 && o_.mode == AggregateMode::rlca && rng_.uniform() >= o_.stick_probability &&
        join_at_random_contact(c, owner_[static_cast<std::size_t>(hit_q)]))
      return;
    for (const std::int32_t p : group.members) {
      positions_[static_cast<std::size_t>(p)] += t * d;
      place(p);
    }
    if (hit_p >= 0) join(c, hit_p, hit_q);
  }

  //! Where a step d of cluster c first brings one of its monomers members[begin, end) into
  //! contact with another cluster's, as a fraction of the step (first_contact_of()).
  struct Contact {
    double t = 1.0;  //!< 1: none within the step
    std::int32_t p = -1, q = -1;
  };
  static constexpr std::size_t kSplitFrom = 512;
  Contact first_contact_of(const std::vector<std::int32_t>& members, std::size_t begin, std::size_t end, std::int32_t c,
                           const Vec3& d) const {
    // In locals, not the struct: the lambdas below keep them in registers.
    double t = 1.0;
    std::int32_t hit_p = -1, hit_q = -1;
    const double keep = 1.0 - o_.overlap;
    for (std::size_t k = begin; k < end; ++k) {
      const std::int32_t p = members[k];
      const auto pi = static_cast<std::size_t>(p);
      const Vec3& wp = wrapped_[pi];
      grid_.around(wp, [&](std::int32_t q) {
        const auto qi = static_cast<std::size_t>(q);
        if (owner_[qi] == c) return;
        const double contact = keep * (radii_[pi] + radii_[qi]);
        const Vec3 gap = grid_.nearest_image(wrapped_[qi] - wp);
        const auto test = [&](const Vec3& g) {
          const double reach2 = (contact + step_) * (contact + step_);
          if (g.squaredNorm() > reach2) return;
          const double at = first_contact(g, d, contact, t);
          if (at < t) {
            t = at;
            hit_p = p;
            hit_q = q;
          }
        };
        if (grid_.one_image()) {
          test(gap);
        } else {
          const double side = grid_.side();
          for (int z = -1; z <= 1; ++z)
            for (int y = -1; y <= 1; ++y)
              for (int x = -1; x <= 1; ++x) test(gap + side * Vec3(x, y, z));
        }
      });
    }
    return {t, hit_p, hit_q};
  }

  //! rlca, a contact that does not stick where it was made: the two clusters roll over each
  //! other until they stick, which in the reaction-limited limit is at any of the ways they can
  //! touch with equal chance (Jullien and Kolb 1984): a monomer of each, the moving cluster
  //! turned at random and touching from a random direction, drawn again while it overlaps
  //! either cluster or a third. Returns false when kContactDraws draws found none (the contact
  //! then sticks where it was made).
  bool join_at_random_contact(std::int32_t moving, std::int32_t met) {
    constexpr int kContactDraws = 2000;
    const std::vector<std::int32_t>& a = clusters_[static_cast<std::size_t>(moving)].members;
    const std::vector<std::int32_t>& b = clusters_[static_cast<std::size_t>(met)].members;
    const OverlapGrid met_grid(b, positions_, radii_, o_.overlap, largest_radius_);
    const double keep = 1.0 - o_.overlap;
    std::vector<Vec3> placed(a.size());
    for (int draw = 0; draw < kContactDraws; ++draw) {
      const Eigen::Matrix3d turn = random_rotation(rng_);
      const std::int32_t i = a[static_cast<std::size_t>(rng_() % a.size())];
      const std::int32_t j = b[static_cast<std::size_t>(rng_() % b.size())];
      const auto ii = static_cast<std::size_t>(i), ji = static_cast<std::size_t>(j);
      const Vec3 at = positions_[ji] + keep * (radii_[ii] + radii_[ji]) * random_direction(rng_, 3);
      bool clear = true;
      for (std::size_t k = 0; k < a.size() && clear; ++k) {
        const auto pi = static_cast<std::size_t>(a[k]);
        placed[k] = at + turn * (positions_[pi] - positions_[ii]);
        clear = met_grid.clear(placed[k], radii_[pi], a[k] == i ? j : -1) && clear_of_others(placed[k], pi, moving, met);
      }
      if (!clear) continue;
      for (std::size_t k = 0; k < a.size(); ++k) {
        positions_[static_cast<std::size_t>(a[k])] = placed[k];
        place(a[k]);
      }
      join(moving, i, j);
      return true;
    }
    return false;
  }

  //! Whether monomer m placed at `p` (not wrapped) overlaps none of a third cluster's.
  bool clear_of_others(const Vec3& p, std::size_t m, std::int32_t one, std::int32_t other) const {
    const Vec3 wrapped = grid_.wrap(p);
    const double keep = 1.0 - o_.overlap;
    bool clear = true;
    grid_.around(wrapped, [&](std::int32_t q) {
      const auto qi = static_cast<std::size_t>(q);
      if (!clear || owner_[qi] == one || owner_[qi] == other) return;
      const double contact = keep * (radii_[m] + radii_[qi]) * (1.0 - 1e-9);
      if (grid_.one_image()) {
        clear = grid_.nearest_image(wrapped_[qi] - wrapped).squaredNorm() >= contact * contact;
        return;
      }
      for (int z = -1; z <= 1 && clear; ++z)
        for (int y = -1; y <= 1 && clear; ++y)
          for (int x = -1; x <= 1 && clear; ++x)
            clear = (grid_.nearest_image(wrapped_[qi] - wrapped) + grid_.side() * Vec3(x, y, z)).squaredNorm() >=
                    contact * contact;
    });
    return clear;
  }

  //! Joins the cluster of p (which moved) and that of q, which touch: the smaller's monomers
  //! take the periodic image that touches the larger's.
  void join(std::int32_t moved, std::int32_t p, std::int32_t q) {
    const auto pi = static_cast<std::size_t>(p), qi = static_cast<std::size_t>(q);
    const std::int32_t other = owner_[qi];
    const Vec3 touching = grid_.nearest_image(wrapped_[qi] - wrapped_[pi]);
    // positions_[q] - (positions_[p] + shift) = touching, shift a whole number of box sides.
    Vec3 shift = positions_[qi] - positions_[pi] - touching;
    for (int a = 0; a < 3; ++a) shift[a] = grid_.side() * std::round(shift[a] / grid_.side());
    Group& a = clusters_[static_cast<std::size_t>(moved)];
    Group& b = clusters_[static_cast<std::size_t>(other)];
    const bool keep_moved = a.members.size() >= b.members.size();
    Group& kept = keep_moved ? a : b;
    Group& gone = keep_moved ? b : a;
    const std::int32_t kept_id = keep_moved ? moved : other, gone_id = keep_moved ? other : moved;
    const Vec3 gone_shift = keep_moved ? Vec3(-shift) : shift;
    forget_size(kept.members.size());
    forget_size(gone.members.size());
    for (const std::int32_t m : gone.members) {
      positions_[static_cast<std::size_t>(m)] += gone_shift;
      owner_[static_cast<std::size_t>(m)] = kept_id;
    }
    kept.members.insert(kept.members.end(), gone.members.begin(), gone.members.end());
    if (kept.members.size() > clusters_[static_cast<std::size_t>(largest_)].members.size()) largest_ = kept_id;
    gone.members = {};
    gone.members.shrink_to_fit();
    ++sizes_[kept.members.size()];
    kept.heading = random_direction(rng_, 3);
    kept.flown = 0.0;
    contacts_.emplace_back(p, q);
    stats_.joins.emplace_back(static_cast<double>(kept.members.size()), gyration_of(kept.members, positions_) / o_.monomer_radius);
    left_.take_out(gone_id);
  }

  void forget_size(std::size_t size) {
    const auto it = sizes_.find(size);
    if (--it->second == 0) sizes_.erase(it);
  }

  const AggregateOptions& o_;
  Rng& rng_;
  AggregateStats& stats_;
  std::vector<double> radii_;
  double step_;  //!< how far a cluster moves in one step: a monomer's mean radius
  double largest_radius_;
  PeriodicGrid grid_;
  std::vector<Vec3> positions_;  //!< each monomer where its cluster has carried it (not wrapped)
  std::vector<Vec3> wrapped_;    //!< the same, in the box
  std::vector<std::int32_t> owner_;
  std::vector<Group> clusters_;
  ClustersLeft left_;                           //!< the clusters that move
  std::int32_t largest_ = 0;                    //!< the largest cluster (the first of the largest)
  std::map<std::size_t, std::size_t> sizes_;    //!< how many clusters there are of each size
  std::vector<std::pair<std::int32_t, std::int32_t>> contacts_;
  detail::Crew crew_;
  std::vector<Contact> firsts_;  //!< each run's first contact in a step
};

// ---------------------------------------------------------------------------------------------
// Tuned: clusters joined two at a time, each join placing the second at the distance from the
// first's centre that puts the joined cluster on the law (Filippov, Zurita and Rosner 2000).

//! One cluster of the tuned mode: its monomers (indices), their centroid and R_g.
struct Piece {
  std::vector<std::int32_t> members;
  Vec3 centroid = Vec3::Zero();
  double gyration2 = 0.0;  //!< R_g^2 of the centres
};

void measure(Piece& piece, const std::vector<Vec3>& x) {
  piece.centroid.setZero();
  for (const std::int32_t m : piece.members) piece.centroid += x[static_cast<std::size_t>(m)];
  piece.centroid /= static_cast<double>(piece.members.size());
  piece.gyration2 = 0.0;
  for (const std::int32_t m : piece.members) piece.gyration2 += (x[static_cast<std::size_t>(m)] - piece.centroid).squaredNorm();
  piece.gyration2 /= static_cast<double>(piece.members.size());
}

class TunedAggregation {
 public:
  TunedAggregation(const AggregateOptions& o, std::vector<double> radii, Rng& rng, AggregateStats& stats)
      : o_(o), rng_(rng), stats_(stats), radii_(std::move(radii)), x_(radii_.size(), Vec3::Zero()),
        mean_radius_(o.monomer_radius), largest_radius_(*std::max_element(radii_.begin(), radii_.end())) {}

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) {
    const std::size_t n = radii_.size();
    detail::ModelShell shell(progress, stop);
    std::vector<std::int32_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    for (std::size_t k = n; k > 1; --k) std::swap(order[k - 1], order[static_cast<std::size_t>(rng_() % k)]);
    // Pieces of 16 to 31 monomers grown a monomer at a time, a power of two of them, then joined
    // in pairs of about equal size, as FracVAL does: fast. Compact targets (high df and kf) leave
    // two pieces no room to interlock on the law; then the aggregate is grown a monomer at a
    // time instead, each placed on the law where it fits, which finds room where pieces do not.
    std::size_t pieces = 1;
    while (n / (2 * pieces) >= 16) pieces *= 2;
    std::optional<Piece> whole;
    try {
      whole = hierarchy(order, pieces, shell);
    } catch (const InvalidInput&) {
      if (pieces == 1) throw;
      contacts_.clear();
      stats_.joins.clear();
      whole = hierarchy(order, 1, shell);
    }
    if (!whole) return stopped_;
    // Grown a monomer at a time, the aggregate's last joins may miss the law when its first
    // clusters could not be as dense as it asks; a monomer moved off the law's distance to find
    // room leaves it a little off.
    const double reached = std::sqrt(whole->gyration2) / mean_radius_, law = law_radius(o_, static_cast<double>(n));
    if (n >= 16 && std::abs(reached - law) > 1e-3 * law)
      throw InvalidInput("`df` " + detail::format_number(o_.df) + " and `kf` " + detail::format_number(o_.kf) + ": " +
                         std::to_string(n) + " monomers came to R_g " + detail::format_number(reached) +
                         " a, not the law's " + detail::format_number(law) +
                         " a, as their first clusters cannot pack that densely; a lower df or kf, or more monomers, "
                         "reach it");
    Cluster out = assemble(whole->members, x_, radii_, contacts_, mean_radius_);
    shell.finish(out);
    return out;
  }

 private:
  //! The aggregate from `pieces` pieces of `order`'s monomers, each grown a monomer at a time,
  //! then joined two at a time; empty when stopped (stopped_ then holds what grew). Throws
  //! InvalidInput when two pieces find no placement on the law.
  std::optional<Piece> hierarchy(const std::vector<std::int32_t>& order, std::size_t pieces, detail::ModelShell& shell) {
    const std::size_t n = order.size();
    std::vector<Piece> level;
    for (std::size_t p = 0; p < pieces; ++p) {
      const std::size_t begin = p * n / pieces, end = (p + 1) * n / pieces;
      Piece piece = single(order[begin]);
      OverlapGrid grid(piece.members, x_, radii_, o_.overlap, largest_radius_);
      for (std::size_t k = begin + 1; k < end; ++k) {
        if (!shell.go_on_making([&] { return so_far(level, piece); })) {
          stopped_ = stopped(level, piece);
          return std::nullopt;
        }
        piece = add_monomer(std::move(piece), order[k], grid);
      }
      level.push_back(std::move(piece));
    }
    while (level.size() > 1) {
      std::vector<Piece> next;
      for (std::size_t k = 0; k + 1 < level.size(); k += 2) {
        if (!shell.go_on_making([&] { return so_far(level, level[k]); })) {
          stopped_ = stopped(level, level[k]);
          return std::nullopt;
        }
        next.push_back(join(std::move(level[k]), std::move(level[k + 1])));
      }
      if (level.size() % 2 == 1) next.push_back(std::move(level.back()));
      level = std::move(next);
    }
    return std::move(level[0]);
  }

  Piece single(std::int32_t m) {
    Piece piece;
    piece.members = {m};
    x_[static_cast<std::size_t>(m)].setZero();
    measure(piece, x_);
    return piece;
  }

  Cluster so_far(const std::vector<Piece>& level, const Piece& growing) const {
    const Piece* largest = &growing;
    for (const Piece& p : level)
      if (p.members.size() > largest->members.size()) largest = &p;
    return assemble(largest->members, x_, radii_, contacts_, mean_radius_);
  }
  Cluster stopped(const std::vector<Piece>& level, const Piece& growing) const {
    Cluster out = so_far(level, growing);
    out.complete = false;
    return out;
  }

  double contact(std::int32_t a, std::int32_t b) const {
    return (1.0 - o_.overlap) * (radii_[static_cast<std::size_t>(a)] + radii_[static_cast<std::size_t>(b)]);
  }

  //! The distance between the centroids of A and B that puts the two, joined, on the law
  //! (Filippov et al. 2000); negative when none does (they are too spread out already).
  double law_distance(const Piece& a, const Piece& b) const {
    const double n1 = static_cast<double>(a.members.size()), n2 = static_cast<double>(b.members.size()), n = n1 + n2;
    const double target = mean_radius_ * law_radius(o_, n);
    const double gamma2 = n / (n1 * n2) * (n * target * target - n1 * a.gyration2 - n2 * b.gyration2);
    return gamma2 > 0.0 ? std::sqrt(gamma2) : -1.0;
  }

  //! Monomer m joined to piece A: on the law where it fits, else as near it as it can (a
  //! piece's first monomers are too few for the law to hold). `grid` holds A's monomers, and
  //! m's once it joins.
  Piece add_monomer(Piece a, std::int32_t m, OverlapGrid& grid) {
    const Piece b = single(m);
    const double gamma = std::max(law_distance(a, b), 0.0);
    std::vector<Vec3> placed(1);
    for (int attempt = 0; attempt < 4000; ++attempt) {
      ++stats_.tries;
      if (place_monomer_near_law(a, b, gamma, attempt, grid, placed)) {
        Piece joined = merged(std::move(a), b, placed);
        grid.add(m);
        return joined;
      }
    }
    throw InvalidInput("a monomer found no room beside a cluster of " + std::to_string(a.members.size()));
  }

  //! Piece B joined to piece A so that the two make a cluster on the law, B's monomers moved
  //! and turned. Throws InvalidInput when no placement is found.
  Piece join(Piece a, Piece b) {
    if (a.members.size() < b.members.size()) std::swap(a, b);
    const double gamma = law_distance(a, b);
    const OverlapGrid grid(a.members, x_, radii_, o_.overlap, largest_radius_);
    // Distances of B's monomers from its centroid, sorted, to find those that can reach.
    std::vector<std::pair<double, std::int32_t>> b_reach;
    for (const std::int32_t m : b.members) b_reach.emplace_back((x_[static_cast<std::size_t>(m)] - b.centroid).norm(), m);
    std::sort(b_reach.begin(), b_reach.end());
    std::vector<Vec3> placed(b.members.size());
    constexpr int kTries = 4000;
    if (gamma > 0.0) {
      for (int attempt = 0; attempt < kTries; ++attempt) {
        ++stats_.tries;
        if (place_on_law(a, b, gamma, grid, b_reach, placed)) return merged(std::move(a), std::move(b), placed);
      }
    }
    throw InvalidInput("`df` " + detail::format_number(o_.df) + " and `kf` " + detail::format_number(o_.kf) +
                       ": found no way to join clusters of " + std::to_string(a.members.size()) + " and " +
                       std::to_string(b.members.size()) + " monomers on the law (" +
                       (gamma > 0.0 ? std::to_string(kTries) + " placements tried" : "they are too spread out already") +
                       "); a df nearer 1.8 or a kf nearer 1.3 joins more easily");
  }

  //! One try: a monomer i of A and j of B that can touch with the centroids `gamma` apart, B
  //! turned at random about that contact. Fills `placed` (B's monomers' new places) on success.
  bool place_on_law(const Piece& a, const Piece& b, double gamma, const OverlapGrid& grid,
                    const std::vector<std::pair<double, std::int32_t>>& b_reach, std::vector<Vec3>& placed) {
    const std::int32_t i = a.members[static_cast<std::size_t>(rng_() % a.members.size())];
    const Vec3 xi = x_[static_cast<std::size_t>(i)] - a.centroid;
    const double di = xi.norm();
    if (a.members.size() > 1 && di == 0.0) return false;
    // B's monomers j whose distance d_j from B's centroid lets them touch i: the distance rho
    // from i to B's centroid is in [|gamma - d_i|, gamma + d_i] and in [|d_j - s|, d_j + s].
    double largest_r = 0.0;
    for (const std::int32_t m : b.members) largest_r = std::max(largest_r, radii_[static_cast<std::size_t>(m)]);
    const double s_most = (1.0 - o_.overlap) * (radii_[static_cast<std::size_t>(i)] + largest_r);
    const double near = std::abs(gamma - di), far = gamma + di;
    const auto first = std::lower_bound(b_reach.begin(), b_reach.end(), std::make_pair(near - s_most, std::int32_t{-1}));
    const auto last = std::upper_bound(b_reach.begin(), b_reach.end(),
                                       std::make_pair(far + s_most, std::numeric_limits<std::int32_t>::max()));
    if (first >= last) return false;
    const std::int32_t j = (first + static_cast<std::ptrdiff_t>(rng_() % static_cast<std::uint64_t>(last - first)))->second;
    const double dj = (x_[static_cast<std::size_t>(j)] - b.centroid).norm(), s = contact(i, j);
    const double lo = std::max(near, std::abs(dj - s)), hi = std::min(far, dj + s);
    if (lo > hi) return false;
    const double rho = lo + (hi - lo) * rng_.uniform();
    // B's centroid: gamma from A's, rho from i.
    const Vec3 centre = di == 0.0 ? Vec3(gamma * random_direction(rng_, 3))
                                  : on_two_spheres(Vec3::Zero(), xi / di, di, gamma, rho, rng_);
    // j: d_j from B's centroid, s from i.
    const Vec3 xj = dj == 0.0 ? centre : on_two_spheres(centre, (xi - centre) / rho, rho, dj, s, rng_);
    const Vec3 from = x_[static_cast<std::size_t>(j)] - b.centroid;
    const Eigen::Matrix3d turn = dj == 0.0 ? random_rotation(rng_)
                                           : rotation(from / dj, (xj - centre) / dj, 2.0 * M_PI * rng_.uniform());
    for (std::size_t k = 0; k < b.members.size(); ++k) {
      const std::int32_t m = b.members[k];
      placed[k] = a.centroid + centre + turn * (x_[static_cast<std::size_t>(m)] - b.centroid);
      if (!grid.clear(placed[k], radii_[static_cast<std::size_t>(m)], m == j ? i : -1)) return false;
    }
    touch_ = {i, j};
    return true;
  }

  //! One try to join monomer B to piece A with its centre `gamma` from A's centroid: of 64
  //! monomers i of A drawn, the one whose touching places come nearest that distance (d_i - s
  //! to d_i + s from the centroid), B placed on the circle of them at the distance nearest
  //! `gamma`, at a random angle; after `attempt` tries that overlapped, that distance moves
  //! at random by up to attempt / 100 contacts, as the nearest may have no room, and after 200
  //! any monomer of A and any distance will do. Fills `placed` on success.
  bool place_monomer_near_law(const Piece& a, const Piece& b, double gamma, int attempt, const OverlapGrid& grid,
                              std::vector<Vec3>& placed) {
    const std::int32_t m = b.members[0];
    std::int32_t best = -1;
    double best_gap = std::numeric_limits<double>::infinity(), best_distance = 0.0;
    for (int draw = 0; draw < 64 && best_gap > 0.0; ++draw) {
      const std::int32_t i = a.members[static_cast<std::size_t>(rng_() % a.members.size())];
      const double di = (x_[static_cast<std::size_t>(i)] - a.centroid).norm(), s = contact(i, m);
      const double distance = std::clamp(gamma, std::abs(di - s), di + s);
      if (std::abs(distance - gamma) < best_gap) {
        best_gap = std::abs(distance - gamma);
        best = i;
        best_distance = distance;
      }
    }
    if (attempt >= 200) best = a.members[static_cast<std::size_t>(rng_() % a.members.size())];  // anywhere with room
    const Vec3 xi = x_[static_cast<std::size_t>(best)] - a.centroid;
    const double di = xi.norm(), s = contact(best, m);
    if (attempt >= 200) best_distance = std::abs(di - s) + (di + s - std::abs(di - s)) * rng_.uniform();
    else if (attempt > 0)
      best_distance = std::clamp(best_distance + attempt / 100.0 * s * (2.0 * rng_.uniform() - 1.0), std::abs(di - s), di + s);
    // On the sphere of `best_distance` about the centroid and of s about monomer i.
    const Vec3 at = di == 0.0 ? Vec3(s * random_direction(rng_, 3))
                              : on_two_spheres(Vec3::Zero(), xi / di, di, best_distance, s, rng_);
    placed[0] = a.centroid + at;
    if (!grid.clear(placed[0], radii_[static_cast<std::size_t>(m)], best)) return false;
    touch_ = {best, m};
    return true;
  }

  Piece merged(Piece a, Piece b, const std::vector<Vec3>& placed) {
    for (std::size_t k = 0; k < b.members.size(); ++k) x_[static_cast<std::size_t>(b.members[k])] = placed[k];
    a.members.insert(a.members.end(), b.members.begin(), b.members.end());
    contacts_.push_back(touch_);
    measure(a, x_);
    stats_.joins.emplace_back(static_cast<double>(a.members.size()), std::sqrt(a.gyration2) / mean_radius_);
    return a;
  }

  const AggregateOptions& o_;
  Rng& rng_;
  AggregateStats& stats_;
  std::vector<double> radii_;
  std::vector<Vec3> x_;
  double mean_radius_;  //!< a, in the law
  double largest_radius_;
  std::pair<std::int32_t, std::int32_t> touch_{-1, -1};
  std::vector<std::pair<std::int32_t, std::int32_t>> contacts_;
  Cluster stopped_;  //!< what grew, when growth was stopped
};

// ---------------------------------------------------------------------------------------------
// rlca at stick_probability 0, the reaction-limited limit: no box. A contact sticks so rarely
// that clusters meet every other cluster many times before one sticks, so which two join is set
// by how many ways they can bond, not by how fast they meet: a pair joins as often as N_i + N_j
// (the sum kernel; a random monomer's cluster, then any other), at a contact drawn at random over
// all the ways the two can touch.

//! The monomers of one cluster of the kinetic limit, in its own frame.
struct Flock {
  std::vector<std::int32_t> members;
  Vec3 sum = Vec3::Zero();  //!< of the members' positions: the centroid and R_g as it grows
  double sum2 = 0.0;        //!< of their squared norms
  std::unique_ptr<OverlapGrid> grid;  //!< the members binned, once the flock is large

  Vec3 centroid() const { return sum / static_cast<double>(members.size()); }
  double gyration() const {
    const double n = static_cast<double>(members.size());
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n).squaredNorm()));
  }
};

class KineticAggregation {
 public:
  KineticAggregation(const AggregateOptions& o, std::vector<double> radii, Rng& rng, AggregateStats& stats)
      : o_(o), rng_(rng), stats_(stats), radii_(std::move(radii)), keep_(1.0 - o.overlap),
        largest_radius_(*std::max_element(radii_.begin(), radii_.end())), x_(radii_.size(), Vec3::Zero()),
        owner_(radii_.size()), flocks_(radii_.size()), left_(radii_.size()) {
    for (std::size_t m = 0; m < radii_.size(); ++m) {
      const auto id = static_cast<std::int32_t>(m);
      owner_[m] = id;
      flocks_[m].members = {id};
    }
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) {
    const auto step = [&] {
      // A monomer at random picks its flock as often as its size; any other flock joins it.
      const std::int32_t a = owner_[static_cast<std::size_t>(rng_() % radii_.size())];
      std::int32_t b = a;
      while (b == a) b = left_.draw(rng_);
      join(a, b);
    };
    return join_until_one(left_, progress, stop, 64, step, [&] { return largest_so_far(); });
  }

 private:
  //! Flocks this large keep their monomers binned; smaller ones are looked through whole.
  static constexpr std::size_t kBinnedFrom = 48;
  //! Random contacts drawn before two flocks are brought together along a random line instead:
  //! two large, open flocks rarely find room at a random contact.
  static constexpr int kContactDraws = 500;

  Cluster largest_so_far() const {
    return assemble(flocks_[static_cast<std::size_t>(largest_)].members, x_, radii_, contacts_, o_.monomer_radius);
  }

  double contact(std::size_t p, std::size_t q) const { return keep_ * (radii_[p] + radii_[q]); }

  //! Whether a monomer of radius r at p overlaps none of `flock`'s monomers but `touching`.
  bool clear_of(const Flock& flock, const Vec3& p, double r, std::int32_t touching) const {
    if (flock.grid) return flock.grid->clear(p, r, touching);
    for (const std::int32_t q : flock.members) {
      if (q == touching) continue;
      const double c = keep_ * (r + radii_[static_cast<std::size_t>(q)]) * (1.0 - 1e-9);
      if ((x_[static_cast<std::size_t>(q)] - p).squaredNorm() < c * c) return false;
    }
    return true;
  }

  //! The smaller of flocks a and b placed touching the larger, its monomers moved into the
  //! larger's frame, and the two made one.
  void join(std::int32_t a, std::int32_t b) {
    if (flocks_[static_cast<std::size_t>(a)].members.size() < flocks_[static_cast<std::size_t>(b)].members.size())
      std::swap(a, b);
    const Flock& big = flocks_[static_cast<std::size_t>(a)];
    const Flock& small = flocks_[static_cast<std::size_t>(b)];
    placed_.resize(small.members.size());
    if (!at_random_contact(big, small)) along_a_line(big, small);
    merge(a, b);
  }

  //! One of kContactDraws draws: a monomer i of the small flock touching a monomer j of the big
  //! one from a random direction, the small flock turned at random about i. Fills placed_ and
  //! touch_ when one overlaps nothing.
  bool at_random_contact(const Flock& big, const Flock& small) {
    for (int draw = 0; draw < kContactDraws; ++draw) {
      ++stats_.tries;
      const Eigen::Matrix3d turn = random_rotation(rng_);
      const std::int32_t i = small.members[static_cast<std::size_t>(rng_() % small.members.size())];
      const std::int32_t j = big.members[static_cast<std::size_t>(rng_() % big.members.size())];
      const auto ii = static_cast<std::size_t>(i), ji = static_cast<std::size_t>(j);
      const Vec3 at = x_[ji] + contact(ii, ji) * random_direction(rng_, 3);
      bool clear = clear_of(big, at, radii_[ii], j);
      for (std::size_t k = 0; k < small.members.size() && clear; ++k) {
        const auto m = static_cast<std::size_t>(small.members[k]);
        placed_[k] = at + turn * (x_[m] - x_[ii]);
        clear = m == ii || clear_of(big, placed_[k], radii_[m], -1);
      }
      if (!clear) continue;
      touch_ = {i, j};
      return true;
    }
    return false;
  }

  //! The small flock, turned at random, brought from afar along a random line at a random offset
  //! until it first touches the big one: the contact is exact, found through the big flock's
  //! monomers binned across the line.
  void along_a_line(const Flock& big, const Flock& small) {
    const Vec3 big_centre = big.centroid(), small_centre = small.centroid();
    double big_reach = 0.0, small_reach = 0.0;
    for (const std::int32_t q : big.members)
      big_reach = std::max(big_reach, (x_[static_cast<std::size_t>(q)] - big_centre).norm() + largest_radius_);
    for (const std::int32_t p : small.members)
      small_reach = std::max(small_reach, (x_[static_cast<std::size_t>(p)] - small_centre).norm() + largest_radius_);
    const double width = 2.0 * keep_ * largest_radius_;
    ++stats_.approaches;
    while (true) {
      ++stats_.tries;
      const Eigen::Matrix3d turn = random_rotation(rng_);
      const Vec3 u = random_direction(rng_, 3);
      const Vec3 e1 = perpendicular(u, 0.0), e2 = u.cross(e1);
      const double offset = (big_reach + small_reach) * std::sqrt(rng_.uniform());
      const Vec3 start = big_centre - 2.0 * (big_reach + small_reach) * u + offset * perpendicular(u, 2.0 * M_PI * rng_.uniform());
      // The big flock's monomers binned by where they lie across the line.
      std::unordered_map<std::uint64_t, std::vector<std::int32_t>> across;
      const auto cell = [&](const Vec3& p) {
        return std::array<std::int64_t, 2>{static_cast<std::int64_t>(std::floor(p.dot(e1) / width)),
                                           static_cast<std::int64_t>(std::floor(p.dot(e2) / width))};
      };
      const auto key = [](std::int64_t s, std::int64_t t) {
        return static_cast<std::uint64_t>(s + (1LL << 31)) << 32 | static_cast<std::uint64_t>(t + (1LL << 31));
      };
      for (const std::int32_t q : big.members) {
        const auto c = cell(x_[static_cast<std::size_t>(q)]);
        across[key(c[0], c[1])].push_back(q);
      }
      double first = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < small.members.size(); ++k) {
        const auto p = static_cast<std::size_t>(small.members[k]);
        placed_[k] = start + turn * (x_[p] - small_centre);
        const auto c = cell(placed_[k]);
        for (std::int64_t s = c[0] - 1; s <= c[0] + 1; ++s)
          for (std::int64_t t = c[1] - 1; t <= c[1] + 1; ++t) {
            const auto found = across.find(key(s, t));
            if (found == across.end()) continue;
            for (const std::int32_t q : found->second) {
              const Vec3 gap = x_[static_cast<std::size_t>(q)] - placed_[k];
              const double along = gap.dot(u), reach2 = contact(p, static_cast<std::size_t>(q)) * contact(p, static_cast<std::size_t>(q));
              const double off2 = gap.squaredNorm() - along * along;
              if (off2 >= reach2) continue;
              const double at = along - std::sqrt(reach2 - off2);
              if (at < first) {
                first = at;
                touch_ = {small.members[k], q};
              }
            }
          }
      }
      if (first == std::numeric_limits<double>::infinity()) continue;  // the line missed
      for (Vec3& p : placed_) p += first * u;
      return;
    }
  }

  //! Flock b, at placed_, made part of flock a, touching it at touch_.
  void merge(std::int32_t a, std::int32_t b) {
    Flock& big = flocks_[static_cast<std::size_t>(a)];
    Flock& small = flocks_[static_cast<std::size_t>(b)];
    for (std::size_t k = 0; k < small.members.size(); ++k) {
      const auto m = static_cast<std::size_t>(small.members[k]);
      x_[m] = placed_[k];
      owner_[m] = a;
      big.sum += x_[m];
      big.sum2 += x_[m].squaredNorm();
      if (big.grid) big.grid->add(small.members[k]);
    }
    big.members.insert(big.members.end(), small.members.begin(), small.members.end());
    if (!big.grid && big.members.size() >= kBinnedFrom)
      big.grid = std::make_unique<OverlapGrid>(big.members, x_, radii_, o_.overlap, largest_radius_);
    small = Flock{};
    if (big.members.size() > flocks_[static_cast<std::size_t>(largest_)].members.size()) largest_ = a;
    contacts_.push_back(touch_);
    stats_.joins.emplace_back(static_cast<double>(big.members.size()), big.gyration() / o_.monomer_radius);
    left_.take_out(b);
  }

  const AggregateOptions& o_;
  Rng& rng_;
  AggregateStats& stats_;
  std::vector<double> radii_;
  double keep_;
  double largest_radius_;
  std::vector<Vec3> x_;  //!< each monomer in its flock's frame
  std::vector<std::int32_t> owner_;
  std::vector<Flock> flocks_;
  ClustersLeft left_;  //!< the flocks left
  std::int32_t largest_ = 0;
  std::vector<Vec3> placed_;  //!< the small flock's monomers where a join puts them
  std::pair<std::int32_t, std::int32_t> touch_{-1, -1};
  std::vector<std::pair<std::int32_t, std::int32_t>> contacts_;
};

}  // namespace

Cluster aggregate(const AggregateOptions& options, const ProgressFn& progress, const StopFlag* stop,
                  AggregateStats* stats) {
  validate(options);
  AggregateStats counted;
  AggregateStats& s = stats ? *stats : counted;
  Rng rng(options.rng_seed);
  std::vector<double> radii = monomer_radii(options, rng);
  if (options.mode == AggregateMode::tuned) return TunedAggregation(options, std::move(radii), rng, s).grow(progress, stop);
  if (reaction_limited(options)) return KineticAggregation(options, std::move(radii), rng, s).grow(progress, stop);
  BoxAggregation box(options, std::move(radii), rng, s);
  return box.grow(progress, stop);
}

}  // namespace dla
