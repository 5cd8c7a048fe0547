#include "dla/mesh/shapes.h"

#include <cmath>

namespace dla {

namespace {

constexpr double kPi = 3.141592653589793238462643383279502884;

std::uint32_t add(TriangleMesh& mesh, const Vec3& v) {
  mesh.vertices.push_back(v);
  return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
}

}  // namespace

TriangleMesh make_box(const Vec3& min, const Vec3& max) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) add(mesh, {i & 1 ? max.x() : min.x(), i & 2 ? max.y() : min.y(), i & 4 ? max.z() : min.z()});
  // Corner i has x from bit 0, y from bit 1, z from bit 2; each face is two triangles.
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

TriangleMesh make_sphere(const Vec3& center, double radius, int rings, int segments) {
  TriangleMesh mesh;
  const std::uint32_t north = add(mesh, center + Vec3(0, 0, radius));
  for (int r = 1; r < rings; ++r) {
    const double theta = kPi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * kPi * s / segments;
      add(mesh, center + radius * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  const std::uint32_t south = add(mesh, center - Vec3(0, 0, radius));
  const auto at = [&](int ring, int s) { return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({north, at(1, s), at(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      mesh.triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      mesh.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
    mesh.triangles.push_back({south, at(rings - 1, s + 1), at(rings - 1, s)});
  }
  return mesh;
}

TriangleMesh make_open_can(const Vec3& base_center, double radius, double height, int segments) {
  TriangleMesh mesh;
  const std::uint32_t middle = add(mesh, base_center);
  for (int level = 0; level < 2; ++level)
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * kPi * s / segments;
      add(mesh, base_center + Vec3(radius * std::cos(phi), radius * std::sin(phi), level * height));
    }
  const auto at = [&](int level, int s) { return static_cast<std::uint32_t>(1 + level * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({middle, at(0, s + 1), at(0, s)});  // the base faces down
    mesh.triangles.push_back({at(0, s), at(0, s + 1), at(1, s + 1)});
    mesh.triangles.push_back({at(0, s), at(1, s + 1), at(1, s)});
  }
  return mesh;
}

}  // namespace dla
