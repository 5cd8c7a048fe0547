#pragma once
//! \file eden.h
//! The Eden model (Eden 1961; Roberts 2001, "Sticky Pixels", sections 3.1 and 4.1): a cluster
//! on a lattice grows by one site at a time. The result is the Cluster every model returns, so
//! every look and writer applies. See docs/eden.md.
//!
//! - `perimeter`: the new site is drawn uniformly among the empty sites next to the cluster.
//! - `drop`: sites are dropped uniformly in a zone around the cluster, and one sticks when a
//!   mask laid over it counts at least k occupied sites. Dropping and rejecting picks every
//!   site that may stick with the same chance, so the engine draws uniformly among those
//!   sites directly: the same growth without the wasted drops, and no wait for ever when none
//!   can stick (growth then ends early). `perimeter` is `drop` with the lattice's neighbours
//!   as the mask and k = 1.
//!
//! A new site's parent is the nearest occupied site of its mask (its neighbours, in
//! `perimeter` mode); among equally near ones, the oldest.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/models/links.h"
#include "dla/models/model_shell.h"
#include "dla/core/words.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace dla {

//! The lattice and which sites are neighbours (`--lattice`).
enum class Lattice {
  square4,   //!< square, the 4 sites sharing an edge (the paper's figure 1, left)
  square8,   //!< square, the 8 sites sharing an edge or a corner (figure 1, right)
  hex,       //!< triangular lattice of hexagonal cells: 6 neighbours
  cubic6,    //!< cubic, the 6 sites sharing a face
  cubic18,   //!< cubic, the 18 sharing a face or an edge
  cubic26,   //!< cubic, the 26 sharing a face, an edge or a corner
};
inline constexpr WordTable<Lattice, 6> kLatticeWords{
    "lattice",
    {{{Lattice::square4, "square4"}, {Lattice::square8, "square8"}, {Lattice::hex, "hex"}, {Lattice::cubic6, "cubic6"},
      {Lattice::cubic18, "cubic18"}, {Lattice::cubic26, "cubic26"}}}};
constexpr const auto& words_of(Lattice) { return kLatticeWords; }

//! 2 for the plane lattices, 3 for the cubic ones.
inline int dimensions_of(Lattice lattice) {
  return lattice == Lattice::cubic6 || lattice == Lattice::cubic18 || lattice == Lattice::cubic26 ? 3 : 2;
}

//! A site's neighbours as offsets in lattice coordinates. The hexagonal lattice is kept in
//! axial coordinates (q, r): the site at (q, r) lies at (q + r / 2, r sqrt(3) / 2) spacings.
inline std::vector<std::array<int, 3>> lattice_neighbours(Lattice lattice) {
  std::vector<std::array<int, 3>> offsets;
  const int depth = dimensions_of(lattice) == 3 ? 1 : 0;
  for (int z = -depth; z <= depth; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        const int nonzero = (x != 0) + (y != 0) + (z != 0);
        if (nonzero == 0) continue;
        bool keep = false;
        switch (lattice) {
          case Lattice::square4:
          case Lattice::cubic6: keep = nonzero == 1; break;
          case Lattice::square8:
          case Lattice::cubic26: keep = true; break;
          case Lattice::cubic18: keep = nonzero <= 2; break;
          case Lattice::hex: keep = x != y; break;  // all but (1, 1) and (-1, -1)
        }
        if (keep) offsets.push_back({x, y, z});
      }
  return offsets;
}

//! How sites are chosen (`--mode`).
enum class EdenMode {
  perimeter,  //!< uniformly among the empty neighbours of the cluster
  drop,       //!< dropped at random; sticks where the mask counts enough occupied sites
};
inline constexpr WordTable<EdenMode, 2> kEdenModeWords{
    "Eden mode",
    {{{EdenMode::perimeter, "perimeter"}, {EdenMode::drop, "drop"}}}};
constexpr const auto& words_of(EdenMode) { return kEdenModeWords; }

