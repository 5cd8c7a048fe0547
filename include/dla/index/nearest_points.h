#pragma once
//! \file nearest_points.h
//! Nearest-point look-ups in a fixed set of points: the distance to the nearest seed
//! (nanoflann's static k-d tree, or a scan for a few), and to the nearest other instancing
//! point (a compact k-d tree of float copies, for millions of tips).

#include "dla/core/options.h"

#include "dla/index/detail/nanoflann.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace dla {

//! Nearest-point queries over `Points`: anything with size() and operator[](i) giving a Vec3,
//! such as a std::vector<Vec3>. Keeps a reference to the points, which must outlive it and not
//! change.
template <class Points = std::vector<Vec3>>
class NearestPoints {
 public:
  explicit NearestPoints(const Points& points)
      : adaptor_{&points}, tree_(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    if (points.size() > 0) tree_.buildIndex();
  }
  NearestPoints(const NearestPoints&) = delete;  // the tree points at adaptor_
  NearestPoints& operator=(const NearestPoints&) = delete;

  //! Distance from p to the nearest point of the set; infinity for an empty set.
  double distance(const Vec3& p) const {
    const Points& points = *adaptor_.points;
    if (points.size() <= kScanned) {
      // A few seeds: a scan beats the tree's descent several times over.
      double d2 = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < points.size(); ++i) d2 = std::min(d2, (points[i] - p).squaredNorm());
      return std::sqrt(d2);
    }
    std::uint32_t index = 0;
    double d2 = 0.0;
    tree_.knnSearch(p.data(), 1, &index, &d2);
    return std::sqrt(d2);
  }

 private:
  static constexpr std::size_t kScanned = 16;

  struct Adaptor {
    const Points* points;
    std::size_t kdtree_get_point_count() const { return points->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const { return (*points)[i][static_cast<int>(axis)]; }
    template <class Bbox>
    bool kdtree_get_bbox(Bbox&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>, Adaptor, 3>;

  Adaptor adaptor_;
  Tree tree_;
};

//! The distance from each of a set of points to the nearest other, for millions of points in
//! 16 bytes each and nothing else: an implicit k-d tree (each range's median splits it, the
//! axes in turn) over float copies relative to an origin. The distances are exact but for the
//! floats' rounding, which is taken off them: they never exceed the true distance.
class NearestOther {
 public:
  //! Room for `count` points; `scale` is a typical distance between them (the spacing), to
  //! keep the floats small.
  NearestOther(const Vec3& origin, double scale, std::size_t count) : origin_(origin), scale_(scale) {
    points_.reserve(count);
  }

  void add(const Vec3& p) {
    points_.push_back({((p - origin_) / scale_).cast<float>(), static_cast<std::uint32_t>(points_.size())});
  }
  std::size_t size() const { return points_.size(); }

  //! Once every point is added, before the first query.
  void build() {
    float reach = 0.0f;
    for (const Point& p : points_) reach = std::max(reach, p.position.cwiseAbs().maxCoeff());
    // Each coordinate is off by half a float step at the reach, a difference by a step per
    // axis, and the float arithmetic adds a few: 8 steps bound it.
    error_ = 8.0 * static_cast<double>(reach) * std::numeric_limits<float>::epsilon();
    axis_count_ = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (const Point& p : points_)
        if (p.position[axis] != points_.front().position[axis]) {
          axes_[axis_count_++] = axis;  // a flat structure (2D) is split on x and y only
          break;
        }
    build(0, points_.size(), 0);
  }

  //! For the points at places [from, to) of the tree's order (a part of [0, size())), calls
  //! visit(k, d): d is the distance from the k-th point added to the nearest other point, a
  //! point at the same place counting at 0, and infinity for a set of one. The tree's order
  //! keeps neighbours together: the look-ups run in cache, not across it at random.
  template <class Visit>
  void distances_to_others(std::size_t from, std::size_t to, Visit&& visit) const {
    for (std::size_t place = from; place < to; ++place) {
      float best[2] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
      search(0, points_.size(), 0, points_[place].position, best);
      const double d = std::isfinite(best[1]) ? std::max(0.0, std::sqrt(static_cast<double>(best[1])) - error_) * scale_
                                              : std::numeric_limits<double>::infinity();
      visit(static_cast<std::size_t>(points_[place].added), d);
    }
  }

 private:
  static constexpr std::size_t kLeaf = 8;

  struct Point {
    Eigen::Vector3f position;
    std::uint32_t added;  //!< its place in the order of add()
  };

  void build(std::size_t from, std::size_t to, int depth) {
    if (to - from <= kLeaf || axis_count_ == 0) return;
    const int axis = axes_[depth % axis_count_];
    const std::size_t middle = from + (to - from) / 2;
    std::nth_element(points_.begin() + static_cast<std::ptrdiff_t>(from), points_.begin() + static_cast<std::ptrdiff_t>(middle),
                     points_.begin() + static_cast<std::ptrdiff_t>(to),
                     [axis](const Point& a, const Point& b) { return a.position[axis] < b.position[axis]; });
    build(from, middle, depth + 1);
    build(middle + 1, to, depth + 1);
  }

  //! Keeps the two smallest squared distances from q in best[0] <= best[1]: the first is q's
  //! own point.
  void search(std::size_t from, std::size_t to, int depth, const Eigen::Vector3f& q, float best[2]) const {
    const auto consider = [&](const Eigen::Vector3f& p) {
      const float d2 = (p - q).squaredNorm();
      if (d2 < best[0]) best[1] = best[0], best[0] = d2;
      else if (d2 < best[1]) best[1] = d2;
    };
    if (to - from <= kLeaf || axis_count_ == 0) {
      for (std::size_t i = from; i < to; ++i) consider(points_[i].position);
      return;
    }
    const int axis = axes_[depth % axis_count_];
    const std::size_t middle = from + (to - from) / 2;
    consider(points_[middle].position);
    const float gap = q[axis] - points_[middle].position[axis];
    const bool left_first = gap < 0.0f;
    if (left_first) search(from, middle, depth + 1, q, best);
    else search(middle + 1, to, depth + 1, q, best);
    if (gap * gap <= best[1]) {
      if (left_first) search(middle + 1, to, depth + 1, q, best);
      else search(from, middle, depth + 1, q, best);
    }
  }

  std::vector<Point> points_;
  Vec3 origin_;
  double scale_;
  double error_ = 0.0;
  int axes_[3] = {0, 1, 2};
  int axis_count_ = 0;
};

//! The distance to a fixed set of points (the seeds), holding its own copy: cheap to copy,
//! and asked per particle rather than stored, at no cost in memory.
class PointDistance {
 public:
  PointDistance() : PointDistance(std::vector<Vec3>{}) {}
  explicit PointDistance(std::vector<Vec3> points) : set_(std::make_shared<const Set>(std::move(points))) {}

  //! Distance from p to the nearest point; infinity for no point.
  double operator()(const Vec3& p) const { return set_->nearest.distance(p); }
  const std::vector<Vec3>& points() const { return set_->points; }

 private:
  struct Set {
    explicit Set(std::vector<Vec3> p) : points(std::move(p)), nearest(points) {}
    std::vector<Vec3> points;
    NearestPoints<> nearest;
  };
  std::shared_ptr<const Set> set_;
};

}  // namespace dla
