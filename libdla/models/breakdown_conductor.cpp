// The breakdown model's conductor field (breakdown_conductor.h): the charges that hold the
// structure at one potential, kept by local relaxation and conjugate-gradient solves over a
// Barnes-Hut tree.

#include "models/breakdown_conductor.h"

#include "dla/core/particle_feed.h"
#include "dla/core/random.h"
#include "dla/index/grid_index.h"
#include "dla/models/electrode.h"
#include "dla/models/model_shell.h"

#include "models/breakdown_charges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace dla::detail {

namespace {

constexpr int kBucket = 8;           // points a leaf holds before it splits
constexpr int kMaxDepth = 48;        // below this, a leaf holds any number (coincident seeds)
constexpr double kFarRadius = 1e6;  // 2D: the far circle at u = 0, in spacings

//! G at r spacings: ln(R/r) in 2D, 1/r in 3D.
template <bool kPlanar>
double green(double r, double far_log) {
  if constexpr (kPlanar) return far_log - std::log(r);
  else return 1.0 / r;
}

}  // namespace

ChargeTree::ChargeTree(int dimensions, double theta)
    : dimensions_(dimensions), theta2_(theta * theta), far_log_(std::log(kFarRadius)) {}

double ChargeTree::kernel(double r, double near) const {
  r = std::max(r, near);
  return dimensions_ == 2 ? green<true>(r, far_log_) : green<false>(r, far_log_);
}

void ChargeTree::Node::add_point(const Vec3& p, double q) {
  ++count;
  total += q;
  moment += q * p;
  point_sum += p;
  focus = point_sum / count;
}

std::int32_t ChargeTree::new_node(const Vec3& centre, double half, std::int32_t depth) {
  Node node;
  node.centre = node.focus = centre;
  node.half = half;
  node.depth = depth;
  std::fill(std::begin(node.child), std::end(node.child), -1);
  nodes_.push_back(node);
  return static_cast<std::int32_t>(nodes_.size() - 1);
}

int ChargeTree::octant(const Node& node, const Vec3& p) const {
  int o = 0;
  for (int a = 0; a < dimensions_; ++a)
    if (p[a] >= node.centre[a]) o |= 1 << a;
  return o;
}

void ChargeTree::split(std::int32_t at) {
  std::int32_t point = nodes_[static_cast<std::size_t>(at)].first;
  nodes_[static_cast<std::size_t>(at)].first = -1;
  nodes_[static_cast<std::size_t>(at)].leaf = false;
  while (point >= 0) {
    Point& moved = points_[static_cast<std::size_t>(point)];
    const std::int32_t following = moved.next;
    const int o = octant(nodes_[static_cast<std::size_t>(at)], moved.at);
    if (nodes_[static_cast<std::size_t>(at)].child[o] < 0) {
      const Node& parent = nodes_[static_cast<std::size_t>(at)];
      Vec3 centre = parent.centre;
      for (int a = 0; a < dimensions_; ++a) centre[a] += (o >> a & 1 ? 0.5 : -0.5) * parent.half;
      const std::int32_t child = new_node(centre, 0.5 * parent.half, parent.depth + 1);
      nodes_[static_cast<std::size_t>(at)].child[o] = child;
    }
    Node& child = nodes_[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(at)].child[o])];
    moved.next = child.first;
    child.first = point;
    child.add_point(moved.at, moved.q);
    point = following;
  }
  for (int o = 0; o < 8; ++o) {
    const std::int32_t child = nodes_[static_cast<std::size_t>(at)].child[o];
    if (child >= 0 && nodes_[static_cast<std::size_t>(child)].count > kBucket &&
        nodes_[static_cast<std::size_t>(child)].depth < kMaxDepth)
      split(child);
  }
}