//! The masks of the paper's figure 4 (`--mask A|B|C|D`), as this engine reads them (the
//! figure itself is not in the text): A the 4 sites sharing an edge, B the 8 of the 3x3 block,
//! C the 12 within two edge steps (a diamond), D the 24 of the 5x5 block. On a cubic lattice
//! the same in 3D: 6, 26, 24 and 124 sites. On the hexagonal lattice A and B are the 6
//! neighbours, C and D the 18 sites within two steps.
enum class EdenMask { A, B, C, D };
inline constexpr WordTable<EdenMask, 4> kEdenMaskWords{
    "mask",
    {{{EdenMask::A, "A"}, {EdenMask::B, "B"}, {EdenMask::C, "C"}, {EdenMask::D, "D"}}}};
constexpr const auto& words_of(EdenMask) { return kEdenMaskWords; }

//! The sites of a preset mask on a lattice, as offsets from the dropped site.
inline std::vector<std::array<int, 3>> mask_sites(EdenMask mask, Lattice lattice) {
  const int depth = dimensions_of(lattice) == 3 ? 2 : 0;
  std::vector<std::array<int, 3>> sites;
  for (int z = -depth; z <= depth; ++z)
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) {
        if (x == 0 && y == 0 && z == 0) continue;
        const int steps = std::abs(x) + std::abs(y) + std::abs(z), block = std::max({std::abs(x), std::abs(y), std::abs(z)});
        // Steps on the hexagonal lattice in axial coordinates.
        const int hex_steps = std::max({std::abs(x), std::abs(y), std::abs(x + y)});
        bool in = false;
        if (lattice == Lattice::hex) {
          in = hex_steps <= (mask == EdenMask::A || mask == EdenMask::B ? 1 : 2);
        } else {
          switch (mask) {
            case EdenMask::A: in = steps <= 1; break;
            case EdenMask::B: in = block <= 1; break;
            case EdenMask::C: in = steps <= 2; break;
            case EdenMask::D: in = block <= 2; break;
          }
        }
        if (in) sites.push_back({x, y, z});
      }
  return sites;
}

//! A mask drawn as text (`--mask FILE`): `o` marks the dropped site, `x` or `#` a site the
//! mask counts, `.` or a space one it does not; the first line is the top row (+y). A 3D mask
//! is its layers from -z to +z, each a block of rows, with a blank line between them; the
//! layer holding `o` is z = 0. Lines starting with `;` are comments. Throws InvalidInput.
inline std::vector<std::array<int, 3>> parse_mask(const std::string& text) {
  std::vector<std::vector<std::string>> layers(1);
  std::size_t from = 0;
  while (from <= text.size()) {
    std::size_t to = text.find('\n', from);
    if (to == std::string::npos) to = text.size();
    std::string line = text.substr(from, to - from);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    from = to + 1;
    if (!line.empty() && line[0] == ';') continue;
    if (line.find_first_not_of(' ') == std::string::npos) {
      if (!layers.back().empty()) layers.emplace_back();
      continue;
    }
    layers.back().push_back(line);
  }
  if (layers.back().empty()) layers.pop_back();
  std::vector<std::array<int, 3>> counted;
  std::array<int, 3> center{0, 0, 0};
  int centers = 0;
  for (std::size_t z = 0; z < layers.size(); ++z)
    for (std::size_t y = 0; y < layers[z].size(); ++y)
      for (std::size_t x = 0; x < layers[z][y].size(); ++x) {
        const char c = layers[z][y][x];
        // x right, y up the picture: a row lower in the text is lower in y.
        const std::array<int, 3> at{static_cast<int>(x), -static_cast<int>(y), static_cast<int>(z)};
        if (c == 'o') {
          center = at;
          ++centers;
        } else if (c == 'x' || c == '#') {
          counted.push_back(at);
        } else if (c != '.' && c != ' ') {
          throw InvalidInput(std::string("a mask holds '") + c + "': o (the dropped site), x or # (counted), . or space");
        }
      }
  if (centers != 1) throw InvalidInput("a mask marks the dropped site with one o, not " + std::to_string(centers));
  if (counted.empty()) throw InvalidInput("a mask counts no site: mark them with x");
  for (auto& site : counted)
    for (std::size_t axis = 0; axis < 3; ++axis) site[axis] -= center[axis];
  return counted;
}

