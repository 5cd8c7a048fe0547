#pragma once
//! \file pov_writer.h
//! POV-Ray scene: PREFIX.pov (camera, lights, look) that includes PREFIX.inc (the geometry,
//! one sphere_sweep per strand). See docs/formats.md.

#include "dla/cluster.h"
#include "dla/mesh.h"

#include <string>

namespace dla {

struct PovOptions {
  double base_radius = 0.5;   //!< radius at each strand's start, in spacings, > 0
  double tip_radius = 0.25;   //!< radius at each strand's tip, in spacings, > 0
  Axis up = Axis::y;          //!< the scene's up direction (a scanned mesh is often z-up)
  std::string comment;        //!< one line written at the top of the .pov (the command, say)
};

//! Throws InvalidInput for a radius that is not positive (POV-Ray renders a negative one wrong
//! without a word).
void validate(const PovOptions& options);

//! Writes PREFIX.pov and PREFIX.inc; the .pov includes the .inc by its file name, so the two
//! stay side by side. With a `mesh` (the constraint), the .inc also holds it as a mesh2,
//! shown in a glassy texture and framed with the structure. Throws IOError if a file cannot be
//! written.
void write_pov(const Cluster& cluster, const std::string& prefix, const PovOptions& options = {},
               const TriangleMesh* mesh = nullptr);

}  // namespace dla
