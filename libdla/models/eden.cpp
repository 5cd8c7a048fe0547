// The Eden model's engine (eden.h): the cluster on a lattice that grows with it, and its
// lattice graph.

#include "dla/models/eden.h"

#include "dla/models/model_shell.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dla {

namespace detail {

//! The sites of an Eden cluster on a dense grid that grows as the cluster reaches its edge.
//! Per site: the particle there (>= 0); empty with c occupied mask sites (-1 - c; a mask has
//! fewer than 17^3 sites); or able to stick, at index -kCandidate - value of their list.
class EdenLattice {
 public:
  static constexpr std::int32_t kEmpty = -1;
  static constexpr std::int32_t kCandidate = 1 << 16;

  EdenLattice(int dimensions, int half_width) : dimensions_(dimensions) { lay_out(half_width); }

  //! The value of the site at lattice coordinates c, which must lie inside the grid.
  std::int32_t& at(const std::array<int, 3>& c) { return values_[index(c)]; }

  //! Makes the grid hold every site within `margin` of c, growing it by half as needed.
  void reach(const std::array<int, 3>& c, int margin) {
    for (int axis = 0; axis < dimensions_; ++axis)
      while (std::abs(c[static_cast<std::size_t>(axis)]) + margin >= half_width_) lay_out(half_width_ + half_width_ / 2);
  }

 private:
  std::size_t index(const std::array<int, 3>& c) const {
    const auto w = static_cast<std::size_t>(2 * half_width_);
    const auto x = static_cast<std::size_t>(c[0] + half_width_), y = static_cast<std::size_t>(c[1] + half_width_);
    const auto z = dimensions_ == 3 ? static_cast<std::size_t>(c[2] + half_width_) : 0;
    return (z * w + y) * w + x;
  }

  //! A grid of sites [-half_width, half_width) along each axis, the old sites kept.
  void lay_out(int half_width) {
    const int old_half = half_width_;
    std::vector<std::int32_t> old = std::move(values_);
    half_width_ = half_width;
    const auto w = static_cast<std::size_t>(2 * half_width);
    values_.assign(dimensions_ == 3 ? w * w * w : w * w, kEmpty);
    if (old.empty()) return;
    const int depth = dimensions_ == 3 ? old_half : 1;
    for (int z = dimensions_ == 3 ? -old_half : 0; z < depth; ++z)
      for (int y = -old_half; y < old_half; ++y) {
        const auto from = ((static_cast<std::size_t>(dimensions_ == 3 ? z + old_half : 0) * (2 * old_half) +
                            static_cast<std::size_t>(y + old_half)) *
                           static_cast<std::size_t>(2 * old_half));
        std::copy_n(old.begin() + static_cast<std::ptrdiff_t>(from), 2 * old_half,
                    values_.begin() + static_cast<std::ptrdiff_t>(index({-old_half, y, z})));
      }
  }

  int dimensions_;
  int half_width_ = 0;
  std::vector<std::int32_t> values_;
};

}  // namespace detail

