#pragma once
//! \file ply_writer.h
//! Particles and branches as a PLY: vertices (x y z parent seed) and edges (parent to child,
//! as `vertex1 vertex2`), which Blender, Houdini and MeshLab import. See docs/formats.md.

#include "dla/cluster.h"

#include <string>

namespace dla {

//! How the PLY's elements are written (`--binary` on the CLI).
enum class PlyEncoding {
  ascii,   //!< text: readable, about 60 bytes a particle
  binary,  //!< binary_little_endian: 28 bytes a particle, and about ten times faster to write
};

//! Throws IOError if the file cannot be written; a file that fails part way is removed, and a
//! file of that name already there is left as it was.
void write_ply(const Cluster& cluster, const std::string& path, PlyEncoding encoding = PlyEncoding::ascii);

}  // namespace dla