//! How an Eden cluster grows.
struct EdenOptions {
  std::size_t sites = 100000;        //!< sites at most, the seed included; 1 to 2e9
  Lattice lattice = Lattice::square4;
  EdenMode mode = EdenMode::perimeter;
  //! drop: the sites the mask counts, as offsets from the dropped site, each coordinate in
  //! [-8, 8] (z = 0 on a plane lattice); empty: the preset `mask`.
  std::vector<std::array<int, 3>> mask_offsets;
  EdenMask mask = EdenMask::A;       //!< drop: the preset, when mask_offsets is empty
  int mask_threshold = 1;            //!< drop: occupied mask sites a site needs, 1 to the mask's size
  //! The cluster starts as every site within this many spacings of the seed, in [0, 100], so
  //! that a threshold above 1 can start.
  double seed_radius = 0.0;
  double spacing = 1.0;              //!< distance between neighbouring sites along an axis,
                                     //!< scene units (a hexagonal lattice's nearest
                                     //!< neighbours are this far apart too)
  std::uint64_t rng_seed = 1;
};

//! The mask a run uses: the lattice's neighbours in perimeter mode, else the offsets or preset.
inline std::vector<std::array<int, 3>> eden_mask(const EdenOptions& o) {
  if (o.mode == EdenMode::perimeter) return lattice_neighbours(o.lattice);
  return o.mask_offsets.empty() ? mask_sites(o.mask, o.lattice) : o.mask_offsets;
}

inline void validate(const EdenOptions& o) {
  if (o.sites < 1 || o.sites > 2'000'000'000u)
    throw InvalidInput("sites " + std::to_string(o.sites) + " is not in [1, 2e9]");
  detail::require_in("spacing", o.spacing, kMinSpacing, kMaxSpacing);
  detail::require_in("seed radius", o.seed_radius, 0.0, 100.0);
  const bool planar = dimensions_of(o.lattice) == 2;
  for (const auto& offset : o.mask_offsets) {
    if (offset == std::array<int, 3>{0, 0, 0}) throw InvalidInput("the mask holds the dropped site itself");
    for (const int c : offset)
      if (c < -8 || c > 8) throw InvalidInput("a mask site lies more than 8 sites from the dropped one");
    if (planar && offset[2] != 0) throw InvalidInput("a mask site lies off the plane of a " + std::string(to_string(o.lattice)) + " lattice");
  }
  std::vector<std::array<int, 3>> sorted = o.mask_offsets;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) throw InvalidInput("a mask site is given twice");
  const std::size_t size = eden_mask(o).size();
  if (o.mask_threshold < 1 || static_cast<std::size_t>(o.mask_threshold) > size)
    throw InvalidInput("mask threshold " + std::to_string(o.mask_threshold) + " is not in [1, " +
                       std::to_string(size) + "], the mask's sites");
}

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

//! The lattice graph of an Eden cluster beside its tree (`links` lattice): a link between every
//! pair of occupied lattice neighbours that the tree does not join. Neighbours are the sites
//! within the lattice's longest neighbour step, and no other site is that near.
inline std::vector<Link> lattice_links(const Cluster& cluster, Lattice lattice, int threads = 1,
                                       const StageWatch& watch = {});

//! The position of lattice site c, `spacing` apart, the seed at the origin.
inline Vec3 eden_position(Lattice lattice, const std::array<int, 3>& c, double spacing) {
  if (lattice == Lattice::hex) return spacing * Vec3(c[0] + 0.5 * c[1], c[1] * (std::sqrt(3.0) / 2), 0.0);
  return spacing * Vec3(c[0], c[1], c[2]);
}

//! Grows an Eden cluster of up to `o.sites` sites from one seed at the origin (and the sites
//! within o.seed_radius of it). Validates the options first. Growth ends early when no site
//! can stick. `progress` is called as model_shell.h says; returning false, or `stop` set, ends
//! growth with the cluster marked incomplete. Throws PartialGrowth when memory runs out.
inline Cluster eden(const EdenOptions& o, const ProgressFn& progress = {}, const StopFlag* stop = nullptr) {
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

inline std::vector<Link> lattice_links(const Cluster& cluster, Lattice lattice, int threads, const StageWatch& watch) {
  const std::vector<std::array<int, 3>> neighbours = lattice_neighbours(lattice);
  double step = 0.0;
  for (const std::array<int, 3>& c : neighbours) step = std::max(step, eden_position(lattice, c, 1.0).norm());
  LinkOptions o;
  o.distance = step * (1.0 + 1e-6);
  o.most = neighbours.size();
  return neighbour_links(cluster, o, threads, {}, 2, watch);  // all but the tree's own edges
}

}  // namespace dla