Cluster eden(const EdenOptions& o, const ProgressFn& progress, const StopFlag* stop) {
  validate(o);
  const int dimensions = dimensions_of(o.lattice);
  const std::vector<std::array<int, 3>> mask = eden_mask(o);
  // Offsets nearest first, to find a new site's parent: groups of equally near sites.
  const auto length = [&](const std::array<int, 3>& c) { return eden_position(o.lattice, c, 1.0).squaredNorm(); };
  const auto nearest_first = [&](std::vector<std::array<int, 3>> offsets) {
    std::stable_sort(offsets.begin(), offsets.end(), [&](const auto& a, const auto& b) { return length(a) < length(b) - 1e-9; });
    return offsets;
  };
  const std::vector<std::array<int, 3>> by_distance = nearest_first(mask);
  int reach = 1;
  for (const auto& offset : mask)
    for (const int c : offset) reach = std::max(reach, std::abs(c));

  Cluster cluster = detail::seeded({}, o.spacing, dimensions);
  cluster.seed_count = 1;  // the site at the origin, which occupy() places on the lattice
  cluster.particles.reserve(std::min<std::size_t>(o.sites, 1u << 24));

  // A compact cluster of n sites spans about n^(1/d) across: start there, grow if needed.
  const int start = 8 + 2 * reach + static_cast<int>(o.seed_radius) +
                    static_cast<int>(std::pow(static_cast<double>(std::min<std::size_t>(o.sites, 1u << 20)), 1.0 / dimensions));
  detail::EdenLattice lattice(dimensions, start);
  std::vector<std::array<int, 3>> candidates;  // the sites that may stick, in any order
  Rng rng(o.rng_seed, 0x6564656eULL);          // a stream of its own: "eden"
  const std::int32_t needed = o.mask_threshold;

  const auto at = [&](const std::array<int, 3>& site, const std::array<int, 3>& offset) -> std::int32_t& {
    return lattice.at({site[0] + offset[0], site[1] + offset[1], site[2] + offset[2]});
  };
  // The nearest occupied site at `offsets` (nearest first) from `site`, the oldest among
  // equally near.
  const auto parent_of = [&](const std::array<int, 3>& site, const std::vector<std::array<int, 3>>& offsets) {
    std::int32_t parent = -1;
    double nearest = 0.0;
    for (const auto& offset : offsets) {
      if (parent >= 0 && length(offset) > nearest + 1e-9) break;
      const std::int32_t value = at(site, offset);
      if (value >= 0 && (parent < 0 || value < parent)) parent = value, nearest = length(offset);
    }
    return parent;
  };
  const auto occupy = [&](const std::array<int, 3>& site, std::int32_t parent) {
    const auto id = static_cast<std::int32_t>(cluster.particles.size());
    cluster.particles.push_back({eden_position(o.lattice, site, o.spacing), parent, 0});
    lattice.reach(site, 2 * reach + 1);
    std::int32_t& here = at(site, {0, 0, 0});
    if (here <= -detail::EdenLattice::kCandidate) {  // out of the list: the last takes its place
      const auto index = static_cast<std::size_t>(-detail::EdenLattice::kCandidate - here);
      candidates[index] = candidates.back();
      lattice.at(candidates[index]) = -detail::EdenLattice::kCandidate - static_cast<std::int32_t>(index);
      candidates.pop_back();
    }
    here = id;
    // Every empty site whose mask holds this one counts one more occupied site.
    for (const auto& offset : mask) {
      std::int32_t& value = at(site, {-offset[0], -offset[1], -offset[2]});
      if (value >= 0 || value <= -detail::EdenLattice::kCandidate) continue;
      const std::int32_t count = -value;  // -1 - c, so c + 1 now
      if (count >= needed) {
        value = -detail::EdenLattice::kCandidate - static_cast<std::int32_t>(candidates.size());
        candidates.push_back({site[0] - offset[0], site[1] - offset[1], site[2] - offset[2]});
      } else {
        value = -1 - count;
      }
    }
  };

  detail::ModelShell shell(progress, stop);
  try {
    occupy({0, 0, 0}, -1);
    // The initial cluster: the sites within the seed radius, nearest first, each hanging from
    // its nearest occupied neighbour.
    if (o.seed_radius > 0.0) {
      // Only the nearest o.sites sites of the disk are needed: they lie within the radius that
      // holds that many (a site per unit of area or volume, or more), with a margin.
      constexpr double kPi = 3.141592653589793;
      const double enough = dimensions == 3 ? std::cbrt(static_cast<double>(o.sites) * 3.0 / (4.0 * kPi))
                                            : std::sqrt(static_cast<double>(o.sites) / kPi);
      const int r = static_cast<int>(std::ceil(std::min(o.seed_radius, enough + 3.0))) + 1;
      std::vector<std::array<int, 3>> disk;
      for (int z = dimensions == 3 ? -r : 0; z <= (dimensions == 3 ? r : 0); ++z)
        for (int y = -r; y <= r; ++y)
          for (int x = -r; x <= r; ++x)
            if ((x || y || z) && length({x, y, z}) <= o.seed_radius * o.seed_radius) disk.push_back({x, y, z});
      std::stable_sort(disk.begin(), disk.end(), [&](const auto& a, const auto& b) { return length(a) < length(b) - 1e-9; });
      const std::vector<std::array<int, 3>> neighbours = nearest_first(lattice_neighbours(o.lattice));
      for (const auto& site : disk) {
        if (cluster.particles.size() >= o.sites) break;
        occupy(site, parent_of(site, neighbours));  // a step towards the seed is a nearer site of the disk
      }
    }

    while (cluster.particles.size() < o.sites && !candidates.empty()) {
      // A site takes a fraction of a microsecond: the shell is asked every 4,096.
      if ((cluster.particles.size() & 0xfff) == 1 && !shell.go_on(cluster)) {
        cluster.complete = false;
        break;
      }
      // Uniform in [0, size) from 53 random bits: no bias worth the name below 2^32 sites.
      const std::size_t pick =
          std::min(candidates.size() - 1, static_cast<std::size_t>(rng.uniform() * static_cast<double>(candidates.size())));
      const std::array<int, 3> site = candidates[pick];
      occupy(site, parent_of(site, by_distance));
    }
  } catch (...) {
    detail::ModelShell::keep_what_grew(cluster);
  }
  shell.finish(cluster);
  return cluster;
}

std::vector<Link> lattice_links(const Cluster& cluster, Lattice lattice, int threads, const StageWatch& watch) {
  const std::vector<std::array<int, 3>> neighbours = lattice_neighbours(lattice);
  double step = 0.0;
  for (const std::array<int, 3>& c : neighbours) step = std::max(step, eden_position(lattice, c, 1.0).norm());
  LinkOptions o;
  o.distance = step * (1.0 + 1e-6);
  o.most = neighbours.size();
  return neighbour_links(cluster, o, threads, {}, 2, watch);  // all but the tree's own edges
}

}  // namespace dla
