#pragma once
// The breakdown model's conductor field (BreakdownField::conductor, breakdown.h). Private to
// libdla; the physics and its measurements are in docs/breakdown.md and docs/dev/breakdown-field.md.
//
// A point charge q_i at every particle, solved so that the structure is one conductor: the
// potential difference u between each particle and the other electrode is 1. The charge on a
// conductor is the field on it, the harmonic measure the walkers count, so a particle grows a
// branch with weight q^eta, and then one of its open sites with weight (1 - u)^eta.
//
// u(x) = sum_j q_j K(x, x_j), in spacings, with G(r) = 1/r in 3D and ln(R/r) in 2D (R a far
// circle, 1e6 spacings), r no less than half a spacing (a particle's own radius):
// - no target: K = G, and u = 0 far away;
// - a plane: K(x, y) = G(x, y) - G(x, y'), y' the image of y across it, and u = 0 on it;
// - a point or a mesh: the target holds the opposite of the structure's charge, spread over
//   its points t (target_charge_points), so that K(x, y) = G(x, y) - T(x) - T(y) + T_tt with
//   T the mean of G(., t) and T_tt the mean of G(t, t').
//
// The charges are kept by the particles near each new one, relaxed by Gauss-Seidel, and solved
// afresh by conjugate gradients each time the count grows by a tenth; every potential is a
// Barnes-Hut sum over a tree of the charges.

#include "dla/core/options.h"
#include "dla/models/breakdown.h"

#include "models/crew.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dla::detail {

//! Point charges in a Barnes-Hut tree (an octree; in 2D only four children are used), for the
//! potential sum_j q_j G(max(|x - x_j|, near)) anywhere in O(log n). Positions are in spacings.
//! A node far enough away (its width over its distance below `theta`) counts as its total
//! charge and its dipole at the mean of its points: a place that does not depend on the
//! charges, so that the potential is linear in them, as conjugate gradients need. The tree's shape depends on the
//! order of insertion alone, and every sum is taken in one fixed order, so results do not
//! depend on the threads that ask.
class ChargeTree {
 public:
  ChargeTree(int dimensions, double theta);

  void insert(const Vec3& p, double q);
  void set_charge(std::size_t i, double q);
  //! Every charge at once, the node sums taken afresh. Until the next insert or set_charge,
  //! potentials are summed over a packed copy of the tree, to the same bits, faster.
  void load(const std::vector<double>& q);

  std::size_t size() const { return points_.size(); }
  double charge(std::size_t i) const { return points_[i].q; }
  const Vec3& point(std::size_t i) const { return points_[i].at; }

  //! G at r spacings, r no less than `near`.
  double kernel(double r, double near = kNear) const;
  double potential(const Vec3& x, double near = kNear) const;

  static constexpr double kNear = 0.5;

 private:
  struct Node {
    Vec3 centre;                       // of the box
    Vec3 focus;                        // the mean of its points, where its charge counts
    Vec3 point_sum = Vec3::Zero();     // of its points
    double half = 0.0;                 // half its width
    double total = 0.0;                // sum of q
    Vec3 moment = Vec3::Zero();        // sum of q x: with the total, the dipole about the focus
    std::int32_t child[8];       // -1: none
    std::int32_t first = -1;     // a leaf's first point, then Point::next
    std::int32_t count = 0;      // points below
    std::int32_t depth = 0;
    bool leaf = true;
    void add_point(const Vec3& p, double q);
  };
  struct Point {
    Vec3 at;
    double q;
    std::int32_t next;  // the next point in its leaf; -1: none
  };

  //! A node as the sums read it: its leaf's points contiguous, in their list's order.
  struct PackedNode {
    Vec3 focus;
    Vec3 dipole;          // moment - total focus
    double total;
    double width2;        // its width squared
    std::int32_t child[8];
    std::int32_t begin;   // a leaf's points in packed_points_; -1: not a leaf
    std::int32_t end;
  };
  struct PackedPoint {
    Vec3 at;
    double q;
  };

