#pragma once
//! \file surface_distance.h
//! Distance from points to a triangle mesh's surface, by CGAL's AABB tree
//! (libdla/surface_distance.cpp): for the attributes and radius models that depend on the
//! distance to a constraint mesh.

#include "dla/mesh/mesh.h"

#include <memory>

namespace dla {

class SurfaceDistance {
 public:
  //! Builds the tree of `mesh`'s triangles. Throws InvalidInput for a mesh with no triangle.
  explicit SurfaceDistance(const TriangleMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;

  //! The point of the surface closest to p. Safe to call from several threads at once.
  Vec3 closest_point(const Vec3& p) const;
  //! Distance from p to the surface (unsigned).
  double distance(const Vec3& p) const { return (closest_point(p) - p).norm(); }

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace dla
