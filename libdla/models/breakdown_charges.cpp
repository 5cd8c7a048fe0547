// The breakdown model's charges field (breakdown_charges.h): equal point charges at the
// particles, their potential summed at candidate sites and kept as each particle attaches.

#include "models/breakdown_charges.h"

#include "dla/core/particle_feed.h"
#include "dla/core/random.h"
#include "dla/index/grid_index.h"
#include "dla/models/electrode.h"
#include "dla/models/model_shell.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace dla::detail {

namespace {

// GCC builds the two hot loops for AVX2 and for any x86-64 and picks one as the program starts.
// Neither contracts a multiply and an add (AVX2 alone has no FMA), and each float is the result
// of the same correctly rounded operations, so both give the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define DLA_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DLA_VECTOR_CLONES
#endif

constexpr int kLanes = 8;
constexpr float kFar = 1e18f;  // where padding sites sit, closed: every charge is far from them

//! ln x for a positive finite float, within about 1e-7, by arithmetic and bit moves alone: the
//! same on every machine and vector width, where a library's log need not be.
inline float log_of(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const float exponent = static_cast<float>(static_cast<std::int32_t>(bits >> 23) - 127);
  bits = (bits & 0x007fffffu) | 0x3f800000u;
  float m;  // in [1, 2)
  std::memcpy(&m, &bits, sizeof m);
  // ln m = 2 atanh t, t = (m - 1) / (m + 1) in [0, 1/3): its series to t^11.
  const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  const float series =
      t * (2.0f + t2 * (2.0f / 3.0f + t2 * (2.0f / 5.0f + t2 * (2.0f / 7.0f + t2 * (2.0f / 9.0f + t2 * (2.0f / 11.0f))))));
  return exponent * 0.6931471805599453f + series;
}

//! A unit charge's potential at squared distance r2 (in spacings): 1/r in 3D, -ln r in 2D.
template <bool kPlanar>
inline float potential(float r2) {
  if constexpr (kPlanar) return -0.5f * log_of(r2);
  else return 1.0f / std::sqrt(r2);
}

struct Point {
  float x, y, z;
};

struct Bound {
  float low, high, open;
};

//! p's image across the plane where `axis` (0, 1, 2; else none) is `at`.
inline Point mirrored(Point p, int axis, float at) {
  if (axis == 0) p.x = 2.0f * at - p.x;
  if (axis == 1) p.y = 2.0f * at - p.y;
  if (axis == 2) p.z = 2.0f * at - p.z;
  return p;
}

struct Sites {
  float* sum;
  float* open;
  const float *x, *y, *z, *target;
};

//! Adds the charge at q, less its image at m, to `count` sites, and closes those nearer q than
//! sqrt(close2). One branch-free loop a kind, so that it runs in vectors.
template <bool kPlanar, bool kMirrored>
inline void add_charge_to(const Sites& s, std::size_t count, Point q, Point m, float close2) {
  float* __restrict sum = s.sum;
  float* __restrict open = s.open;
  const float* __restrict x = s.x;
  const float* __restrict y = s.y;
  const float* __restrict z = s.z;
  for (std::size_t k = 0; k < count; ++k) {
    const float dx = x[k] - q.x, dy = y[k] - q.y, dz = z[k] - q.z;
    const float r2 = dx * dx + dy * dy + dz * dz;
    float g = potential<kPlanar>(r2);
    if constexpr (kMirrored) {
      const float mx = x[k] - m.x, my = y[k] - m.y, mz = z[k] - m.z;
      g -= potential<kPlanar>(mx * mx + my * my + mz * mz);
    }
    sum[k] += g;
    open[k] = r2 >= close2 ? open[k] : 0.0f;
  }
}

//! add_charge_to() for `count` sites (a multiple of kLanes), then the least and greatest U =
//! sum - n_target * target over the open ones, and how many are open.
DLA_VECTOR_CLONES
Bound add_to_block(const Sites& s, std::size_t count, Point q, const Point* mirror, bool planar, float n_target,
                   float close2) {
  const Point m = mirror ? *mirror : q;
  if (planar) {
    if (mirror) add_charge_to<true, true>(s, count, q, m, close2);
    else add_charge_to<true, false>(s, count, q, m, close2);
  } else {
    if (mirror) add_charge_to<false, true>(s, count, q, m, close2);
    else add_charge_to<false, false>(s, count, q, m, close2);
  }
  float low[kLanes], high[kLanes], opened[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    low[l] = std::numeric_limits<float>::infinity();
    high[l] = -std::numeric_limits<float>::infinity();
    opened[l] = 0.0f;
  }
  for (std::size_t i = 0; i < count; i += kLanes)
    for (int l = 0; l < kLanes; ++l) {
      const std::size_t k = i + static_cast<std::size_t>(l);
      const float o = s.open[k], u = s.sum[k] - n_target * s.target[k];
      const float shut = o != 0.0f ? 0.0f : std::numeric_limits<float>::infinity();
      low[l] = std::min(low[l], u + shut);
      high[l] = std::max(high[l], u - shut);
      opened[l] += o;
    }
  Bound b{low[0], high[0], opened[0]};
  for (int l = 1; l < kLanes; ++l) {
    b.low = std::min(b.low, low[l]);
    b.high = std::max(b.high, high[l]);
    b.open += opened[l];
  }
  return b;
}

//! The potential at c of the `count` charges, in kLanes fixed lanes (charge j in lane j mod
//! kLanes, in order), added up lane by lane: the same sum for any vector width.
template <bool kPlanar>
inline float sum_of(const float* __restrict x, const float* __restrict y, const float* __restrict z, std::size_t count,
                    Point c) {
  float lane[kLanes] = {};
  const std::size_t whole = count - count % kLanes;
  for (std::size_t i = 0; i < whole; i += kLanes)
    for (int l = 0; l < kLanes; ++l) {
      const std::size_t k = i + static_cast<std::size_t>(l);
      const float dx = x[k] - c.x, dy = y[k] - c.y, dz = z[k] - c.z;
      lane[l] += potential<kPlanar>(dx * dx + dy * dy + dz * dz);
    }
  for (std::size_t k = whole; k < count; ++k) {
    const float dx = x[k] - c.x, dy = y[k] - c.y, dz = z[k] - c.z;
    lane[k % kLanes] += potential<kPlanar>(dx * dx + dy * dy + dz * dz);
  }
  float total = 0.0f;
  for (int l = 0; l < kLanes; ++l) total += lane[l];
  return total;
}

DLA_VECTOR_CLONES
float sum_at(const float* x, const float* y, const float* z, std::size_t count, Point c, bool planar) {
  return planar ? sum_of<true>(x, y, z, count, c) : sum_of<false>(x, y, z, count, c);
}

//! Sites nearer a charge than this many spacings (squared) close; the exact test at the draw
//! (grow_by_charges) catches the few the floats' rounding leaves open.
constexpr float kClose2 = (1.0f - 1e-3f) * (1.0f - 1e-3f);

//! Blocks a thread at least before add_charge splits them among the crew.
constexpr std::size_t kBlocksPerThread = 16;

}  // namespace

