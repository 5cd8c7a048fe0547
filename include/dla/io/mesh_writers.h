#pragma once
//! \file mesh_writers.h
//! The structure as a tube mesh (tubes.h) for game engines and 3D tools: binary glTF 2.0
//! (.glb) and Wavefront OBJ. Both stream the tubes, one strand at a time. See docs/look.md.

#include "dla/look/look.h"

#include <string>

namespace dla {

//! Writes PATH as binary glTF 2.0: one mesh of one triangle primitive with POSITION, NORMAL,
//! COLOR_0 (with a colour attribute) and the attributes as `_AGE`, `_DEPTH`, `_DESCENDANTS`,
//! `_ORDER` (Strahler), `_SEED` and `_RADIUS` (floats, the vertex's particle's). A structure
//! with no branch gives a valid file with an empty scene. Throws IOError.
void write_glb(const Cluster& cluster, const Look& look, const std::string& path);

//! Writes PATH as OBJ: `v x y z [r g b]`, `vn`, and `f v//vn` triangles, one object. Throws
//! IOError.
void write_obj(const Cluster& cluster, const Look& look, const std::string& path);

}  // namespace dla
