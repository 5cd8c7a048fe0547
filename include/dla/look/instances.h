#pragma once
//! \file instances.h
//! Instancing points, the thesis' object fill: where copies of an object (a leaf, a flower, a
//! crystal) go, which way they point and how large they may be without overlapping. Written
//! as PREFIX_tips.ply for Houdini's Copy to Points and Blender's geometry nodes, and called as
//! DLA_Tip in the POV-Ray scene. See docs/look.md.

#include "dla/look/attributes.h"
#include "dla/index/nearest_points.h"
#include "dla/mesh/paint.h"
#include "dla/core/option_description.h"
#include "dla/core/words.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace dla {

//! Which particles become instancing points (`--instances tips|all`).
enum class InstanceSet {
  tips,  //!< the particles with no child
  all,   //!< every particle
};
inline constexpr WordTable<InstanceSet, 2> kInstanceSetWords{
    "instance set",
    {{{InstanceSet::tips, "tips"}, {InstanceSet::all, "all"}}}};
constexpr const auto& words_of(InstanceSet) { return kInstanceSetWords; }

struct InstanceOptions {
  InstanceSet set = InstanceSet::tips;
  //! Keep only points within this distance of the mesh's surface, in spacings, >= 0
  //! (`--tips-within`: the thesis' leaves near the boundary); infinity keeps all.
  double within = std::numeric_limits<double>::infinity();
  //! Keep one point in this many of those the set and `within` pick, in attach order: the
  //! first, the (every + 1)th, and so on (`--tips-every`: sparser leaves), in [1, 1000000]; 1
  //! keeps all.
  int every = 1;
  //! Leave out the points whose closest point of the mesh's surface is painted this colour
  //! (`--tips-exclude-paint`: no flowers where the artist painted, the thesis' figure 32).
  std::optional<Paint> exclude_paint;
};

//! Whether `options` pick every tip and nothing else: the points whose gaps the attributes
//! keep (AttributeOptions::tip_gaps). Any other selection measures its own.
inline bool picks_every_tip(const InstanceOptions& options) {
  return options.set == InstanceSet::tips && options.within == std::numeric_limits<double>::infinity() &&
         options.every == 1 && !options.exclude_paint;
}

//! Which particles are instancing points, described once (option_description.h); the paint
//! that leaves some out is the front ends' (a colour and a tolerance).
inline const OptionTable<InstanceOptions>& instance_option_table() {
  using O = InstanceOptions;
  static const OptionTable<O> table{
      word("instances", &O::set, "Look",
           "tips: which particles get instancing points and the scene's DLA_Tip, tips or all (object fill)"),
      real("tips_within", &O::within, closed(0, 1e9), "spacings", "Look",
           "tips: only points within this of the mesh's surface",
           SpecialValue{std::numeric_limits<double>::infinity(), "all of them"}),
      integer("tips_every", &O::every, closed(1, 1e6), "", "Look",
              "tips: keep one point in K, in attach order (sparser leaves)"),
  };
  return table;
}

inline void validate(const InstanceOptions& options) { require_in_ranges(instance_option_table(), options); }

struct Instance {
  Vec3 position;
  Vec3 direction;          //!< unit: from the parent to the particle (a seed: +z)
  double scale;            //!< half the distance to the nearest other instance (less its
                           //!< float rounding: about 1e-6 of the structure's size), and no more
                           //!< than the distance to the mesh's surface: unit-radius copies
                           //!< scaled by it never overlap nor cross the mesh
  std::int32_t particle;   //!< index in Cluster::particles
};

//! Which particles become instancing points: selected(i) says whether particle i does.
//! Throws InvalidInput for `within` without the distance to a mesh, or `exclude_paint`
//! without the paint (AttributeOptions::paint).
class InstanceSelection {
 public:
  InstanceSelection(const Cluster& cluster, const Attributes& attributes, const InstanceOptions& options)
      : attributes_(attributes), set_(options.set), within_(options.within * cluster.spacing),
        near_boundary_(options.within != std::numeric_limits<double>::infinity()),
        unpainted_(options.exclude_paint.has_value()) {
    validate(options);
    if (near_boundary_ && attributes.boundary_distance.empty())
      throw InvalidInput("`tips_within` measures to a constraint mesh (`stl`)");
    if (unpainted_ && attributes.on_paint.empty())
      throw InvalidInput("`tips_exclude_paint` reads the paint of a constraint mesh (`stl`)");
    if (options.every == 1) return;
    // Thinning needs each point's rank among those picked: kept once, read from any thread.
    thinned_.resize(cluster.particles.size());
    std::size_t rank = 0;
    for (std::size_t i = 0; i < thinned_.size(); ++i)
      if (picked(i)) thinned_[i] = rank++ % static_cast<std::size_t>(options.every) == 0;
  }
  bool operator()(std::size_t i) const { return thinned_.empty() ? picked(i) : static_cast<bool>(thinned_[i]); }

