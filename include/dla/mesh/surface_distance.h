#pragma once
//! \file surface_distance.h
//! Closest points of a triangle mesh's surface, by Embree's point queries on its bounding volume
//! hierarchy (libdla/mesh/surface_distance.cpp): for the attributes and radius models that depend on
//! the distance to a constraint mesh, a shell's exact test and the vessels of space colonization.

#include "dla/mesh/mesh.h"

#include <cstdint>
#include <limits>
#include <memory>

namespace dla {

class SurfaceDistance {
 public:
  //! Builds Embree's hierarchy of `mesh`'s triangles. Throws InvalidInput for a mesh with no
  //! triangle and GrowthError if Embree fails.
  explicit SurfaceDistance(const TriangleMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;

  //! A point of the surface and the triangle it lies on.
  struct Closest {
    Vec3 point;
    std::uint32_t triangle;
  };
  static constexpr std::uint32_t kNoHint = std::numeric_limits<std::uint32_t>::max();

  //! The point of the surface closest to p: exactly that of a scan of every triangle in double
  //! precision (on a tie, the triangle listed first). `hint`, a triangle that is likely near
  //! (a neighbour's closest), only speeds the search. Safe to call from several threads at once.
  Closest closest(const Vec3& p, std::uint32_t hint = kNoHint) const;
  //! The point of triangle t closest to p: closest(p) itself, bit for bit, where t is the
  //! closest triangle. For closest triangles found before (attributes.h).
  Closest on_triangle(const Vec3& p, std::uint32_t t) const;
  Vec3 closest_point(const Vec3& p) const { return closest(p).point; }
  //! Distance from p to the surface (unsigned).
  double distance(const Vec3& p) const { return (closest_point(p) - p).norm(); }

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

//! The point of triangle (a, b, c) closest to p.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace dla
