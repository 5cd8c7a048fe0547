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
    std::array<std::size_t, 3> c;
    return locate(p, c) ? (c[2] * dims[1] + c[1]) * dims[0] + c[0] : size();
  }
  //! The cell holding p, by its place along each axis; false beyond the grid.
  bool locate(const Vec3& p, std::array<std::size_t, 3>& c) const {
    const Vec3 f = (p - origin) / cell;
    if (!(f.x() >= 0.0 && f.y() >= 0.0 && f.z() >= 0.0 && f.x() < limits_[0] && f.y() < limits_[1] && f.z() < limits_[2]))
      return false;
    c = {static_cast<std::size_t>(f.x()), static_cast<std::size_t>(f.y()), static_cast<std::size_t>(f.z())};
    return true;
  }
  Vec3 center(std::size_t i, std::size_t j, std::size_t k) const {
    return origin + cell * Vec3(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5, static_cast<double>(k) + 0.5);
  }

 private:
  double limits_[3] = {1, 1, 1};  // dims as doubles, for the look-up
};

//! A bit for each cell of a VoxelGrid, kept by bricks of 4x4x4 cells (a 64-bit word each),
//! under a bit for each brick that says whether any of its cells is set. A test in a brick
//! with none set reads only that bit: the brick bits, a bit for 64 cells (32 KB for 16 million
//! cells), stay in a core's caches where the cells' bits (2 MB) do not.
class BrickBits {
 public:
  BrickBits() = default;
  //! The cells i (VoxelGrid::index) for which set(i) is true.
  template <class Set>
  BrickBits(const VoxelGrid& grid, Set&& set) {
    for (int a = 0; a < 3; ++a) bricks_[a] = (grid.dims[a] + 3) / 4;
    const std::size_t count = bricks_[0] * bricks_[1] * bricks_[2];
    cells_.assign(count, 0);
    any_.assign((count + 63) / 64, 0);
    std::size_t i = 0;
    for (std::size_t z = 0; z < grid.dims[2]; ++z)
      for (std::size_t y = 0; y < grid.dims[1]; ++y)
        for (std::size_t x = 0; x < grid.dims[0]; ++x, ++i) {
          if (!set(i)) continue;
          const std::size_t brick = brick_of({x, y, z});
          cells_[brick] |= std::uint64_t{1} << bit_of({x, y, z});
          any_[brick >> 6] |= std::uint64_t{1} << (brick & 63);
        }
  }

  //! Whether the cell at c (VoxelGrid::locate) is set.
  bool test(const std::array<std::size_t, 3>& c) const {
    const std::size_t brick = brick_of(c);
    return (any_[brick >> 6] >> (brick & 63) & 1) && (cells_[brick] >> bit_of(c) & 1);
  }

 private:
  std::size_t brick_of(const std::array<std::size_t, 3>& c) const {
    return ((c[2] >> 2) * bricks_[1] + (c[1] >> 2)) * bricks_[0] + (c[0] >> 2);
  }
  static unsigned bit_of(const std::array<std::size_t, 3>& c) {
    return static_cast<unsigned>((c[2] & 3) << 4 | (c[1] & 3) << 2 | (c[0] & 3));
  }

  std::array<std::size_t, 3> bricks_{0, 0, 0};
  std::vector<std::uint64_t> cells_;  // a word a brick, bit (z, y, x) at 16z + 4y + x
  std::vector<std::uint64_t> any_;    // a bit a brick: any of its cells set
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
  //! Whether every edge is used as often one way as the other. The winding number of a closed
  //! mesh changes only across its triangles: it is the same all over a triangle that meets none.
  bool closed() const { return closed_; }
  //! True only if the triangle (a, b, c) stays more than `margin` from every triangle of the
  //! mesh, each kept apart from it by the plane of one of the two. False where some triangle
  //! comes nearer, and also for some that do not, and for a triangle over more than 256 of
  //! the winding number's columns: a cheap test for the common case, not a distance.
  bool clear_of_surface(const Vec3& a, const Vec3& b, const Vec3& c, double margin) const;

  //! contains() at the centre of every cell of a grid (x fastest, then y, then z), by one
  //! sweep of vertical lines: for a grid of one's own (ShellBand's).
  std::vector<bool> inside_centres(const VoxelGrid& grid) const;

  //! The cell's answer for p, a look-up; `outside` beyond the grid.
  Region region(const Vec3& p) const {
    const std::size_t i = grid_.index(p);
    return i < cells_.size() ? cells_[i] : Region::outside;
  }

  double cell_size() const { return grid_.cell; }
  const VoxelGrid& grid() const { return grid_; }
  //! A cell's answer, by its index in grid().
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
