#pragma once
//! \file shell.h
//! The layer over a surface that growth keeps to (`--shell T`): frost, lichen or rust creeping
//! over a model. A voxel grid says, for every walk step, whether a walker is in the layer; the
//! exact test, by the distance to the nearest triangle, is for new particles only. See
//! docs/constraints.md#growth-over-a-surface.

#include "dla/core/random.h"
#include "dla/mesh/inside_test.h"
#include "dla/mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace dla {

//! Which side of the surface the layer lies on.
enum class Layer { inside, outside, both };

class ShellBand {
 public:
  //! The voxels, of `cell` or larger (the grid stays within about 16 million, and a thick
  //! shell's set-up within a few seconds), whose centres lie within `thickness` of `mesh`, on
  //! the `layer` side of it by `inside`.
  ShellBand(const TriangleMesh& mesh, const InsideTest& inside, Layer layer, double thickness, double cell);

  //! Whether p's voxel is in the layer: a look-up, for every step.
  bool holds(const Vec3& p) const {
    std::array<std::size_t, 3> c;
    return grid_.locate(p, c) && held_.test(c);
  }

  //! A point uniform in the layer's voxels.
  Vec3 draw(Rng& rng) const;

  double cell_size() const { return grid_.cell; }
  std::size_t voxel_count() const { return voxels_.size(); }

 private:
  VoxelGrid grid_;
  BrickBits held_;
  std::vector<std::uint32_t> voxels_;  // the held ones, to draw from
};

}  // namespace dla
