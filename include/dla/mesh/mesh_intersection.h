#pragma once
//! \file mesh_intersection.h
//! Where two triangle meshes' surfaces meet, by CGAL's AABB tree and exact predicates
//! (libdla/mesh/mesh_intersection.cpp): for seeds where one object enters another (`--seed-mesh`).

#include "dla/mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace dla {

//! The pieces two surfaces share. Each names the triangle of the first mesh it lies on.
struct SurfaceIntersection {
  struct Segment {
    Vec3 a, b;
    std::uint32_t triangle;
  };
  struct Patch {  //!< where two triangles lie in one plane and overlap: a piece of area
    Vec3 a, b, c;
    std::uint32_t triangle;
  };
  std::vector<Segment> segments;  //!< the curves where the surfaces cross, piece by piece
  std::vector<Patch> patches;
};

//! What `first` and `second` share, triangle by triangle: no mesh need be closed, manifold or
//! free of self-intersections. Degenerate triangles of `second` are skipped.
SurfaceIntersection intersect_surfaces(const TriangleMesh& first, const TriangleMesh& second);

}  // namespace dla