 private:
  //! Whether the set, `within` and the paint pick particle i, before thinning.
  bool picked(std::size_t i) const {
    if (set_ == InstanceSet::tips && !attributes_.tip(i)) return false;
    if (unpainted_ && attributes_.on_paint[i]) return false;
    return !near_boundary_ || attributes_.boundary_distance[i] <= within_;
  }

  const Attributes& attributes_;
  InstanceSet set_;
  double within_;
  bool near_boundary_;
  bool unpainted_;  // whether points over the paint are left out
  std::vector<bool> thinned_;  // with `every` > 1: whether particle i is kept
};

//! The instancing point at particle i, whose half gap to the nearest other is `gap` spacings
//! (half_gaps in attributes.h).
inline Instance instance_at(const Cluster& cluster, const Attributes& attributes, std::size_t i, float gap) {
  const auto& ps = cluster.particles;
  const Particle& p = ps[i];
  Vec3 direction = Vec3::UnitZ();
  if (p.parent >= 0) direction = (p.position - ps[static_cast<std::size_t>(p.parent)].position).normalized();
  double scale = static_cast<double>(gap) * cluster.spacing;
  if (!std::isfinite(scale)) scale = cluster.spacing;  // a lone instance: as large as a particle
  if (!attributes.boundary_distance.empty()) scale = std::min(scale, static_cast<double>(attributes.boundary_distance[i]));
  return {p.position, direction, scale, static_cast<std::int32_t>(i)};
}

//! How many instancing points the options give.
inline std::size_t count_instances(const Cluster& cluster, const Attributes& attributes, const InstanceOptions& options) {
  const InstanceSelection selected(cluster, attributes, options);
  std::size_t count = 0;
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) count += selected(i);
  return count;
}

//! The half gaps (half_gaps in attributes.h) of the points `selected` picks under `options`, in
//! attach order: the attributes' tip_gaps for every tip where they were measured, else
//! measured into `measured` on `threads`, 20 bytes a point while it runs.
inline const std::vector<float>& instance_gaps(const Cluster& cluster, const Attributes& attributes,
                                               const InstanceOptions& options, const InstanceSelection& selected,
                                               std::vector<float>& measured, int threads = 1) {
  if (picks_every_tip(options) && !attributes.tip_gaps.empty()) return attributes.tip_gaps;
  std::vector<bool> chosen(cluster.particles.size());
  for (std::size_t i = 0; i < chosen.size(); ++i) chosen[i] = selected(i);
  measured = half_gaps(cluster, chosen, threads);
  return measured;
}

//! Calls visit(const Instance&) for each instancing point, in attach order, holding none of
//! them, with instance_gaps' scales. Throws as InstanceSelection.
template <class Visit>
void for_each_instance(const Cluster& cluster, const Attributes& attributes, const InstanceOptions& options,
                       Visit&& visit) {
  const InstanceSelection selected(cluster, attributes, options);
  const auto& ps = cluster.particles;
  std::vector<float> measured;
  const std::vector<float>& gaps = instance_gaps(cluster, attributes, options, selected, measured);
  std::size_t k = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (selected(i)) visit(static_cast<const Instance&>(instance_at(cluster, attributes, i, gaps[k++])));
}

//! The instancing points of a structure, all at once.
inline std::vector<Instance> instancing_points(const Cluster& cluster, const Attributes& attributes,
                                               const InstanceOptions& options) {
  std::vector<Instance> instances;
  for_each_instance(cluster, attributes, options, [&](const Instance& instance) { instances.push_back(instance); });
  return instances;
}

}  // namespace dla
