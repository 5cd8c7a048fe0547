#pragma once
//! \file drop.h
//! Random-drop ballistic aggregation, RDBA (Roberts 2001, "Sticky Pixels", sections 4.2 and
//! 4.3): each particle is dropped at a random point of a drop zone and joins the exactly
//! closest particle of the structure, one spacing from it on the line towards the drop point.
//! A drop within a spacing of the structure fell on top of it and is rejected. The closest
//! particle to any point lies farther than the new one's neighbours can (the ball about the
//! drop point through it holds the ball of one spacing about the new particle), so no particle
//! comes closer than the spacing to an earlier one. The result is the Cluster every model
//! returns. See docs/drop.md.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/mesh/constraint.h"
#include "dla/core/words.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dla {

//! Where particles are dropped (`--zone`).
enum class DropZone {
  ball,  //!< a disk (2D) or ball about the seeds' centre, fixed or growing with the structure
  box,   //!< a box: fixed, or the square or cube around the ball
  mesh,  //!< the volume of the constraint mesh (`--stl`, `--side inside`)
};
inline constexpr WordTable<DropZone, 3> kDropZoneWords{
    "drop zone",
    {{{DropZone::ball, "ball"}, {DropZone::box, "box"}, {DropZone::mesh, "mesh"}}}};
constexpr const auto& words_of(DropZone) { return kDropZoneWords; }

//! How drop points follow one another (`--drop`; the paper's section 4.3).
enum class DropPattern {
  uniform,  //!< each uniform in the zone
  same,     //!< `same:N`: N drops at one uniform point, then N at the next
  circle,   //!< uniform on the zone's edge: the circle or sphere (the paper's figure 10,
            //!< lightning bolts), the box's faces, the mesh's surface
  offset,   //!< `offset:N,R`: a uniform drop, then N each uniform within R of the one before
};

struct DropBias {
  DropPattern pattern = DropPattern::uniform;
  std::uint64_t count = 1;     //!< same, offset: N, 1 to 1e9
  double offset_radius = 0.0;  //!< offset: R, scene units, in (0, 1e6 spacings]
};

//! "uniform", "same:N", "circle" or "offset:N,R", as the CLI writes them.
inline std::string to_string(const DropBias& bias) {
  switch (bias.pattern) {
    case DropPattern::uniform: return "uniform";
    case DropPattern::circle: return "circle";
    case DropPattern::same: return "same:" + std::to_string(bias.count);
    case DropPattern::offset: return "offset:" + std::to_string(bias.count) + "," + detail::format_number(bias.offset_radius);
  }
  return "?";
}

//! Parses `--drop`'s words; throws InvalidInput naming the accepted forms. N and R are
//! checked by validate().
inline DropBias parse_drop_bias(const std::string& text) {
  const auto fail = [&] {
    return InvalidInput("`drop` '" + text + "' is not uniform, circle, same:N or offset:N,R");
  };
  const auto number = [&](const std::string& word) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(word, &used);
    } catch (const std::exception&) {
      throw fail();
    }
    if (used != word.size()) throw fail();
    return value;
  };
  const auto count = [&](const std::string& word) {
    const double n = number(word);
    if (!(n >= 1.0 && n <= 1e9 && n == std::floor(n))) throw InvalidInput("`drop` '" + text + "': N is not a whole number in [1, 1e9]");
    return static_cast<std::uint64_t>(n);
  };
  DropBias bias;
  if (text == "uniform") return bias;
  if (text == "circle") {
    bias.pattern = DropPattern::circle;
    return bias;
  }
  if (text.rfind("same:", 0) == 0) {
    bias.pattern = DropPattern::same;
    bias.count = count(text.substr(5));
    return bias;
  }
  if (text.rfind("offset:", 0) == 0) {
    const std::size_t comma = text.find(',', 7);
    if (comma == std::string::npos) throw fail();
    bias.pattern = DropPattern::offset;
    bias.count = count(text.substr(7, comma - 7));
    bias.offset_radius = number(text.substr(comma + 1));
    return bias;
  }
  throw fail();
}

//! Options of a random-drop run. Lengths are in scene units; the spacing sets the scale.
struct DropOptions {
  std::size_t particles = 10000;  //!< particles to attach, seeds not counted
  double spacing = 1.0;           //!< distance from a particle to its parent; no two come
                                  //!< closer; in [1e-25, 1e25]
  double stickiness = 1.0;        //!< chance that a particle sticks when it reaches the
                                  //!< structure, in [1e-4, 1]; one that does not takes a
                                  //!< random step of a spacing from its drop point and
                                  //!< reaches again from there
  std::uint64_t rng_seed = 1;     //!< seeds every random choice of the run
  int dimensions = 3;             //!< 3, or 2 for growth in the plane z = 0
  std::vector<Vec3> seeds = {Vec3::Zero()};  //!< one tree per seed
  DropZone zone = DropZone::ball;
  //! ball: the zone's radius about the seeds' centre; 0: growing, `zone_margin` beyond the
  //! farthest particle. At most 1e6 spacings.
  double zone_radius = 0.0;
  double zone_margin = 10.0;      //!< growing ball: spacings beyond the farthest particle, [0.5, 1e6]
  std::optional<Box> zone_box;    //!< box: a fixed box; unset, the square or cube around the ball
  DropBias bias;                  //!< `--drop`
};

