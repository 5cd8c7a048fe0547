#pragma once
//! \file fill.h
//! How much of a mesh's growing side the structure covers: the fraction of the enclosed volume
//! within a distance of some particle, kept on a voxel grid as particles attach (never by a
//! rescan). Growth with DlaOptions::fill stops when it reaches the asked fraction: the
//! Houdini thesis' "until the object is covered".

#include "dla/core/options.h"
#include "dla/mesh/constraint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dla {

class FillGauge {
 public:
  //! Voxels at most this many: the grid coarsens for a mesh large against the distance.
  static constexpr double kMaxVoxels = 32e6;

  //! Classifies the centre of every voxel of the mesh's box, half the distance wide (or as
  //! wide as the inside grid's cells, or wider to stay within kMaxVoxels), as enclosed by the
  //! mesh or not: the volume growth inside it
  //! fills (DlaOptions::fill needs `--side inside`).
  FillGauge(const MeshConstraint& constraint, double distance) : distance_(distance) {
    const Box& box = constraint.box();
    const Vec3 size = box.max - box.min;
    // No finer than the inside grid: a voxel near the surface takes an exact test.
    cell_ = std::max({0.5 * distance, constraint.inside_test().cell_size(), std::cbrt(size.prod() / kMaxVoxels)});
    origin_ = box.min;
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, static_cast<int>(std::ceil(size[a] / cell_)));
    state_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2], kOutside);
    // The inside grid answers most voxels; only those near the surface need the exact test.
    const InsideTest& inside = constraint.inside_test();
    for (int k = 0; k < dims_[2]; ++k)
      for (int j = 0; j < dims_[1]; ++j)
        for (int i = 0; i < dims_[0]; ++i) {
          const Vec3 c = centre(i, j, k);
          const Region region = inside.region(c);
          if (region == Region::inside || (region == Region::surface && inside.contains(c))) {
            state_[index(i, j, k)] = kOpen;
            ++volume_;
          }
        }
  }

  //! Marks the voxels whose centres lie within the distance of p.
  void add(const Vec3& p) {
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {  // clamped before the cast: a point may lie far off the box
      const double from = std::floor((p[a] - distance_ - origin_[a]) / cell_ - 0.5);
      const double to = std::ceil((p[a] + distance_ - origin_[a]) / cell_ - 0.5);
      if (!(to >= 0.0 && from <= dims_[a] - 1.0)) return;
      lo[a] = static_cast<int>(std::max(from, 0.0));
      hi[a] = static_cast<int>(std::min(to, dims_[a] - 1.0));
    }
    const double reach2 = distance_ * distance_;
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          std::uint8_t& state = state_[index(i, j, k)];
          if (state == kOpen && (centre(i, j, k) - p).squaredNorm() <= reach2) {
            state = kCovered;
            ++covered_;
          }
        }
  }

  //! The fraction of the growing side's voxels covered, in [0, 1]; 0 for an empty volume.
  double fraction() const { return volume_ ? static_cast<double>(covered_) / static_cast<double>(volume_) : 0.0; }
  double voxel_size() const { return cell_; }
  std::size_t volume_voxels() const { return volume_; }

 private:
  static constexpr std::uint8_t kOutside = 0, kOpen = 1, kCovered = 2;

  Vec3 centre(int i, int j, int k) const { return origin_ + cell_ * Vec3(i + 0.5, j + 0.5, k + 0.5); }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i;
  }

  double distance_;
  double cell_ = 1.0;
  Vec3 origin_ = Vec3::Zero();
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::uint8_t> state_;  // per voxel: outside the growing side, open, or covered
  std::size_t volume_ = 0, covered_ = 0;
};

}  // namespace dla