ChargeField::ChargeField(const Vec3& origin, double spacing, int dimensions, int mirror_axis, double mirror_at)
    : origin_(origin),
      spacing_(spacing),
      dimensions_(dimensions),
      mirror_axis_(mirror_axis),
      mirror_at_(mirror_axis >= 0 ? static_cast<float>((mirror_at - origin[mirror_axis]) / spacing) : 0.0f) {}

void ChargeField::over_blocks(Crew& crew, const std::function<void(std::size_t, std::size_t)>& job) {
  const std::size_t blocks = block_low_.size();
  const std::size_t parts = std::min(crew.size(), std::max<std::size_t>(1, blocks / kBlocksPerThread));
  if (parts == 1) {
    job(0, blocks);
    return;
  }
  crew.run(parts, [&](std::size_t part) { job(blocks * part / parts, blocks * (part + 1) / parts); });
}

void ChargeField::add_charge(const Vec3& p, Crew& crew) {
  const Point q{scaled(p, 0), scaled(p, 1), scaled(p, 2)};
  charge_x_.push_back(q.x);
  charge_y_.push_back(q.y);
  charge_z_.push_back(q.z);
  ++charges_;
  const Point image = mirrored(q, mirror_axis_, mirror_at_);
  const float n_target = target_on_ ? static_cast<float>(charges_) : 0.0f;
  const bool planar = dimensions_ == 2;
  over_blocks(crew, [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b) {
      const std::size_t at = b * kBlock;
      const Sites sites{&sum_[at], &open_[at], &x_[at], &y_[at], &z_[at], &target_[at]};
      const Bound bound = add_to_block(sites, kBlock, q, mirror_axis_ >= 0 ? &image : nullptr, planar, n_target, kClose2);
      block_low_[b] = bound.low;
      block_high_[b] = bound.high;
      block_open_[b] = static_cast<std::uint32_t>(bound.open);
    }
  });
  open_count_ = 0;
  for (const std::uint32_t n : block_open_) open_count_ += n;
}

