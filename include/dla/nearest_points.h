#pragma once
//! \file nearest_points.h
//! Nearest-point look-ups in a fixed set of points (nanoflann's static k-d tree): the distance
//! to the nearest seed, and to the nearest other instancing point.

#include "dla/options.h"

// nanoflann 1.4 leaves a bounding box uninitialised on a path it never takes; GCC warns.
#pragma GCC diagnostic push
#if defined(__GNUC__) && !defined(__clang__)  // a GCC-only warning
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nanoflann.hpp>
#pragma GCC diagnostic pop

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla {

class NearestPoints {
 public:
  //! Keeps a reference to `points`, which must outlive this and not change.
  explicit NearestPoints(const std::vector<Vec3>& points)
      : adaptor_{&points}, tree_(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    if (!points.empty()) tree_.buildIndex();
  }

  //! Distance from p to the nearest point of the set; infinity for an empty set.
  double distance(const Vec3& p) const {
    if (adaptor_.points->empty()) return std::numeric_limits<double>::infinity();
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
    const std::size_t found = tree_.knnSearch((*adaptor_.points)[i].data(), 2, index, d2);
    if (found < 2) return std::numeric_limits<double>::infinity();
    return std::sqrt(index[0] == i ? d2[1] : d2[0]);
  }

 private:
  struct Adaptor {
    const std::vector<Vec3>* points;
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
