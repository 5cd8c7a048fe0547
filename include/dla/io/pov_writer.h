#pragma once
//! \file pov_writer.h
//! POV-Ray scene: PREFIX.pov (camera, lights, look) that includes PREFIX.inc (the geometry:
//! one sphere_sweep per strand, or a blob of spheres), PREFIX_mesh.inc (the constraint mesh),
//! and, for a frame of growth (DLA_Show < 1), PREFIX_growth.inc instead of PREFIX.inc. The
//! radius model, the radii, the colours and DLA_Show are switches at the top of the .pov. See
//! docs/formats.md and docs/look.md.

#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/mesh/mesh.h"
#include "dla/core/option_description.h"
#include "dla/core/words.h"

#include <string>
#include <string_view>

namespace dla {

//! What the structure is made of in the scene, and how it is lit (`--look branches|blob|glow`).
enum class PovStyle {
  branches,  //!< a sphere_sweep along each strand
  blob,      //!< metaballs: a blob of one sphere per particle (the thesis' "uncanny growth")
  glow,      //!< the branches, emissive on black, as bright as the colour value (a discharge's
             //!< current unless `color_by` says otherwise)
  spheres,   //!< a sphere of its radius at each particle: an aggregate's monomers
};
inline constexpr WordTable<PovStyle, 4> kPovStyleWords{
    "look",
    {{{PovStyle::branches, "branches"}, {PovStyle::blob, "blob"}, {PovStyle::glow, "glow"},
      {PovStyle::spheres, "spheres"}}}};
constexpr const auto& words_of(PovStyle) { return kPovStyleWords; }

struct PovOptions {
  PovStyle style = PovStyle::branches;
  Axis up = Axis::y;          //!< the scene's up direction (a scanned mesh is often z-up)
  std::string comment;        //!< one line written at the top of the .pov (the command, say)
  //! Also write PREFIX_tips.inc, DLA_Tip at every tip, which the .pov reads when DLA_ShowTips
  //! is on (the CLI: with tips in --formats). At 10^7 it takes a fifth of the scene's bytes,
  //! and measuring the tips' gaps a third of the look's time.
  bool tips = false;
  //! Which particles PREFIX_tips.inc calls DLA_Tip at: the tips (default), or every particle
  //! (`--instances all`: the thesis' object fill); `within` keeps those near the mesh.
  InstanceOptions instances;
};

//! Throws InvalidInput if the prefix's file name has a double quote, a backslash or a control
//! character: POV-Ray's #include cannot name such a file (spaces and other characters work).
void validate_pov_prefix(const std::string& prefix);

//! The scene's options a user sets, described once (option_description.h).
inline const OptionTable<PovOptions>& pov_option_table() {
  using O = PovOptions;
  static const OptionTable<O> table{
      word("look", &O::style, "Look",
           "POV-Ray: branches (sphere sweeps), blob (metaballs), glow (emissive branches on black, brightest "
           "where the colour value is highest) or spheres (one a particle: an aggregate's default)"),
      word("up", &O::up, "Output",
           "POV-Ray: the axis that is up in the picture; with a mesh, default: its longest side's"),
  };
  return table;
}

//! Writes PREFIX.pov, PREFIX.inc and PREFIX_growth.inc (and PREFIX_mesh.inc with a mesh,
//! PREFIX_tips.inc with `options.tips`); the .pov includes them by their file names, so they
//! stay side by side. The look gives the radius
//! model and range (switchable in the .pov: the .inc carries what every model needs) and the
//! colour; without one, the default look. With a `mesh` (the constraint), PREFIX_mesh.inc holds
//! it as a smooth mesh2, shown as glass and framed with the structure. A structure whose
//! spacing is far from 1, or that lies far from the origin, is written scaled and shifted (the
//! .pov says so). Throws IOError if a file cannot be written.
void write_pov(const Cluster& cluster, const std::string& prefix, const PovOptions& options = {},
               const TriangleMesh* mesh = nullptr, const Look* look = nullptr);

}  // namespace dla