void ChargeField::push_padding_block() {
  const std::size_t size = x_.size() + kBlock;
  x_.resize(size, kFar);
  y_.resize(size, kFar);
  z_.resize(size, kFar);
  sum_.resize(size, 0.0f);
  target_.resize(size, 0.0f);
  open_.resize(size, 0.0f);
  at_.resize(size, Vec3::Zero());
  parent_.resize(size, -1);
  block_low_.push_back(std::numeric_limits<float>::infinity());
  block_high_.push_back(-std::numeric_limits<float>::infinity());
  block_open_.push_back(0);
}

void ChargeField::bound_blocks(std::size_t first, std::size_t last) {
  for (std::size_t b = first; b < last; ++b) {
    float low = std::numeric_limits<float>::infinity(), high = -low;
    std::uint32_t opened = 0;
    for (std::size_t i = b * kBlock; i < (b + 1) * kBlock; ++i) {
      if (open_[i] == 0.0f) continue;
      low = std::min(low, u(i));
      high = std::max(high, u(i));
      ++opened;
    }
    open_count_ += opened;
    open_count_ -= block_open_[b];
    block_low_[b] = low;
    block_high_[b] = high;
    block_open_[b] = opened;
  }
}

void ChargeField::add_sites(const std::vector<Vec3>& at, std::int32_t parent, const std::vector<double>& target_potential,
                            Crew& crew) {
  const std::size_t first = used_;
  for (std::size_t s = 0; s < at.size(); ++s) {
    if (used_ == x_.size()) push_padding_block();
    const std::size_t i = used_++;
    x_[i] = scaled(at[s], 0);
    y_[i] = scaled(at[s], 1);
    z_[i] = scaled(at[s], 2);
    target_[i] = static_cast<float>(target_potential[s]);
    open_[i] = 1.0f;
    at_[i] = at[s];
    parent_[i] = parent;
  }
  const bool planar = dimensions_ == 2;
  crew.run(at.size(), [&](std::size_t s) {
    const std::size_t i = first + s;
    const Point c{x_[i], y_[i], z_[i]};
    float total = sum_at(charge_x_.data(), charge_y_.data(), charge_z_.data(), charges_, c, planar);
    if (mirror_axis_ >= 0)
      total -= sum_at(charge_x_.data(), charge_y_.data(), charge_z_.data(), charges_, mirrored(c, mirror_axis_, mirror_at_), planar);
    sum_[i] = total;
  });
  if (used_ > first) bound_blocks(first / kBlock, (used_ - 1) / kBlock + 1);
}

void ChargeField::drop_target() {
  target_on_ = false;
  bound_blocks(0, block_open_.size());
}

void ChargeField::close(std::size_t site) {
  open_[site] = 0.0f;
  bound_blocks(site / kBlock, site / kBlock + 1);
}

