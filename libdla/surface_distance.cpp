// CGAL's AABB tree behind SurfaceDistance, kept to this one translation unit (CGAL's headers
// take tens of seconds to compile).

#include "dla/mesh/surface_distance.h"

#include "dla/core/errors.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

namespace dla {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

struct SurfaceDistance::Tree {
  Triangles triangles;
  AabbTree tree;
};

SurfaceDistance::SurfaceDistance(const TriangleMesh& mesh) : tree_(std::make_unique<Tree>()) {
  if (mesh.triangles.empty()) throw InvalidInput("the mesh has no triangle to measure distances to");
  tree_->triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    tree_->triangles.emplace_back(point(mesh.vertices[t[0]]), point(mesh.vertices[t[1]]), point(mesh.vertices[t[2]]));
  tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
  tree_->tree.build();
  // Built now, on this thread: queries from several threads then only read the tree.
  tree_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

Vec3 SurfaceDistance::closest_point(const Vec3& p) const {
  const Kernel::Point_3 q = tree_->tree.closest_point(point(p));
  return {q.x(), q.y(), q.z()};
}

}  // namespace dla
