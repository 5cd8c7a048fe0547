#pragma once
//! \file instances.h
//! Instancing points, the thesis' object fill: where copies of an object (a leaf, a flower, a
//! crystal) go, which way they point and how large they may be without overlapping. Written
//! as PREFIX_tips.ply for Houdini's Copy to Points and Blender's geometry nodes, and called as
//! DLA_Tip in the POV-Ray scene. See docs/look.md.

#include "dla/attributes.h"
#include "dla/nearest_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace dla {

//! Which particles become instancing points (`--instances tips|all`).
enum class InstanceSet {
  tips,  //!< the particles with no child
  all,   //!< every particle
};

inline std::string_view to_string(InstanceSet set) { return set == InstanceSet::tips ? "tips" : "all"; }

inline InstanceSet parse_instance_set(std::string_view word) {
  constexpr InstanceSet values[] = {InstanceSet::tips, InstanceSet::all};
  return detail::parse_word(word, values, "instance set");
}

struct InstanceOptions {
  InstanceSet set = InstanceSet::tips;
  //! Keep only points within this distance of the mesh's surface, in spacings, >= 0
  //! (`--tips-within`: the thesis' leaves near the boundary); infinity keeps all.
  double within = std::numeric_limits<double>::infinity();
};

inline void validate(const InstanceOptions& options) {
  if (!(options.within >= 0.0)) throw InvalidInput("tips within " + detail::format_number(options.within) + " is not >= 0");
}

struct Instance {
  Vec3 position;
  Vec3 direction;          //!< unit: from the parent to the particle (a seed: +z)
  double scale;            //!< half the distance to the nearest other instance, and no more
                           //!< than the distance to the mesh's surface: unit-radius copies
                           //!< scaled by it never overlap nor cross the mesh
  std::int32_t particle;   //!< index in Cluster::particles
};

//! Some particles' positions by index, for NearestPoints: 4 bytes a point, not 24.
struct ParticleSubset {
  const std::vector<Particle>* particles;
  const std::vector<std::int32_t>* ids;
  std::size_t size() const { return ids->size(); }
  const Vec3& operator[](std::size_t i) const { return (*particles)[static_cast<std::size_t>((*ids)[i])].position; }
};

//! The particles that become instancing points, in attach order. Throws InvalidInput for
//! `within` without the distance to a mesh.
inline std::vector<std::int32_t> instance_particles(const Cluster& cluster, const Attributes& attributes,
                                                    const InstanceOptions& options) {
  validate(options);
  const bool near_boundary = options.within != std::numeric_limits<double>::infinity();
  if (near_boundary && attributes.boundary_distance.empty())
    throw InvalidInput("--tips-within measures to a constraint mesh (--stl)");
  const double within = options.within * cluster.spacing;
  std::vector<std::int32_t> ids;
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    if (options.set == InstanceSet::tips && !attributes.tip(i)) continue;
    if (near_boundary && attributes.boundary_distance[i] > within) continue;
    ids.push_back(static_cast<std::int32_t>(i));
  }
  return ids;
}

//! Calls visit(const Instance&) for the instancing point of each particle in `ids` (from
//! instance_particles), in order, holding none of them: about 10 bytes a point.
template <class Visit>
void for_each_instance(const Cluster& cluster, const Attributes& attributes, const std::vector<std::int32_t>& ids,
                       Visit&& visit) {
  const ParticleSubset points{&cluster.particles, &ids};
  const NearestPoints<ParticleSubset> nearest(points);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const auto i = static_cast<std::size_t>(ids[k]);
    const Particle& p = cluster.particles[i];
    Vec3 direction = Vec3::UnitZ();
    if (p.parent >= 0) direction = (p.position - cluster.particles[static_cast<std::size_t>(p.parent)].position).normalized();
    double scale = 0.5 * nearest.distance_to_other(k);
    if (!std::isfinite(scale)) scale = cluster.spacing;  // a lone instance: as large as a particle
    if (!attributes.boundary_distance.empty()) scale = std::min(scale, static_cast<double>(attributes.boundary_distance[i]));
    visit(static_cast<const Instance&>(Instance{p.position, direction, scale, ids[k]}));
  }
}

//! The instancing points of a structure, all at once.
inline std::vector<Instance> instancing_points(const Cluster& cluster, const Attributes& attributes,
                                               const InstanceOptions& options) {
  std::vector<Instance> instances;
  for_each_instance(cluster, attributes, instance_particles(cluster, attributes, options),
                    [&](const Instance& instance) { instances.push_back(instance); });
  return instances;
}

}  // namespace dla
