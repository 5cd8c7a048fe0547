#include "dla/mesh/shell.h"

#include "dla/mesh/constraint.h"

#include <algorithm>
#include <cmath>

namespace dla {

namespace {

//! The voxels the triangles' boxes, widened by `thickness`, cover in all: the set-up's work.
double voxel_visits(const TriangleMesh& mesh, double thickness, double cell) {
  double visits = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 extent = a.cwiseMax(b).cwiseMax(c) - a.cwiseMin(b).cwiseMin(c);
    visits += ((extent.array() + 2.0 * thickness) / cell + 1.0).prod();
  }
  return visits;
}

}  // namespace

ShellBand::ShellBand(const TriangleMesh& mesh, const InsideTest& inside, Layer layer, double thickness, double cell) {
  // A thick shell over many triangles gets coarser voxels, so the set-up stays a few seconds
  // (10^9 visits) rather than growing with the cube of the thickness.
  constexpr double max_visits = 1e9;
  for (double visits = voxel_visits(mesh, thickness, cell); visits > max_visits;
       visits = voxel_visits(mesh, thickness, cell))
    cell *= 1.05 * std::cbrt(visits / max_visits);
  grid_ = VoxelGrid(bounding_box(mesh), thickness + cell, cell);
  const std::size_t nx = grid_.dims[0], ny = grid_.dims[1];
  // Which voxel centres lie within `thickness` of a triangle. Cheap bounds first: a centre
  // already near one, or farther than that from the triangle's plane or its bounding sphere,
  // needs no exact distance.
  std::vector<bool> near(grid_.size(), false);
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 normal = (b - a).cross(c - a).normalized();
    const Vec3 middle = (a + b + c) / 3.0;
    const double sphere = std::max({(a - middle).norm(), (b - middle).norm(), (c - middle).norm()}) + thickness;
    std::size_t from[3], to[3];
    for (int axis = 0; axis < 3; ++axis) {
      const double last = static_cast<double>(grid_.dims[axis] - 1);
      const double l = (std::min({a[axis], b[axis], c[axis]}) - thickness - grid_.origin[axis]) / grid_.cell - 0.5;
      const double h = (std::max({a[axis], b[axis], c[axis]}) + thickness - grid_.origin[axis]) / grid_.cell - 0.5;
      from[axis] = static_cast<std::size_t>(std::clamp(std::ceil(l), 0.0, last));
      to[axis] = static_cast<std::size_t>(std::clamp(std::floor(h), 0.0, last));
    }
    for (std::size_t k = from[2]; k <= to[2]; ++k)
      for (std::size_t j = from[1]; j <= to[1]; ++j)
        for (std::size_t i = from[0]; i <= to[0]; ++i) {
          const std::size_t v = (k * ny + j) * nx + i;
          if (near[v]) continue;
          const Vec3 center = grid_.center(i, j, k);
          if ((center - middle).squaredNorm() > sphere * sphere) continue;
          if (normal.allFinite() && std::abs(normal.dot(center - a)) > thickness) continue;
          if (distance_to_triangle(center, a, b, c) <= thickness) near[v] = true;
        }
  }
  const std::vector<bool> in = layer != Layer::both ? inside.inside_centres(grid_) : std::vector<bool>();
  const auto held = [&](std::size_t v) { return near[v] && (layer == Layer::both || in[v] == (layer == Layer::inside)); };
  for (std::size_t v = 0; v < near.size(); ++v)
    if (held(v)) voxels_.push_back(static_cast<std::uint32_t>(v));
  held_ = BrickBits(grid_, held);
}

Vec3 ShellBand::draw(Rng& rng) const {
  const std::size_t nx = grid_.dims[0], ny = grid_.dims[1];
  const std::size_t v = voxels_[std::min(voxels_.size() - 1, static_cast<std::size_t>(rng.uniform() * voxels_.size()))];
  const std::size_t i = v % nx, j = v / nx % ny, k = v / (nx * ny);
  // One draw a statement: the order of a call's arguments is the compiler's to choose (GCC and
  // clang differ); z, y, x is the order of the files dla3d has written.
  const double dz = rng.uniform(), dy = rng.uniform(), dx = rng.uniform();
  return grid_.origin + grid_.cell * Vec3(i + dx, j + dy, k + dz);
}

}  // namespace dla
