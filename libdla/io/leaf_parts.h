#pragma once
// The leaf's glTF objects renumbered to follow the glb writer's own, as JSON text to append to
// its arrays (leaf.h).

#include "dla/io/leaf.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace dla::detail {

//! How many of each object the glb has before the leaf's, and where the leaf's binary chunk
//! starts in its buffer.
struct GlbCounts {
  std::size_t accessors = 0, buffer_views = 0, meshes = 0, materials = 0;
  std::uint64_t binary_offset = 0;
};

//! Each array's added objects, comma-separated and without brackets, empty for none.
struct LeafParts {
  std::string accessors, buffer_views, meshes, materials, textures, images, samplers;
  std::vector<std::string> extensions_used, extensions_required;
  std::size_t mesh = 0;                                     //!< the leaf's mesh, renumbered
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();  //!< its node's, in the leaf's scene
};

//! read_leaf of a file's `bytes`, `path` only for messages.
Leaf parse_leaf(const std::string& bytes, const std::string& path);

//! Throws InvalidInput, naming `leaf`, for a JSON chunk whose objects are not as glTF has them.
LeafParts leaf_parts(const Leaf& leaf, const GlbCounts& before);

}  // namespace dla::detail