//! What happened to the drops, for the summary and the JSON record.
struct DropStats {
  std::uint64_t drops = 0;          //!< drop points drawn, biased ones included
  std::uint64_t on_structure = 0;   //!< rejected: within a spacing of the structure
  std::uint64_t refused = 0;        //!< reached the structure and did not stick (stickiness)
  std::uint64_t lost = 0;           //!< on the wrong side of the constraint mesh
  std::uint64_t mesh_rejected = 0;  //!< branches refused because they crossed the mesh
  std::uint64_t clipped = 0;        //!< branches cut short at the mesh
  bool zone_full = false;           //!< growth ended early: kMaxFailedDrops in a row failed
};

//! Drops that fail in a row before growth ends early, the zone full: ~0.1 s of drops.
inline constexpr std::uint64_t kMaxFailedDrops = 1'000'000;

//! Random drops' options with a single value, described once (option_description.h); the count,
//! plane, spacing and seeds are those drop shares with ballistic aggregation, the zone's radius
//! and box and the drop pattern the front ends'.
inline const OptionTable<DropOptions>& drop_option_table() {
  using O = DropOptions;
  static constexpr std::string_view group = "Random drops";
  static const OptionTable<O> table{
      real("stickiness", &O::stickiness, closed(kMinStickiness, 1), "", group,
           "chance of sticking on reaching the structure; else a random step and again"),
      word("zone", &O::zone, group, "where particles drop: ball (a disk in 2D), box, or mesh (inside --stl)"),
      real("zone_margin", &O::zone_margin, closed(0.5, 1e6), "spacings", group,
           "growing ball: how far beyond the farthest particle"),
  };
  return table;
}

inline void validate(const DropOptions& o) {
  detail::validate_seeded(o.particles, o.seeds, o.spacing, o.dimensions);
  require_in_ranges(drop_option_table(), o);
  if (o.zone_radius != 0.0) detail::require_in("zone radius", o.zone_radius / o.spacing, 1.0, 1e6);
  if (o.zone_box) {
    detail::require_representable("zone box's min corner", o.zone_box->min, o.spacing);
    detail::require_representable("zone box's max corner", o.zone_box->max, o.spacing);
    for (int a = 0; a < o.dimensions; ++a)
      if (!(o.zone_box->min[a] < o.zone_box->max[a]))
        throw InvalidInput("zone box is empty: its min corner is not below its max corner");
  }
  if (o.zone_box && o.zone != DropZone::box) throw InvalidInput("a zone box needs the box zone");
  if (o.zone_radius != 0.0 && o.zone == DropZone::mesh) throw InvalidInput("a zone radius has no use with the mesh zone");
  if (o.zone == DropZone::mesh && o.dimensions != 3) throw InvalidInput("the mesh zone needs 3 dimensions");
  if (o.bias.count < 1 || o.bias.count > 1'000'000'000u)
    throw InvalidInput("`drop`'s N " + std::to_string(o.bias.count) + " is not in [1, 1e9]");
  if (o.bias.pattern == DropPattern::offset)
    detail::require_in("`drop`'s offset radius, in spacings,", o.bias.offset_radius / o.spacing, 1e-6, 1e6);
}

//! Checks the options against a constraint mesh as well: 3 dimensions, the same spacing, seeds
//! on the growing side, and a side for zones that need one.
inline void validate(const DropOptions& o, const MeshConstraint& constraint) {
  validate(o);
  if (o.dimensions != 3) throw InvalidInput("a constraint mesh needs growth in 3 dimensions");
  if (o.spacing != constraint.spacing())
    throw InvalidInput("the constraint was built for spacing " + detail::format_number(constraint.spacing()) +
                       ", not " + detail::format_number(o.spacing));
  if (constraint.shell() > 0.0)
    throw InvalidInput("drops fall through space, not over a surface: `side` surface and shells are for DLA");
  const Side side = constraint.options().side;
  if (o.zone == DropZone::mesh && side != Side::inside)
    throw InvalidInput("the mesh zone drops inside the mesh: it needs `side` inside, not `side` " + std::string(to_string(side)));
  if (o.zone == DropZone::mesh && o.bias.pattern == DropPattern::circle && side == Side::both)
    throw InvalidInput("drops on the mesh's surface need a growing side, `side` inside or outside");
  for (std::size_t i = 0; i < o.seeds.size(); ++i)
    if (!constraint.on_growth_side(o.seeds[i]))
      throw InvalidInput("seed " + std::to_string(i + 1) + " is not on the growing side of the mesh");
}

//! Grows a structure by random drops with a given index (GridIndex, or BruteForceIndex to test
//! against), constrained by `constraint` if set. Does not validate. Calls `progress` every 256
//! particles and at the end; `stop` ends growth early, the cluster marked incomplete. Growth
//! that attaches nothing in kMaxFailedDrops drops in a row ends there, complete, with
//! `stats->zone_full` set. Throws PartialGrowth if the structure outgrows the index.
template <class Index>
Cluster drop_with(const DropOptions& options, const MeshConstraint* constraint, const ProgressFn& progress = {},
                  const StopFlag* stop = nullptr, DropStats* stats = nullptr);

//! Validates the options (against the constraint, if any) and grows with the grid index.
Cluster drop(const DropOptions& options, const MeshConstraint* constraint = nullptr, const ProgressFn& progress = {},
             const StopFlag* stop = nullptr, DropStats* stats = nullptr);

}  // namespace dla