  std::int32_t new_node(const Vec3& centre, double half, std::int32_t depth);
  void pack();
  int octant(const Node& node, const Vec3& p) const;
  //! Adds charge dq at point i along the path from the root to its leaf.
  void add_along(std::size_t i, double dq);
  void split(std::int32_t node);
  static double width2(const Node& node) { return (2.0 * node.half) * (2.0 * node.half); }
  static double width2(const PackedNode& node) { return node.width2; }
  static Vec3 dipole_of(const Node& node) { return node.moment - node.total * node.focus; }
  static const Vec3& dipole_of(const PackedNode& node) { return node.dipole; }
  template <bool kPlanar, bool kPacked>
  double sum_at(const Vec3& x, double near) const;

  int dimensions_;
  double theta2_;
  double far_log_;  // ln R, 2D
  std::vector<Node> nodes_;
  std::int32_t root_ = -1;
  std::vector<Point> points_;
  std::vector<PackedNode> packed_nodes_;  // valid while packed_
  std::vector<PackedPoint> packed_points_;
  bool packed_ = false;
};

//! The structure's charges against the other electrode: K q = 1 over the particles, kept as
//! particles come. Positions are in scene units; a particle's index is its order of adding.
class ConductorField {
 public:
  //! `threads` share the conjugate-gradient products; the charges do not depend on them.
  ConductorField(const Vec3& origin, double spacing, int dimensions, const Target& target, std::uint64_t rng_seed,
                 int threads);

  //! A particle, with the charge that holds it at the structure's potential against the rest.
  void add(const Vec3& p);
  //! One Gauss-Seidel step for each of `particles`, in their order.
  void relax(const std::vector<std::int32_t>& particles);
  //! K q = 1 by conjugate gradients from the kept charges, at most `steps` of them; `stop`,
  //! set, ends it early with the charges it reached.
  void solve(int steps, const StopFlag* stop = nullptr);
  //! The target ball is at the structure's potential (struck): the structure alone is charged.
  void drop_target();

  std::size_t size() const { return tree_.size(); }
  double charge(std::size_t i) const { return tree_.charge(i); }
  //! 1 - u at x: 0 on the structure, 1 at the other electrode (and far away).
  double potential(const Vec3& x) const;
  //! (K q)_i: 1 once the charges are solved.
  double held_at(std::size_t i) const { return u(tree_.point(i), target_[i], total_, weighted_); }

 private:
  Vec3 scaled(const Vec3& x) const { return (x - origin_) / spacing_; }
  double target_potential(const Vec3& x) const;
  Vec3 mirrored(Vec3 x) const;
  double u(const Vec3& x, double target, double total, double weighted) const;
  double diagonal(std::size_t i) const;
  void set_charge(std::size_t i, double q);
  void product(const std::vector<double>& v, std::vector<double>& y);

  Vec3 origin_;  // of the field's coordinates, in spacings from it
  double spacing_;
  int mirror_axis_ = -1;  // a plane target: its axis, and where it crosses it
  double mirror_at_ = 0.0;
  std::vector<Vec3> target_points_;  // a point's or a mesh's charge, spread evenly over them
  bool target_on_ = false;
  double target_self_ = 0.0;  // T_tt
  ChargeTree tree_;
  Crew crew_;
  std::vector<double> target_;    // T per particle
  std::vector<double> diagonal_;  // K_ii per particle
  double total_ = 0.0, weighted_ = 0.0;  // sum q, sum q T
};

//! Grows the breakdown model with the conductor field; breakdown() validates first.
Cluster grow_by_conductor(const DlaOptions& walk, const BreakdownOptions& options, const MeshConstraint* constraint,
                          const ProgressFn& progress, const StopFlag* stop, BreakdownStats& stats);

}  // namespace dla::detail