void ChargeTree::insert(const Vec3& p, double q) {
  packed_ = false;
  const std::int32_t id = static_cast<std::int32_t>(points_.size());
  points_.push_back({p, q, -1});
  if (root_ < 0) root_ = new_node(p, 8.0, 0);
  // Outside the root: a root twice as wide, the old one its child, until p is inside.
  const auto outside = [&] {
    const Node& root = nodes_[static_cast<std::size_t>(root_)];
    for (int a = 0; a < dimensions_; ++a)
      if (std::abs(p[a] - root.centre[a]) > root.half) return true;
    return false;
  };
  while (outside()) {
    const Node old = nodes_[static_cast<std::size_t>(root_)];
    Vec3 centre = old.centre;
    for (int a = 0; a < dimensions_; ++a) centre[a] += p[a] >= old.centre[a] ? old.half : -old.half;
    // Depths count from the root: everything there is goes a level deeper.
    for (Node& node : nodes_) ++node.depth;
    const std::int32_t root = new_node(centre, 2.0 * old.half, 0);
    Node& grown = nodes_[static_cast<std::size_t>(root)];
    grown.child[octant(grown, old.centre)] = root_;
    grown.leaf = false;
    grown.count = old.count;
    grown.total = old.total;
    grown.moment = old.moment;
    grown.point_sum = old.point_sum;
    grown.focus = old.focus;
    root_ = root;
  }
  std::int32_t at = root_;
  for (;;) {
    Node& node = nodes_[static_cast<std::size_t>(at)];
    node.add_point(p, q);
    if (node.leaf) {
      points_[static_cast<std::size_t>(id)].next = node.first;
      node.first = id;
      if (node.count > kBucket && node.depth < kMaxDepth) split(at);
      return;
    }
    const int o = octant(node, p);
    if (node.child[o] < 0) {
      Vec3 centre = node.centre;
      for (int a = 0; a < dimensions_; ++a) centre[a] += (o >> a & 1 ? 0.5 : -0.5) * node.half;
      const std::int32_t child = new_node(centre, 0.5 * node.half, node.depth + 1);
      nodes_[static_cast<std::size_t>(at)].child[o] = child;
    }
    at = nodes_[static_cast<std::size_t>(at)].child[o];
  }
}

void ChargeTree::add_along(std::size_t i, double dq) {
  const Vec3& p = points_[i].at;
  for (std::int32_t at = root_; at >= 0;) {
    Node& node = nodes_[static_cast<std::size_t>(at)];
    node.total += dq;
    node.moment += dq * p;
    if (node.leaf) return;
    at = node.child[octant(node, p)];
  }
}

void ChargeTree::set_charge(std::size_t i, double q) {
  packed_ = false;
  const double old = points_[i].q;
  points_[i].q = q;
  add_along(i, q - old);
}

void ChargeTree::load(const std::vector<double>& q) {
  for (Node& node : nodes_) {
    node.total = 0.0;
    node.moment = Vec3::Zero();
  }
  for (std::size_t i = 0; i < points_.size(); ++i) {
    points_[i].q = q[i];
    add_along(i, q[i]);
  }
  pack();
}

// A product sums the tree once for every particle: a leaf's points, scattered over points_
// in the order they came, cost a cache miss each, and a node's unused fields more lines.
void ChargeTree::pack() {
  packed_nodes_.resize(nodes_.size());
  packed_points_.clear();
  packed_points_.reserve(points_.size());
  for (std::size_t at = 0; at < nodes_.size(); ++at) {
    const Node& node = nodes_[at];
    PackedNode& packed = packed_nodes_[at];
    packed.focus = node.focus;
    packed.dipole = dipole_of(node);
    packed.total = node.total;
    packed.width2 = width2(node);
    std::copy(std::begin(node.child), std::end(node.child), std::begin(packed.child));
    packed.begin = packed.end = -1;
    if (!node.leaf) continue;
    packed.begin = static_cast<std::int32_t>(packed_points_.size());
    for (std::int32_t j = node.first; j >= 0; j = points_[static_cast<std::size_t>(j)].next)
      packed_points_.push_back({points_[static_cast<std::size_t>(j)].at, points_[static_cast<std::size_t>(j)].q});
    packed.end = static_cast<std::int32_t>(packed_points_.size());
  }
  packed_ = true;
}

