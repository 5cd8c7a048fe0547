#pragma once
//! \file nearest_points.h
//! Nearest-point look-ups in a fixed set of points (nanoflann's static k-d tree): the distance
//! to the nearest seed, and to the nearest other instancing point.

#include "dla/options.h"

#include "dla/detail/nanoflann.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla {

//! Nearest-point queries over `Points`: anything with size() and operator[](i) giving a Vec3,
//! such as a std::vector<Vec3> or a ParticleSubset. Keeps a reference to the points, which
//! must outlive it and not change.
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
    if (adaptor_.points->size() == 0) return std::numeric_limits<double>::infinity();
    std::uint32_t index = 0;
    double d2 = 0.0;
    tree_.knnSearch(p.data(), 1, &index, &d2);
    return std::sqrt(d2);
  }

  //! Distance from point i of the set to the nearest other point of it (a point at the same
  //! place counts, at 0); infinity if the set holds one point.
  double distance_to_other(std::size_t i) const {
    std::uint32_t index[2] = {0, 0};
    double d2[2] = {0.0, 0.0};
    const Vec3 p = (*adaptor_.points)[i];
    const std::size_t found = tree_.knnSearch(p.data(), 2, index, d2);
    if (found < 2) return std::numeric_limits<double>::infinity();
    return std::sqrt(index[0] == i ? d2[1] : d2[0]);
  }

 private:
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

}  // namespace dla
