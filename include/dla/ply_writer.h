#pragma once
//! \file ply_writer.h
//! Particles and branches as an ASCII PLY: vertices (x y z parent seed) and edges (child to
//! parent), which Blender, Houdini and MeshLab import.

#include "dla/cluster.h"

#include <string>

namespace dla {

//! Throws IOError if the file cannot be written.
void write_ply(const Cluster& cluster, const std::string& path);

}  // namespace dla
