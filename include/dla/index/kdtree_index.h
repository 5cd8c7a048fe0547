#pragma once
//! \file kdtree_index.h
//! A dynamic k-d tree (nanoflann's logarithmic forest of static trees) behind the index
//! interface of spatial_index.h. Exact at every query; slower than GridIndex (see docs/spatial-index.md).

#include "dla/index/spatial_index.h"

#include "dla/index/detail/nanoflann.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace dla {

class KdTreeIndex {
 public:
  KdTreeIndex(const std::vector<Particle>& particles, double /*spacing*/, int /*dimensions*/)
      : adaptor_{&particles, 0},
        tree_(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(16), std::size_t{1} << 31) {}

  KdTreeIndex(const KdTreeIndex&) = delete;
  KdTreeIndex& operator=(const KdTreeIndex&) = delete;

  void reserve(std::size_t /*particles*/) {}
  bool holds(const Vec3& /*center*/, double /*radius*/) const { return true; }
  bool insert(std::int32_t id) {
    adaptor_.count = static_cast<std::size_t>(id) + 1;
    tree_.addPoints(static_cast<std::uint32_t>(id), static_cast<std::uint32_t>(id));
    return true;
  }
  void cover(const Vec3& /*center*/, double /*radius*/) {}

  Probe probe(const Vec3& x, Reach /*reach*/ = Reach::set) const {  // the reach costs nothing here
    Probe result;
    if (adaptor_.count == 0) return result;
    std::uint32_t id = 0;
    double d2 = 0.0;
    nanoflann::KNNResultSet<double, std::uint32_t> found(1);
    found.init(&id, &d2);
    tree_.findNeighbors(found, x.data(), nanoflann::SearchParams());
    result.nearest = static_cast<std::int32_t>(id);
    result.reaching(x, result.distance = std::sqrt(d2));
    return result;
  }

  template <class Visit>
  void for_each_within(const Vec3& x, double radius, Visit&& visit) const {
    if (adaptor_.count == 0) return;
    matches_.clear();
    nanoflann::RadiusResultSet<double, std::uint32_t> found(radius * radius, matches_);
    tree_.findNeighbors(found, x.data(), nanoflann::SearchParams());
    for (const auto& [id, d2] : matches_) visit(static_cast<std::int32_t>(id), d2);
  }

 private:
  //! nanoflann's dataset interface over the particle store: only the first `count` exist.
  struct Adaptor {
    const std::vector<Particle>* particles;
    std::size_t count;
    std::size_t kdtree_get_point_count() const { return count; }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const {
      return (*particles)[i].position[static_cast<Eigen::Index>(axis)];
    }
    template <class Bbox>
    bool kdtree_get_bbox(Bbox& /*bbox*/) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexDynamicAdaptor<
      nanoflann::L2_Simple_Adaptor<double, Adaptor>, Adaptor, 3, std::uint32_t>;

  Adaptor adaptor_;
  Tree tree_;
  mutable std::vector<std::pair<std::uint32_t, double>> matches_;  // reused between queries
};

}  // namespace dla