// Over the tree itself, or over its packed copy (kPacked): the same operations in the same
// order, so the same bits.
template <bool kPlanar, bool kPacked>
double ChargeTree::sum_at(const Vec3& x, double near) const {
  const auto g = [&](double r2) { return green<kPlanar>(std::sqrt(std::max(r2, near * near)), far_log_); };
  // Depth-first; at most seven siblings wait at each level.
  std::array<std::int32_t, 8 * (kMaxDepth + 2)> stack;
  std::size_t top = 0;
  stack[top++] = root_;
  double total = 0.0;
  while (top > 0) {
    const std::size_t at = static_cast<std::size_t>(stack[--top]);
    const auto& node = [&]() -> const auto& {
      if constexpr (kPacked) return packed_nodes_[at];
      else return nodes_[at];
    }();
    if constexpr (kPacked) {
      if (node.begin >= 0) {
        for (std::int32_t j = node.begin; j < node.end; ++j) {
          const PackedPoint& point = packed_points_[static_cast<std::size_t>(j)];
          total += point.q * g((x - point.at).squaredNorm());
        }
        continue;
      }
    } else if (node.leaf) {
      for (std::int32_t j = node.first; j >= 0;) {
        const Point& point = points_[static_cast<std::size_t>(j)];
        total += point.q * g((x - point.at).squaredNorm());
        j = point.next;
      }
      continue;
    }
    const Vec3 off = x - node.focus;
    const double d2 = off.squaredNorm();
    if (width2(node) < theta2_ * d2) {
      // The monopole and the dipole p = sum q (x_j - focus): G's gradient towards x is
      // off / d^3 in 3D and off / d^2 in 2D.
      const double dipole = dipole_of(node).dot(off);
      if constexpr (kPlanar) total += node.total * g(d2) + dipole / d2;
      else total += node.total * g(d2) + dipole / (d2 * std::sqrt(d2));
      continue;
    }
    for (int o = 7; o >= 0; --o)
      if (node.child[o] >= 0) stack[top++] = node.child[o];
  }
  return total;
}

double ChargeTree::potential(const Vec3& x, double near) const {
  if (root_ < 0) return 0.0;
  if (packed_) return dimensions_ == 2 ? sum_at<true, true>(x, near) : sum_at<false, true>(x, near);
  return dimensions_ == 2 ? sum_at<true, false>(x, near) : sum_at<false, false>(x, near);
}

namespace {

// Barnes-Hut's opening angle: below 1/sqrt(3), a node that holds the point asked about is
// always opened, so no particle's own charge is lumped with others.
constexpr double kTheta = 0.5;
//! Each new particle relaxes the charges within this many spacings of it, this many times.
constexpr double kRelaxRadius = 3.0;
constexpr int kSweeps = 2;
//! A solve each time the count grows by this fraction, of this many conjugate-gradient steps
//! from the kept charges (docs/dev/breakdown-field.md measures the choice).
constexpr double kSolveEvery = 0.1;
constexpr int kSolveSteps = 12;
//! The first solve, of the seeds and the first few particles.
constexpr std::size_t kFirstSolve = 8;
constexpr int kFirstSolveSteps = 50;
//! A point target is a ball half a spacing across; a mesh's points are as near each other.
constexpr double kTargetNear = 0.25;
//! A particle's image across a plane counts no nearer than a spacing: one that touches the
//! plane keeps a charge rather than cancel with its image.
constexpr double kImageNear = 1.0;
//! Rows of a product a job.
constexpr std::size_t kRowsPerJob = 256;

//! A Fenwick tree of weights: a draw by weight and a change of one in O(log n).
class WeightTree {
 public:
  void push(double w) {
    values_.push_back(w);
    const std::size_t k = values_.size();  // 1-based
    double sum = w;
    for (std::size_t j = k - 1; j > k - (k & (~k + 1)); j -= j & (~j + 1)) sum += tree_[j - 1];
    tree_.push_back(sum);
  }
  void set(std::size_t i, double w) {
    const double delta = w - values_[i];
    values_[i] = w;
    for (std::size_t k = i + 1; k <= tree_.size(); k += k & (~k + 1)) tree_[k - 1] += delta;
  }
  //! Sums taken afresh: the changes' rounding is gone.
  void rebuild() {
    tree_ = values_;
    for (std::size_t k = 1; k <= tree_.size(); ++k) {
      const std::size_t up = k + (k & (~k + 1));
      if (up <= tree_.size()) tree_[up - 1] += tree_[k - 1];
    }
  }
  //! A weight changed without the sums: rebuild() follows.
  void set_alone(std::size_t i, double w) { values_[i] = w; }
  double value(std::size_t i) const { return values_[i]; }
  double total() const {
    double sum = 0.0;
    for (std::size_t k = tree_.size(); k > 0; k -= k & (~k + 1)) sum += tree_[k - 1];
    return sum;
  }
  //! The entry whose span of the running sum holds `pick`, in [0, total()); size() past it.
  std::size_t find(double pick) const {
    std::size_t at = 0, step = 1;
    while (step * 2 <= tree_.size()) step *= 2;
    for (; step > 0; step /= 2)
      if (at + step <= tree_.size() && tree_[at + step - 1] <= pick) {
        at += step;
        pick -= tree_[at - 1];
      }
    return at;
  }
  std::size_t size() const { return values_.size(); }

