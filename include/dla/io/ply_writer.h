#pragma once
//! \file ply_writer.h
//! Particles and branches as a PLY: vertices with their radius and attributes
//! (x y z radius age depth descendants order tip seed parent, and for a discharge that struck
//! current channel light) and edges (parent to child, as
//! `vertex1 vertex2`), which Blender, Houdini and MeshLab import; and instancing points as
//! PREFIX_tips.ply. See docs/formats.md.

#include "dla/core/options.h"
#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/core/words.h"

#include <string>
#include <string_view>

namespace dla {

//! How the PLY's elements are written (`--ply-format` on the CLI).
enum class PlyEncoding {
  binary,  //!< binary_little_endian: 46 bytes a particle, what Blender and Houdini write
  ascii,   //!< text: readable, about 80 bytes a particle, and three times slower to write
};
inline constexpr WordTable<PlyEncoding, 2> kPlyEncodingWords{
    "ply-format",
    {{{PlyEncoding::binary, "binary"}, {PlyEncoding::ascii, "ascii"}}}};
constexpr const auto& words_of(PlyEncoding) { return kPlyEncodingWords; }

//! Throws IOError if the file cannot be written; a file that fails part way is removed, and a
//! file of that name already there is left as it was.
void write_ply(const Cluster& cluster, const Look& look, const std::string& path,
               PlyEncoding encoding = PlyEncoding::binary);

//! The same with the default look (the taper radius model).
void write_ply(const Cluster& cluster, const std::string& path, PlyEncoding encoding = PlyEncoding::binary);

//! Instancing points (instances.h) as a PLY of vertices `x y z nx ny nz pscale age id`: N is
//! the direction, pscale the scale, id the particle's index; Houdini and Blender read these
//! names as they are. Streamed: about 10 bytes a point beside the structure. Throws
//! InvalidInput for bad options and IOError.
void write_instances_ply(const Cluster& cluster, const Attributes& attributes, const InstanceOptions& options,
                         const std::string& path, PlyEncoding encoding = PlyEncoding::binary);

}  // namespace dla
