#pragma once
//! \file surface_intersector.h
//! First hit of a segment with a triangle mesh, by Embree (libdla/mesh/surface_intersector.cpp).
//! Used when a walker is about to stick, never on a walk step.

#include "dla/mesh/mesh.h"

#include <memory>

namespace dla {

class SurfaceIntersector {
 public:
  //! Builds Embree's robust scene of `mesh` on one thread. Throws GrowthError if Embree fails.
  explicit SurfaceIntersector(const TriangleMesh& mesh);
  ~SurfaceIntersector();
  SurfaceIntersector(SurfaceIntersector&&) noexcept;
  SurfaceIntersector& operator=(SurfaceIntersector&&) noexcept;

  //! The smallest t in [t_min, t_max] with from + t (to - from) on a triangle, or -1 if none.
  //! Safe to call from several threads at once.
  double first_hit(const Vec3& from, const Vec3& to, double t_min, double t_max) const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace dla
