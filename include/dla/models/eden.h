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

//! The Eden model's options with a single value, described once (option_description.h); the
//! count, lattice, mask and spacing are the front ends'.
inline const OptionTable<EdenOptions>& eden_option_table() {
  using O = EdenOptions;
  static const OptionTable<O> table{
      word("mode", &O::mode, "Eden",
           "perimeter (a random empty neighbour joins) or drop (a random site joins where the mask counts enough of "
           "the cluster)"),
      real("seed_radius", &O::seed_radius, closed(0, 100), "spacings", "Eden",
           "the cluster starts as every site within this of the seed"),
  };
  return table;
}

inline void validate(const EdenOptions& o) {
  require_in_ranges(eden_option_table(), o);
  if (o.sites < 1 || o.sites > 2'000'000'000u)
    throw InvalidInput("sites " + std::to_string(o.sites) + " is not in [1, 2e9]");
  detail::require_in("spacing", o.spacing, kMinSpacing, kMaxSpacing);
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

//! The lattice graph of an Eden cluster beside its tree (`links` lattice): a link between every
//! pair of occupied lattice neighbours that the tree does not join. Neighbours are the sites
//! within the lattice's longest neighbour step, and no other site is that near.
std::vector<Link> lattice_links(const Cluster& cluster, Lattice lattice, int threads = 1,
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
Cluster eden(const EdenOptions& o, const ProgressFn& progress = {}, const StopFlag* stop = nullptr);

}  // namespace dla
