#pragma once
//! \file radius_model.h
//! How thick each branch is: a radius per particle from its attributes, between a tip radius
//! and a base radius. The words are the CLI's (`--radius taper|pipe|boundary|seed-distance|
//! uniform`). See docs/look.md.

#include "dla/look/attributes.h"
#include "dla/core/option_description.h"
#include "dla/core/words.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

namespace dla {

enum class RadiusModel {
  taper,          //!< base at each strand's start, tip at its end (Bourke)
  pipe,           //!< the pipe model: tip · flow^(1/e), up to base (da Vinci, Murray); the flow
                  //!< is the subtree's particles, or a discharge's current (Attributes::flow)
  boundary,       //!< thick far from the mesh's surface, fine near it (the thesis' wire fill)
  seed_distance,  //!< thick at the seeds, finer the farther from them
  uniform,        //!< the base radius everywhere
  particle,       //!< each particle's own radius (Cluster::radii), from a model that sizes them:
                  //!< an aggregate's monomers
};
inline constexpr WordTable<RadiusModel, 6> kRadiusModelWords{
    "radius model",
    {{{RadiusModel::taper, "taper"}, {RadiusModel::pipe, "pipe"}, {RadiusModel::boundary, "boundary"},
      {RadiusModel::seed_distance, "seed-distance"}, {RadiusModel::uniform, "uniform"},
      {RadiusModel::particle, "particle"}}}};
constexpr const auto& words_of(RadiusModel) { return kRadiusModelWords; }

//! The range of branch radii, in spacings: beyond it a branch vanishes or swallows the scene.
inline constexpr double kMinBranchRadius = 1e-3, kMaxBranchRadius = 1e3;

struct RadiusOptions {
  RadiusModel model = RadiusModel::taper;
  double tip_radius = 0.25;    //!< the finest radius, in spacings, in [1e-3, 1e3]
  double base_radius = 0.5;    //!< the thickest radius, in spacings, in [1e-3, 1e3]
  double pipe_exponent = 2.0;  //!< pipe: e, in [1, 10]; 2 keeps the cross-section's area, about
                               //!< 3 is Murray's law
};

//! The branch thickness, described once (option_description.h).
inline const OptionTable<RadiusOptions>& radius_option_table() {
  using O = RadiusOptions;
  static const OptionTable<O> table{
      word("radius", &O::model, "Look",
           "branch thickness: taper, pipe, boundary (needs a mesh), seed-distance, uniform or particle (each "
           "particle's own: an aggregate's monomers, its default); with a mesh, default pipe"),
      real("base_radius", &O::base_radius, closed(kMinBranchRadius, kMaxBranchRadius), "spacings", "Look",
           "the thickest branch's radius; with a mesh, default 3"),
      real("tip_radius", &O::tip_radius, closed(kMinBranchRadius, kMaxBranchRadius), "spacings", "Look",
           "the finest branch's radius; with a mesh, default 0.05"),
      real("pipe_exponent", &O::pipe_exponent, closed(1, 10), "", "Look",
           "pipe: e in r = tip * (descendants + 1)^(1/e); 2 keeps the area, 3 is Murray's law"),
  };
  return table;
}

inline void validate(const RadiusOptions& options) { require_in_ranges(radius_option_table(), options); }

//! Where particle i lies between the tip radius (0) and the base radius (1) under the model.
//! The largest distances of the structure (Attributes::boundary_reach, seed_reach) map to the
//! thickest and the finest branch.
inline double radius_fraction(const RadiusOptions& options, const Cluster& cluster, const Attributes& a,
                              std::size_t i) {
  switch (options.model) {
    case RadiusModel::taper: return a.taper(i);
    case RadiusModel::pipe: {
      // tip · flow^(1/e), capped at the base, as a fraction of the range.
      const double range = options.base_radius - options.tip_radius;
      if (range <= 0.0) return 1.0;
      const double r = options.tip_radius * std::pow(static_cast<double>(a.flow(i)), 1.0 / options.pipe_exponent);
      return std::min(1.0, (r - options.tip_radius) / range);
    }
    case RadiusModel::boundary: return a.boundary_reach > 0.0 ? a.boundary_distance[i] / a.boundary_reach : 1.0;
    case RadiusModel::seed_distance:
      return a.seed_reach > 0.0 ? 1.0 - a.seed_distance(cluster.particles[i].position) / a.seed_reach : 1.0;
    case RadiusModel::uniform:
    case RadiusModel::particle: return 1.0;  // particle: branch_radius() takes the particle's own
  }
  return 1.0;
}

//! Throws InvalidInput for bad options, and for `boundary` without a mesh distance.
inline void validate(const RadiusOptions& options, const Attributes& attributes) {
  validate(options);
  if (options.model == RadiusModel::boundary && attributes.boundary_distance.empty())
    throw InvalidInput("the boundary radius model needs a constraint mesh (`stl`)");
}

//! Particle i's branch radius, in spacings (a float holds it at any spacing: multiply by the
//! cluster's spacing for scene units). Computed when asked, as it is cheap, rather than stored.
//! The options must have passed validate(options, attributes).
inline float branch_radius(const RadiusOptions& options, const Cluster& cluster, const Attributes& attributes,
                           std::size_t i) {
  if (options.model == RadiusModel::particle) return static_cast<float>(cluster.radii[i] / cluster.spacing);
  const double f = radius_fraction(options, cluster, attributes, i);
  return static_cast<float>(options.tip_radius + (options.base_radius - options.tip_radius) * f);
}

//! The branch radius of every particle, in spacings, for the tube meshes. Throws as validate.
inline std::vector<float> branch_radii(const RadiusOptions& options, const Cluster& cluster,
                                       const Attributes& attributes) {
  validate(options, attributes);
  if (options.model == RadiusModel::particle && cluster.radii.size() != cluster.particles.size())
    throw InvalidInput("the particle radius model draws each particle's own radius: only `aggregate` sizes them");
  std::vector<float> radii(attributes.size());
  for (std::size_t i = 0; i < radii.size(); ++i) radii[i] = branch_radius(options, cluster, attributes, i);
  return radii;
}

}  // namespace dla
