#pragma once
//! \file mesh_writers.h
//! The structure as a tube mesh (tubes.h) for game engines and 3D tools: binary glTF 2.0
//! (.glb) and Wavefront OBJ. Both stream the tubes, one strand at a time. See docs/look.md.

#include "dla/io/leaf.h"
#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/mesh/mesh.h"

#include <cstddef>
#include <string>
#include <vector>

namespace dla {

//! The most levels of detail write_glb writes.
inline constexpr int kMaxLods = 8;

struct GlbOptions {
  //! Levels of detail written beside the glb, in [0, kMaxLods]: for PATH = PREFIX.glb,
  //! PREFIX_lod1.glb, PREFIX_lod2.glb, ..., each with about half the triangles of the one
  //! before. The branches of fewer particles than a threshold that grows with the level are
  //! left out (twigs first), then each tube is simplified by meshoptimizer within a quarter of
  //! its thinnest radius. They carry no leaves.
  int lods = 0;
  //! A leaf (read_leaf) placed at each of the instancing points `instances` picks, or none:
  //! one node a point under a node named `leaves`, the leaf's +Y along the point's direction,
  //! scaled by the point's scale (a leaf within a unit sphere about its origin overlaps no other).
  const Leaf* leaf = nullptr;
  InstanceOptions instances;
};

//! What write_glb wrote besides the tubes.
struct GlbWritten {
  std::vector<std::size_t> lod_triangles;  //!< each level of detail's triangles, from level 1
  std::size_t leaves = 0;                  //!< leaf nodes: one an instancing point, with a leaf
};

//! Writes PATH as binary glTF 2.0: one mesh of one triangle primitive with POSITION, NORMAL,
//! TANGENT, TEXCOORD_0, COLOR_0 (with a colour attribute) and the attributes as `_AGE`,
//! `_DEPTH`, `_DESCENDANTS`, `_ORDER` (Strahler), `_SEED` and `_RADIUS` (floats, the vertex's
//! particle's); with a leaf, the leaves. A structure with no branch gives a valid file with an
//! empty scene. Throws InvalidInput for levels out of range and for instancing points the look
//! cannot give (InstanceSelection), IOError.
GlbWritten write_glb(const Cluster& cluster, const Look& look, const std::string& path, const GlbOptions& options = {});

//! Writes PATH as OBJ: `v x y z [r g b]`, `vn`, `vt u 1-v`, and `f v/vt/vn` triangles, one
//! object. Throws IOError.
void write_obj(const Cluster& cluster, const Look& look, const std::string& path);

//! Writes a mesh as binary STL (its header does not begin with "solid"), as `dla3d convert`
//! does. Throws IOError.
void write_stl(const TriangleMesh& mesh, const std::string& path);

}  // namespace dla
