#pragma once
//! \file look.h
//! How a grown structure looks in every file: its attributes, the radius model's radii, the
//! colour and the tube mesh's resolution, computed once after growth and shared by the
//! writers. See docs/look.md.

#include "dla/look/attributes.h"
#include "dla/look/color_map.h"
#include "dla/look/radius_model.h"
#include "dla/look/tubes.h"

namespace dla {

struct LookOptions {
  RadiusOptions radius;               //!< branch thickness
  ColorBy color_by = ColorBy::none;   //!< vertex colours of the tube meshes, textures in POV-Ray
  TubeOptions tubes;                  //!< the glTF and OBJ tube meshes
};

//! The look's options, described once (option_description.h): the radii, the colour, the tubes.
inline const OptionTable<LookOptions>& look_option_table() {
  static const OptionTable<LookOptions> table = [] {
    OptionTable<LookOptions> rows = nested(radius_option_table(), &LookOptions::radius);
    rows.push_back(word("color_by", &LookOptions::color_by, "Look",
                        "colour the glb, obj, svg and POV-Ray scene by none, age, depth, seed, distance (to the "
                        "mesh, or to the seeds) or current (what flows through it: a discharge's main channel "
                        "brightest)"));
    for (DescribedOption<LookOptions>& row : nested(tube_option_table(), &LookOptions::tubes)) rows.push_back(row);
    return rows;
  }();
  return table;
}

inline void validate(const LookOptions& options) { require_in_ranges(look_option_table(), options); }

//! A structure's look: its options and what they give for each particle.
struct Look {
  LookOptions options;
  Attributes attributes;
  //! Every particle's branch radius, in spacings: the tube meshes', the solid's, the viewer's.
  std::vector<float> radii;

  //! Particle i's branch radius in scene units.
  double radius(const Cluster& cluster, std::size_t i) const { return static_cast<double>(radii[i]) * cluster.spacing; }
};

//! Computes the attributes and, from them, the radii, once for every writer. Throws
//! InvalidInput for bad options, or a model that needs a mesh (`boundary`) without
//! `sources.surface`.
inline Look make_look(const Cluster& cluster, const LookOptions& options, const AttributeOptions& sources = {}) {
  validate(options);
  Look look;
  look.options = options;
  look.attributes = compute_attributes(cluster, sources);
  look.radii = branch_radii(options.radius, cluster, look.attributes);
  return look;
}

}  // namespace dla