 private:
  std::vector<double> values_, tree_;
};

}  // namespace

ConductorField::ConductorField(const Vec3& origin, double spacing, int dimensions, const Target& target,
                               std::uint64_t rng_seed, int threads)
    : origin_(origin), spacing_(spacing), tree_(dimensions, kTheta), crew_(threads) {
  if (target.kind == TargetKind::plane) {
    mirror_axis_ = static_cast<int>(target.axis);
    mirror_at_ = (target.at - origin_[mirror_axis_]) / spacing;
  }
  for (const Vec3& t : target_charge_points(target, rng_seed)) target_points_.push_back(scaled(t));
  target_on_ = !target_points_.empty();
  for (const Vec3& a : target_points_)
    for (const Vec3& b : target_points_) target_self_ += tree_.kernel((a - b).norm(), kTargetNear);
  if (target_on_) target_self_ /= static_cast<double>(target_points_.size() * target_points_.size());
}

double ConductorField::target_potential(const Vec3& x) const {
  double total = 0.0;
  for (const Vec3& t : target_points_) total += tree_.kernel((x - t).norm(), kTargetNear);
  return target_points_.empty() ? 0.0 : total / static_cast<double>(target_points_.size());
}

Vec3 ConductorField::mirrored(Vec3 x) const {
  x[mirror_axis_] = 2.0 * mirror_at_ - x[mirror_axis_];
  return x;
}

// u at x (in spacings), whose target potential is `target`: the tree's charges' potential less
// their images' and the target's share; `total` and `weighted` are the charges' sum and their
// sum weighted by each one's target potential.
double ConductorField::u(const Vec3& x, double target, double total, double weighted) const {
  double sum = tree_.potential(x);
  if (mirror_axis_ >= 0) sum -= tree_.potential(mirrored(x), kImageNear);
  if (target_on_) sum -= target * total + weighted - target_self_ * total;
  return sum;
}

double ConductorField::potential(const Vec3& x) const {
  const Vec3 at = scaled(x);
  return 1.0 - u(at, target_potential(at), total_, weighted_);
}

// K_ii, floored where an image or the target's charge nearly cancels the particle's own term,
// so that a relaxation step stays finite.
double ConductorField::diagonal(std::size_t i) const {
  const Vec3& x = tree_.point(i);
  double k = tree_.kernel(0.0);
  if (mirror_axis_ >= 0) k -= tree_.kernel((mirrored(x) - x).norm(), kImageNear);
  if (target_on_) k -= 2.0 * target_[i] - target_self_;
  return std::max(k, tree_.kernel(1.0) - tree_.kernel(2.0));
}