void ChargeField::compact_if_sparse() {
  const std::size_t closed = used_ - open_count_;
  if (closed <= std::max(open_count_, 4 * kBlock)) return;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < used_; ++i) {
    if (open_[i] == 0.0f) continue;
    x_[kept] = x_[i];
    y_[kept] = y_[i];
    z_[kept] = z_[i];
    sum_[kept] = sum_[i];
    target_[kept] = target_[i];
    open_[kept] = 1.0f;
    at_[kept] = at_[i];
    parent_[kept] = parent_[i];
    ++kept;
  }
  used_ = kept;
  const std::size_t size = (kept + kBlock - 1) / kBlock * kBlock;
  for (std::size_t i = kept; i < x_.size(); ++i) {
    x_[i] = y_[i] = z_[i] = kFar;
    sum_[i] = target_[i] = open_[i] = 0.0f;
    parent_[i] = -1;
  }
  for (std::vector<float>* v : {&x_, &y_, &z_, &sum_, &target_, &open_}) v->resize(size);
  at_.resize(size);
  parent_.resize(size);
  block_low_.resize(size / kBlock);
  block_high_.resize(size / kBlock);
  block_open_.assign(size / kBlock, 0);
  open_count_ = 0;
  bound_blocks(0, size / kBlock);
}

std::ptrdiff_t ChargeField::draw(Rng& rng, double eta) const {
  if (open_count_ == 0) return -1;
  float top = -std::numeric_limits<float>::infinity(), bottom = std::numeric_limits<float>::infinity();
  for (std::size_t b = 0; b < block_open_.size(); ++b) {
    if (block_open_[b] == 0) continue;
    top = std::max(top, block_high_[b]);
    bottom = std::min(bottom, block_low_[b]);
  }
  const double range = static_cast<double>(top) - static_cast<double>(bottom);
  const auto weight = [&](float u) {
    return range > 0.0 ? std::pow((static_cast<double>(top) - static_cast<double>(u)) / range, eta) : 1.0;
  };
  // A block's bound is its most exposed site's weight: every site in it weighs no more.
  std::vector<double> cumulative(block_open_.size());
  double total = 0.0;
  for (std::size_t b = 0; b < block_open_.size(); ++b) {
    if (block_open_[b] != 0) total += weight(block_low_[b]);
    cumulative[b] = total;
  }
  // At most kBlock tries on average (a block's bound is at most its weight); past many more,
  // something in the floats is amiss, and a plain draw over every open site stands in.
  constexpr int kMaxTries = 1 << 20;
  for (int tries = 0; tries < kMaxTries; ++tries) {
    const double pick = rng.uniform() * total;
    const std::size_t b = static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), pick) -
                                                   cumulative.begin());
    if (b >= cumulative.size()) continue;
    const std::size_t i = b * kBlock + std::min(kBlock - 1, static_cast<std::size_t>(rng.uniform() * kBlock));
    const double u = rng.uniform();
    if (open_[i] == 0.0f) continue;
    if (u * weight(block_low_[b]) < weight(this->u(i))) return static_cast<std::ptrdiff_t>(i);
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < used_; ++i)
    if (open_[i] != 0.0f) sum += weight(this->u(i));
  double pick = rng.uniform() * sum;
  std::ptrdiff_t last = -1;
  for (std::size_t i = 0; i < used_; ++i) {
    if (open_[i] == 0.0f) continue;
    last = static_cast<std::ptrdiff_t>(i);
    pick -= weight(this->u(i));
    if (pick < 0.0) break;
  }
  return last;
}

namespace {

//! Sites a particle opens at most.
constexpr int kSitesPerParticle = 6;
//! Points a target mesh's charge is spread over, uniformly by area.
constexpr int kTargetMeshCharges = 512;

//! The six directions of a random frame: the axes of a uniform rotation both ways in 3D, a
//! hexagon's at a uniform turn in 2D.
std::vector<Vec3> site_frame(Rng& rng, int dimensions) {
  constexpr double two_pi = 6.283185307179586;
  std::vector<Vec3> directions;
  if (dimensions == 2) {
    const double turn = two_pi * rng.uniform();
    for (int i = 0; i < kSitesPerParticle; ++i) {
      const double angle = turn + two_pi * i / kSitesPerParticle;
      directions.emplace_back(std::cos(angle), std::sin(angle), 0.0);
    }
    return directions;
  }
  // A uniform rotation (Shoemake's quaternion from three uniform numbers); its axes both ways.
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond(b * std::cos(two_pi * u3), a * std::sin(two_pi * u2), a * std::cos(two_pi * u2),
                         b * std::sin(two_pi * u3))
          .toRotationMatrix();
  for (int axis = 0; axis < 3; ++axis) {
    directions.push_back(turn.col(axis));
    directions.push_back(-turn.col(axis));
  }
  return directions;
}

}  // namespace

