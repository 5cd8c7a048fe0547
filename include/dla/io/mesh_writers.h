#pragma once
//! \file mesh_writers.h
//! The structure as a tube mesh (tubes.h) for game engines and 3D tools: binary glTF 2.0
//! (.glb) and Wavefront OBJ. Both stream the tubes, one strand at a time. See docs/look.md.

#include "dla/look/look.h"

#include <cstddef>
#include <string>
#include <vector>

namespace dla {

//! Writes PATH as binary glTF 2.0: one mesh of one triangle primitive with POSITION, NORMAL,
//! TANGENT, TEXCOORD_0, COLOR_0 (with a colour attribute) and the attributes as `_AGE`, `_DEPTH`, `_DESCENDANTS`,
//! `_ORDER` (Strahler), `_SEED` and `_RADIUS` (floats, the vertex's particle's). A structure
//! with no branch gives a valid file with an empty scene. Throws IOError.
void write_glb(const Cluster& cluster, const Look& look, const std::string& path);

//! The most levels of detail write_glb_lods writes.
inline constexpr int kMaxLods = 8;

//! Writes `levels` levels of detail of the glb (0-kMaxLods) as PREFIX_lod1.glb, PREFIX_lod2.glb,
//! ..., each with about half the triangles of the one before: the branches of fewer particles
//! than a threshold that grows with the level left out (twigs first), then each tube simplified
//! by meshoptimizer within a quarter of its thinnest radius. Returns each level's triangles.
//! Throws InvalidInput for a count out of range, IOError.
std::vector<std::size_t> write_glb_lods(const Cluster& cluster, const Look& look, int levels,
                                        const std::string& prefix);

//! Writes PATH as OBJ: `v x y z [r g b]`, `vn`, `vt u 1-v`, and `f v/vt/vn` triangles, one object. Throws
//! IOError.
void write_obj(const Cluster& cluster, const Look& look, const std::string& path);

}  // namespace dla
