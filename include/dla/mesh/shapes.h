#pragma once
//! \file shapes.h
//! Simple meshes made in code, triangles facing out: for examples, tests and quick vessels.

#include "dla/mesh/mesh.h"

namespace dla {

//! A closed box.
TriangleMesh make_box(const Vec3& min, const Vec3& max);

//! A closed UV sphere with `rings` bands of latitude (>= 2) and `segments` of longitude (>= 3).
TriangleMesh make_sphere(const Vec3& center, double radius, int rings = 24, int segments = 48);

//! A can: a cylinder about the z axis standing on `base_center`, closed at the base, open at
//! the top (Bourke's figure 4). `segments` >= 3 round the circle.
TriangleMesh make_open_can(const Vec3& base_center, double radius, double height, int segments = 64);

}  // namespace dla