std::vector<Vec3> target_charge_points(const Target& target, std::uint64_t rng_seed) {
  std::vector<Vec3> points;
  if (target.kind == TargetKind::point) points.push_back(target.point);
  if (target.kind == TargetKind::mesh) {
    Rng rng(rng_seed, kTargetStreams);
    for (int i = 0; i < kTargetMeshCharges; ++i) points.push_back(target.mesh->draw_near_surface(rng));
  }
  return points;
}

bool free_at(const GridIndex& index, const Vec3& c, std::int32_t parent, double spacing) {
  bool free = true;
  index.for_each_within(c, spacing * (1.0 - 1e-9), [&](std::int32_t id, double) {
    if (id != parent) free = false;
  });
  return free;
}

void sites_beside(std::int32_t id, const Vec3& from, const DlaOptions& walk, const MeshConstraint* constraint,
                  const GridIndex& index, std::vector<Vec3>& out) {
  Rng rng(walk.rng_seed, kFrameStreams + static_cast<std::uint64_t>(id));
  out.clear();
  for (const Vec3& direction : site_frame(rng, walk.dimensions)) {
    Vec3 at = from + walk.spacing * direction;
    if (constraint) {
      const BranchCheck check = constraint->check_branch(from, at);
      if (!check.accepted) continue;
      at = check.end;
    }
    if (free_at(index, at, id, walk.spacing)) out.push_back(at);
  }
}

void grow_until_done(Cluster& cluster, const DlaOptions& walk, const BreakdownOptions& options,
                     const Electrode* electrode, const ProgressFn& progress, const StopFlag* stop,
                     BreakdownStats& stats, const std::function<void()>& seed,
                     const std::function<void(std::size_t)>& attach, const std::function<void()>& point_struck) {
  ModelShell shell(progress, stop);
  const auto finish_stats = [&] {
    stats.strike = cluster.strike;
    stats.channel = channel_length(cluster);
  };
  try {
    seed();
    for (std::size_t k = 0; k < walk.particles; ++k) {
      attach(k);
      const Vec3& p = cluster.particles.back().position;
      if (electrode && cluster.strike < 0 && electrode->distance(p) <= walk.spacing) {
        cluster.strike = static_cast<std::int32_t>(cluster.particles.size() - 1);
        if (options.stop_at_strike) break;
        // A ball touched is at the structure's potential: its charge is gone.
        if (options.target.kind == TargetKind::point) point_struck();
      }
      if (k + 1 < walk.particles && !shell.go_on(cluster)) {
        cluster.complete = false;
        break;
      }
    }
  } catch (...) {
    finish_stats();
    ModelShell::keep_what_grew(cluster);
  }
  finish_stats();
  shell.finish(cluster);
}

namespace {

class ChargeDischarge {
 public:
  ChargeDischarge(const DlaOptions& walk, const BreakdownOptions& o, const MeshConstraint* constraint, const StopFlag* stop,
                  BreakdownStats& stats)
      : walk_(walk),
        options_(o),
        constraint_(constraint),
        stop_(stop),
        stats_(stats),
        cluster_(seeded(walk.seeds, walk.spacing, walk.dimensions)),
        index_(cluster_.particles, walk.spacing, walk.dimensions, false),
        field_(cluster_.center, walk.spacing, walk.dimensions,
               o.target.kind == TargetKind::plane ? static_cast<int>(o.target.axis) : -1, o.target.at),
        crew_(walk.threads) {
    if (o.target.kind != TargetKind::none) electrode_.emplace(o.target, cluster_.center, walk.spacing, walk.dimensions);
    target_charges_ = target_charge_points(o.target, walk.rng_seed);
    cluster_.particles.reserve(cluster_.particles.size() + walk.particles);
    index_.reserve(cluster_.particles.capacity());
  }

