#pragma once
//! \file solid_writers.h
//! The solid (solid.h) as files: binary STL and 3MF for printing, a glb and an OBJ coloured
//! like the tubes, and an OpenVDB volume for VFX. See docs/solid.md.

#include "dla/look/look.h"
#include "dla/look/solid.h"

#include <string>

namespace dla {

//! Writes PATH as binary STL: the solid's triangles with their normals, in millimetres (the
//! STL has no unit; slicers read millimetres). Throws IOError.
void write_stl(const Solid& solid, const std::string& path);

//! Writes PATH as 3MF (lib3mf) with the unit millimetre: one mesh object, one build item.
//! Throws IOError.
void write_3mf(const Solid& solid, const std::string& path);

//! Writes PATH as an OpenVDB file of three grids: `surface`, the level set (signed distance,
//! negative inside); `density`, a fog volume, 1 inside and falling to 0 across the band outside
//! the surface's inner half; `age`, the normalised attach order of the nearest particle, on the
//! band's voxels. Throws IOError.
void write_vdb(const Solid& solid, const Cluster& cluster, const Look& look, const std::string& path);

//! Writes PATH as binary glTF 2.0 or OBJ, as write_glb() and write_obj() do the tubes: each
//! vertex carries the colour and attributes of the particle nearest to it. Throws IOError.
void write_solid_glb(const Solid& solid, const Cluster& cluster, const Look& look, const std::string& path);
void write_solid_obj(const Solid& solid, const Cluster& cluster, const Look& look, const std::string& path);

}  // namespace dla