void ConductorField::set_charge(std::size_t i, double q) {
  const double old = tree_.charge(i);
  tree_.set_charge(i, q);
  total_ += q - old;
  weighted_ += (q - old) * target_[i];
}

void ConductorField::add(const Vec3& p) {
  const Vec3 x = scaled(p);
  const std::size_t i = tree_.size();
  tree_.insert(x, 0.0);
  target_.push_back(target_potential(x));
  diagonal_.push_back(diagonal(i));
  set_charge(i, (1.0 - held_at(i)) / diagonal_[i]);
}

void ConductorField::relax(const std::vector<std::int32_t>& particles) {
  for (const std::int32_t j : particles) {
    const std::size_t i = static_cast<std::size_t>(j);
    set_charge(i, tree_.charge(i) + (1.0 - held_at(i)) / diagonal_[i]);
  }
}

// y = K v over every particle, on the crew's threads; the tree holds v after.
void ConductorField::product(const std::vector<double>& v, std::vector<double>& y) {
  tree_.load(v);
  double total = 0.0, weighted = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    total += v[i];
    weighted += v[i] * target_[i];
  }
  y.resize(v.size());
  const std::size_t jobs = (v.size() + kRowsPerJob - 1) / kRowsPerJob;
  crew_.run(jobs, [&](std::size_t job) {
    const std::size_t last = std::min(v.size(), (job + 1) * kRowsPerJob);
    for (std::size_t i = job * kRowsPerJob; i < last; ++i) y[i] = u(tree_.point(i), target_[i], total, weighted);
  });
}

namespace {
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
  return sum;
}
}  // namespace

void ConductorField::solve(int steps, const StopFlag* stop) {
  const std::size_t n = tree_.size();
  std::vector<double> q(n), residual(n), direction, image;
  for (std::size_t i = 0; i < n; ++i) q[i] = tree_.charge(i);
  product(q, image);
  for (std::size_t i = 0; i < n; ++i) residual[i] = 1.0 - image[i];
  direction = residual;
  double rr = dot(residual, residual);
  for (int step = 0; step < steps && rr > 1e-24 * static_cast<double>(n); ++step) {
    if (stop && stop->load(std::memory_order_relaxed)) break;
    product(direction, image);
    const double curvature = dot(direction, image);
    if (!(curvature > 0.0)) break;
    const double length = rr / curvature;
    for (std::size_t i = 0; i < n; ++i) {
      q[i] += length * direction[i];
      residual[i] -= length * image[i];
    }
    const double before = rr;
    rr = dot(residual, residual);
    for (std::size_t i = 0; i < n; ++i) direction[i] = residual[i] + (rr / before) * direction[i];
  }
  tree_.load(q);
  total_ = weighted_ = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    total_ += q[i];
    weighted_ += q[i] * target_[i];
  }
}

void ConductorField::drop_target() {
  target_on_ = false;
  for (std::size_t i = 0; i < diagonal_.size(); ++i) diagonal_[i] = diagonal(i);
}

namespace {

class ConductorDischarge {
 public:
  ConductorDischarge(const DlaOptions& walk, const BreakdownOptions& o, const MeshConstraint* constraint,
                     const StopFlag* stop, BreakdownStats& stats)
      : walk_(walk),
        options_(o),
        constraint_(constraint),
        stop_(stop),
        stats_(stats),
        cluster_(seeded(walk.seeds, walk.spacing, walk.dimensions)),
        index_(cluster_.particles, walk.spacing, walk.dimensions, false),
        field_(cluster_.center, walk.spacing, walk.dimensions, o.target, walk.rng_seed, walk.threads) {
    if (o.target.kind != TargetKind::none) electrode_.emplace(o.target, cluster_.center, walk.spacing, walk.dimensions);
    cluster_.particles.reserve(cluster_.particles.size() + walk.particles);
    index_.reserve(cluster_.particles.capacity());
  }

