#pragma once
//! \file leaf.h
//! A leaf (or a flower, a thorn, any object) read from a binary glTF, for the glb writer to
//! place at every instancing point (instances.h): one glTF node a point, each referencing the
//! one leaf mesh, so Blender and game engines import the tree with its leaves from one file.
//! See docs/look.md.

#include <string>

namespace dla {

//! A leaf file's two chunks, checked by read_leaf: the glb writer carries its meshes,
//! materials, textures and images over, renumbered, and its binary chunk after its own.
struct Leaf {
  std::string path;    //!< where it was read, for messages
  std::string json;    //!< the JSON chunk
  std::string binary;  //!< the binary chunk, padded to 4 bytes (empty if it has none)
};

//! Reads PATH, a binary glTF 2.0 with at least one mesh whose data is all inside it (no
//! outside or data: URI, no Draco or meshopt compression). The leaf is the first mesh that its
//! default scene shows, with that node's transform; its +Y axis (glTF's up) is laid along each
//! point's direction. Throws InvalidInput, with one line naming `leaf`, for a file that is not
//! such a glTF; IOError for one that cannot be read.
Leaf read_leaf(const std::string& path);

}  // namespace dla