  Cluster run(const ProgressFn& progress) {
    const auto seed = [&] {
      // Every seed's charge first, so that each seed's sites sum them all.
      for (std::size_t i = 0; i < cluster_.particles.size(); ++i) charge(static_cast<std::int32_t>(i));
      for (std::size_t i = 0; i < cluster_.particles.size(); ++i) open_sites(static_cast<std::int32_t>(i));
    };
    grow_until_done(cluster_, walk_, options_, electrode_ ? &*electrode_ : nullptr, progress, stop_, stats_, seed,
                    [&](std::size_t k) { attach(k); }, [&] { field_.drop_target(); });
    return std::move(cluster_);
  }

 private:
  //! Particle k, drawn among the open sites by weight; a site the floats left open but that
  //! lies within a spacing of another particle closes, and the draw goes again.
  void attach(std::size_t k) {
    Rng rng(walk_.rng_seed, kChoiceStreams + k);
    stats_.sites += field_.open_sites();
    for (;;) {
      const std::ptrdiff_t site = field_.draw(rng, options_.eta);
      if (site < 0)
        throw GrowthError("no free site is left next to the structure after " + std::to_string(k) +
                          " particles: the mesh holds no more");
      const std::size_t s = static_cast<std::size_t>(site);
      if (!free_at(index_, field_.at(s), field_.parent(s), walk_.spacing)) {
        field_.close(s);
        continue;
      }
      const std::int32_t parent = field_.parent(s);
      cluster_.particles.push_back({field_.at(s), parent, cluster_.particles[static_cast<std::size_t>(parent)].seed});
      break;
    }
    const std::int32_t id = static_cast<std::int32_t>(cluster_.particles.size() - 1);
    charge(id);
    open_sites(id);
    field_.compact_if_sparse();
  }

  //! Particle id is in the structure: the index, the feed, the electrode and the field know it.
  void charge(std::int32_t id) {
    const Particle& p = cluster_.particles[static_cast<std::size_t>(id)];
    index_.insert(id);
    if (stats_.feed) stats_.feed->put(p);
    if (electrode_) electrode_->grown(p.position);
    field_.add_charge(p.position, crew_);
  }

  //! The sites beside particle id, each with the target's potential there.
  void open_sites(std::int32_t id) {
    sites_beside(id, cluster_.particles[static_cast<std::size_t>(id)].position, walk_, constraint_, index_, sites_);
    potentials_.clear();
    for (const Vec3& at : sites_) potentials_.push_back(target_potential(at));
    field_.add_sites(sites_, id, potentials_, crew_);
  }

  //! The target's potential at c per unit of its charge, spread over its points; 0 for a plane
  //! (its images are in the sums) and without a target.
  double target_potential(const Vec3& c) const {
    if (target_charges_.empty()) return 0.0;
    double total = 0.0;
    for (const Vec3& t : target_charges_) {
      const double r = std::max((c - t).norm() / walk_.spacing, 0.5);
      total += walk_.dimensions == 2 ? -std::log(r) : 1.0 / r;
    }
    return total / static_cast<double>(target_charges_.size());
  }

  const DlaOptions& walk_;
  const BreakdownOptions& options_;
  const MeshConstraint* constraint_;
  const StopFlag* stop_;
  BreakdownStats& stats_;
  Cluster cluster_;
  GridIndex index_;
  std::optional<Electrode> electrode_;
  std::vector<Vec3> target_charges_;  // a point's or a mesh's charge, spread evenly over them
  ChargeField field_;
  Crew crew_;
  std::vector<Vec3> sites_;         // open_sites()'s, kept between particles
  std::vector<double> potentials_;  // likewise
};

}  // namespace

Cluster grow_by_charges(const DlaOptions& walk, const BreakdownOptions& options, const MeshConstraint* constraint,
                        const ProgressFn& progress, const StopFlag* stop, BreakdownStats& stats) {
  return ChargeDischarge(walk, options, constraint, stop, stats).run(progress);
}

}  // namespace dla::detail