  Cluster run(const ProgressFn& progress) {
    const auto seed = [&] {
      for (std::size_t i = 0; i < cluster_.particles.size(); ++i) charge(static_cast<std::int32_t>(i));
      solve(kFirstSolveSteps);
      for (std::size_t i = 0; i < cluster_.particles.size(); ++i) open_sites(static_cast<std::int32_t>(i));
      next_solve_ = std::max(kFirstSolve, grown_by(cluster_.particles.size()));
    };
    const auto point_struck = [&] {
      field_.drop_target();
      next_solve_ = 0;
    };
    grow_until_done(cluster_, walk_, options_, electrode_ ? &*electrode_ : nullptr, progress, stop_, stats_, seed,
                    [&](std::size_t k) { attach(k); }, point_struck);
    return std::move(cluster_);
  }

 private:
  static std::size_t grown_by(std::size_t n) {
    return std::max(n + 1, static_cast<std::size_t>(static_cast<double>(n) * (1.0 + kSolveEvery)));
  }

  double weight_of(std::size_t i) const {
    return site_open_[i] != 0 ? std::pow(std::max(field_.charge(i), 0.0), options_.eta) : 0.0;
  }

  //! Particle id is in the structure: the index, the feed, the electrode and the field know it.
  void charge(std::int32_t id) {
    const Particle& p = cluster_.particles[static_cast<std::size_t>(id)];
    index_.insert(id);
    if (stats_.feed) stats_.feed->put(p);
    if (electrode_) electrode_->grown(p.position);
    field_.add(p.position);
    site_open_.push_back(0);
    weights_.push(0.0);
  }

  //! The charges within kRelaxRadius of particle id, relaxed in their order.
  void relax_near(std::int32_t id) {
    near_.clear();
    index_.for_each_within(cluster_.particles[static_cast<std::size_t>(id)].position, kRelaxRadius * walk_.spacing,
                           [&](std::int32_t j, double) { near_.push_back(j); });
    std::sort(near_.begin(), near_.end());
    for (int sweep = 0; sweep < kSweeps; ++sweep) field_.relax(near_);
    for (const std::int32_t j : near_) weights_.set(static_cast<std::size_t>(j), weight_of(static_cast<std::size_t>(j)));
  }

  void solve(int steps) {
    field_.solve(steps, stop_);
    for (std::size_t i = 0; i < field_.size(); ++i) weights_.set_alone(i, weight_of(i));
    weights_.rebuild();
    ++stats_.solves;
  }

  //! A particle with an open site, by weight q^eta: -1 when none has one.
  std::ptrdiff_t draw_parent(Rng& rng) {
    const double total = weights_.total();
    if (total > 0.0) {
      const std::size_t i = weights_.find(rng.uniform() * total);
      if (i < weights_.size() && weights_.value(i) > 0.0) return static_cast<std::ptrdiff_t>(i);
    }
    // The sums' rounding, or no weight at all (charges at or below zero): by weight, else
    // evenly, over the particles with an open site, one pass.
    double sum = 0.0;
    std::size_t open = 0;
    for (std::size_t i = 0; i < weights_.size(); ++i) {
      sum += weights_.value(i);
      open += site_open_[i] != 0;
    }
    if (open == 0) return -1;
    double pick = rng.uniform() * (sum > 0.0 ? sum : static_cast<double>(open));
    std::ptrdiff_t last = -1;
    for (std::size_t i = 0; i < weights_.size(); ++i) {
      if (site_open_[i] == 0) continue;
      last = static_cast<std::ptrdiff_t>(i);
      pick -= sum > 0.0 ? weights_.value(i) : 1.0;
      if (pick < 0.0) break;
    }
    return last;
  }

