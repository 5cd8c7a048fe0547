#pragma once
//! \file inside_test.h
//! Inside or outside a closed triangle mesh: an exact winding number by signed ray crossings,
//! right on self-intersecting meshes too, and a voxel grid of the answer for look-ups on every
//! walk step. No CGAL or Embree here. See docs/constraints.md.

#include "dla/mesh/mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dla {

//! A box, widened by a margin on every side, cut into cubic cells of `cell` or larger so that
//! there are at most about 16 million: the grids of InsideTest and ShellBand.
struct VoxelGrid {
  VoxelGrid() = default;
  VoxelGrid(const Box& box, double margin, double cell);

  Vec3 origin = Vec3::Zero();
  double cell = 1.0;
  std::array<std::size_t, 3> dims{1, 1, 1};  //!< cells along x, y and z

  std::size_t size() const { return dims[0] * dims[1] * dims[2]; }
  //! The cell holding p (x fastest, then y, then z), or size() beyond the grid.
  std::size_t index(const Vec3& p) const {
    const Vec3 f = (p - origin) / cell;
    if (!(f.x() >= 0.0 && f.y() >= 0.0 && f.z() >= 0.0 && f.x() < limits_[0] && f.y() < limits_[1] && f.z() < limits_[2]))
      return size();
    return (static_cast<std::size_t>(f.z()) * dims[1] + static_cast<std::size_t>(f.y())) * dims[0] +
           static_cast<std::size_t>(f.x());
  }
  Vec3 center(std::size_t i, std::size_t j, std::size_t k) const {
    return origin + cell * Vec3(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5, static_cast<double>(k) + 0.5);
  }

 private:
  double limits_[3] = {1, 1, 1};  // dims as doubles, for the look-up
};

//! What a cell of the inside grid holds.
enum class Region : std::uint8_t {
  outside,  //!< every point of the cell is outside, farther than the band from the surface
  inside,   //!< every point of the cell is inside, farther than the band from the surface
  surface,  //!< the cell comes within the band of a triangle: ask winding_number()
};

class InsideTest {
 public:
  //! `mesh` should be closed and oriented outward (see repair_mesh()); on an open mesh the
  //! winding number jumps across the holes. Cells within `band` of a triangle are `surface`;
  //! the cell size is `cell` or larger, so the grid stays within about 16 million cells.
  InsideTest(const TriangleMesh& mesh, double band, double cell);

  //! How many times the surface winds around p: 1 inside a simple closed mesh, 0 outside, 2
  //! where a self-intersecting mesh overlaps itself. Counts the signed crossings of the ray
  //! from p towards +z, with a tie rule that counts a ray through an edge or a vertex once.
  int winding_number(const Vec3& p) const;

  //! winding_number(p) > 0.
  bool contains(const Vec3& p) const { return winding_number(p) > 0; }

  //! contains() at the centre of every cell of a grid (x fastest, then y, then z), by one
  //! sweep of vertical lines: for a grid of one's own (ShellBand's).
  std::vector<bool> inside_centres(const VoxelGrid& grid) const;

  //! The cell's answer for p, a look-up; `outside` beyond the grid.
  Region region(const Vec3& p) const {
    const std::size_t i = grid_.index(p);
    return i < cells_.size() ? cells_[i] : Region::outside;
  }

  double cell_size() const { return grid_.cell; }
  std::size_t cell_count() const { return cells_.size(); }
  //! The grid's cell holding p, or cell_count() beyond it; and a cell's answer.
  std::size_t cell_of(const Vec3& p) const { return grid_.index(p); }
  Region cell_region(std::size_t cell) const { return cells_[cell]; }

 private:
  std::vector<Vec3> corners_;  // three per triangle
  // Triangles by xy bucket (compressed rows), for winding_number(): highest top first, with the
  // height above which each cannot be crossed, and lowest bottom first, with the height below
  // which it cannot.
  struct ByHeight {
    std::vector<std::uint32_t> triangles;
    std::vector<double> heights;
  };
  Vec3 bucket_origin_;
  double bucket_ = 1.0;
  int bucket_dims_[2] = {0, 0};
  std::vector<std::uint32_t> bucket_start_;
  ByHeight from_top_, from_bottom_;
  bool closed_ = false;  // every edge used as often one way as the other
  VoxelGrid grid_;
  std::vector<Region> cells_;
};

}  // namespace dla
