#pragma once
//! \file pov_writer.h
//! POV-Ray scene: PREFIX.pov (camera, lights, look) that includes PREFIX.inc (the geometry,
//! one sphere_sweep per strand). See docs/formats.md.

#include "dla/cluster.h"
#include "dla/mesh.h"

#include <string>

namespace dla {

//! The range of branch radii, in spacings: beyond it a branch vanishes or swallows the scene.
inline constexpr double kMinBranchRadius = 1e-3, kMaxBranchRadius = 1e3;

struct PovOptions {
  double base_radius = 0.5;   //!< radius at each strand's start, in spacings, in [1e-3, 1e3]
  double tip_radius = 0.25;   //!< radius at each strand's tip, in spacings, in [1e-3, 1e3]
  Axis up = Axis::y;          //!< the scene's up direction (a scanned mesh is often z-up)
  std::string comment;        //!< one line written at the top of the .pov (the command, say)
};

//! Throws InvalidInput for a radius out of range (POV-Ray renders a negative one wrong without a
//! word).
void validate(const PovOptions& options);

//! Throws InvalidInput if the prefix's file name has a double quote, a backslash or a control
//! character: POV-Ray's #include cannot name such a file (spaces and other characters work).
void validate_pov_prefix(const std::string& prefix);

//! Writes PREFIX.pov and PREFIX.inc; the .pov includes the .inc by its file name, so the two
//! stay side by side. With a `mesh` (the constraint), the .inc also holds it as a mesh2,
//! shown in a glassy texture and framed with the structure. A structure whose spacing is far
//! from 1, or that lies far from the origin, is written scaled and shifted (the .pov says so).
//! Throws IOError if a file cannot be written.
void write_pov(const Cluster& cluster, const std::string& prefix, const PovOptions& options = {},
               const TriangleMesh* mesh = nullptr);

}  // namespace dla