  //! Particle k: a parent by q^eta, then one of its open sites by (1 - u)^eta. Sites that
  //! later particles came within a spacing of close as the draw finds them.
  void attach(std::size_t k) {
    if (cluster_.particles.size() >= next_solve_) {
      solve(kSolveSteps);
      next_solve_ = grown_by(cluster_.particles.size());
    }
    Rng rng(walk_.rng_seed, kChoiceStreams + k);
    for (;;) {
      const std::ptrdiff_t drawn = draw_parent(rng);
      if (drawn < 0)
        throw GrowthError("no free site is left next to the structure after " + std::to_string(k) +
                          " particles: the mesh holds no more");
      const std::size_t parent = static_cast<std::size_t>(drawn);
      candidates_.clear();
      for (int s = 0; s < kSites; ++s) {
        if (!(site_open_[parent] >> s & 1)) continue;
        const Vec3& at = site_at_[parent * kSites + static_cast<std::size_t>(s)];
        if (free_at(index_, at, static_cast<std::int32_t>(parent), walk_.spacing)) candidates_.push_back(s);
        else site_open_[parent] &= static_cast<std::uint8_t>(~(1u << s));
      }
      if (candidates_.empty()) {
        weights_.set(parent, 0.0);
        continue;
      }
      stats_.sites += candidates_.size();
      chances_.clear();
      double sum = 0.0;
      for (const int s : candidates_) {
        const double phi = std::max(0.0, field_.potential(site_at_[parent * kSites + static_cast<std::size_t>(s)]));
        chances_.push_back(std::pow(phi, options_.eta));
        sum += chances_.back();
      }
      double pick = rng.uniform() * (sum > 0.0 ? sum : static_cast<double>(candidates_.size()));
      std::size_t chosen = 0;
      for (; chosen + 1 < candidates_.size(); ++chosen) {
        pick -= sum > 0.0 ? chances_[chosen] : 1.0;
        if (pick < 0.0) break;
      }
      const int s = candidates_[chosen];
      site_open_[parent] &= static_cast<std::uint8_t>(~(1u << s));
      weights_.set(parent, weight_of(parent));
      const Particle& from = cluster_.particles[parent];
      cluster_.particles.push_back({site_at_[parent * kSites + static_cast<std::size_t>(s)],
                                    static_cast<std::int32_t>(parent), from.seed});
      break;
    }
    const std::int32_t id = static_cast<std::int32_t>(cluster_.particles.size() - 1);
    charge(id);
    relax_near(id);
    open_sites(id);
  }

  //! The sites beside particle id (breakdown_charges.h's sites_beside), open.
  void open_sites(std::int32_t id) {
    sites_beside(id, cluster_.particles[static_cast<std::size_t>(id)].position, walk_, constraint_, index_, sites_);
    const std::size_t i = static_cast<std::size_t>(id);
    site_at_.resize((i + 1) * kSites, Vec3::Zero());
    std::uint8_t open = 0;
    for (std::size_t s = 0; s < sites_.size(); ++s) {
      site_at_[i * kSites + s] = sites_[s];
      open |= static_cast<std::uint8_t>(1u << s);
    }
    site_open_[i] = open;
    weights_.set(i, weight_of(i));
  }

  static constexpr int kSites = 6;  // sites_beside() opens at most six

  const DlaOptions& walk_;
  const BreakdownOptions& options_;
  const MeshConstraint* constraint_;
  const StopFlag* stop_;
  BreakdownStats& stats_;
  Cluster cluster_;
  GridIndex index_;
  std::optional<Electrode> electrode_;
  ConductorField field_;
  WeightTree weights_;
  std::vector<Vec3> site_at_;           // kSites a particle
  std::vector<std::uint8_t> site_open_;  // a bit a site
  std::size_t next_solve_ = 0;
  // Scratch, kept between particles.
  std::vector<std::int32_t> near_;
  std::vector<Vec3> sites_;
  std::vector<int> candidates_;
  std::vector<double> chances_;
};

}  // namespace

Cluster grow_by_conductor(const DlaOptions& walk, const BreakdownOptions& options, const MeshConstraint* constraint,
                          const ProgressFn& progress, const StopFlag* stop, BreakdownStats& stats) {
  return ConductorDischarge(walk, options, constraint, stop, stats).run(progress);
}

}  // namespace dla::detail
