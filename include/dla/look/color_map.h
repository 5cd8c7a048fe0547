#pragma once
//! \file color_map.h
//! Colour by attribute (`--color-by none|age|depth|seed|distance|current`): one value in [0, 1] per
//! particle, and one colour map for every file that carries colour (glTF, OBJ, POV-Ray).

#include "dla/look/attributes.h"
#include "dla/core/words.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

namespace dla {

enum class ColorBy {
  none,      //!< no colour: each file's plain look
  age,       //!< attach order: the oldest dark, the newest bright
  depth,     //!< path length to the seed
  seed,      //!< which tree: a colour each
  distance,  //!< distance to the mesh's surface, or to the seeds without a mesh
  current,   //!< the charge that flows through it (Attributes::current): a discharge's main
             //!< channel brightest, fading along the side branches
};
inline constexpr WordTable<ColorBy, 6> kColorByWords{
    "colour attribute",
    {{{ColorBy::none, "none"}, {ColorBy::age, "age"}, {ColorBy::depth, "depth"}, {ColorBy::seed, "seed"},
      {ColorBy::distance, "distance"}, {ColorBy::current, "current"}}}};
constexpr const auto& words_of(ColorBy) { return kColorByWords; }

//! Maps a particle to [0, 1] by one attribute, scaled by the structure's largest value.
class ColorScale {
 public:
  ColorScale(const Cluster& cluster, const Attributes& attributes, ColorBy by)
      : cluster_(&cluster), attributes_(&attributes), by_(by) {
    if (by == ColorBy::depth) reach_ = attributes.depth.empty() ? 0.0 : *std::max_element(attributes.depth.begin(), attributes.depth.end());
    if (by == ColorBy::distance) reach_ = attributes.boundary_distance.empty() ? attributes.seed_reach : attributes.boundary_reach;
  }

  double operator()(std::size_t i) const {
    switch (by_) {
      case ColorBy::none: return 0.0;
      case ColorBy::age: return attributes_->age(i);
      case ColorBy::depth: return reach_ > 0 ? attributes_->depth[i] / reach_ : 0.0;
      // The golden ratio spreads tree after tree around the map.
      case ColorBy::seed: return std::fmod(0.15 + 0.618034 * cluster_->particles[i].seed, 1.0);
      case ColorBy::distance: return reach_ > 0 ? distance(i) / reach_ : 0.0;
      // The square root: a side branch of a hundredth of the current still shows, at a tenth.
      case ColorBy::current: return std::sqrt(attributes_->current(i));
    }
    return 0.0;
  }

 private:
  double distance(std::size_t i) const {
    return attributes_->boundary_distance.empty() ? attributes_->seed_distance(cluster_->particles[i].position)
                                                  : attributes_->boundary_distance[i];
  }

  const Cluster* cluster_;
  const Attributes* attributes_;
  ColorBy by_;
  double reach_ = 0.0;
};

//! The colour map: matplotlib's viridis (#440154, #3b528b, #21918c, #5ec962, #fde725) in
//! linear RGB, as glTF's COLOR_0 and POV-Ray's assumed_gamma 1.0 take it.
inline constexpr std::array<std::array<double, 3>, 5> kColorStops = {{
    {0.058, 0.0003, 0.089}, {0.044, 0.084, 0.258}, {0.015, 0.283, 0.262}, {0.112, 0.584, 0.122}, {0.982, 0.799, 0.019}}};

inline std::array<double, 3> color_at(double value) {
  const double x = std::clamp(value, 0.0, 1.0) * (kColorStops.size() - 1);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(x), kColorStops.size() - 2);
  const double f = x - static_cast<double>(k);
  std::array<double, 3> rgb{};
  for (int c = 0; c < 3; ++c) rgb[c] = kColorStops[k][c] + (kColorStops[k + 1][c] - kColorStops[k][c]) * f;
  return rgb;
}

}  // namespace dla
