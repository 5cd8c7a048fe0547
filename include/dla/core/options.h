#pragma once
//! \file options.h
//! What a growth run is asked to do, with defaults, and the one place it is checked.

#include "dla/core/errors.h"
#include "dla/core/option_description.h"
#include "dla/core/words.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dla {

using Vec3 = Eigen::Vector3d;

//! Where walkers start. The words are the CLI's (`--spawn sphere|disk|box|inside|radial|surface`).
enum class SpawnMode {
  sphere,  //!< uniform on a sphere just outside the structure (with a mesh: around the mesh)
  disk,    //!< uniform in a disk across the spawn axis, just outside the structure: directed growth
  box,     //!< uniform in a box
  inside,  //!< uniform in the volume of a constraint mesh (constraint.h)
  radial,  //!< along rays from a constraint mesh's centroid to its surface (constraint.h)
  surface, //!< just off a constraint mesh's surface, on the growing side (constraint.h)
};
inline constexpr WordTable<SpawnMode, 6> kSpawnModeWords{
    "spawn mode",
    {{{SpawnMode::sphere, "sphere"}, {SpawnMode::disk, "disk"}, {SpawnMode::box, "box"}, {SpawnMode::inside, "inside"},
      {SpawnMode::radial, "radial"}, {SpawnMode::surface, "surface"}}}};
constexpr const auto& words_of(SpawnMode) { return kSpawnModeWords; }

//! A coordinate axis, for the disk spawn.
enum class Axis { x, y, z };
inline constexpr WordTable<Axis, 3> kAxisWords{"axis", {{{Axis::x, "x"}, {Axis::y, "y"}, {Axis::z, "z"}}}};
constexpr const auto& words_of(Axis) { return kAxisWords; }

//! The nearest-particle look-up behind the walk (`--index grid|kdtree|brute`); see docs/spatial-index.md.
enum class IndexKind {
  grid,    //!< cell grid with a pyramid of occupancy bits: the fastest, the default
  kdtree,  //!< nanoflann's dynamic k-d tree
  brute,   //!< a linear scan: a reference for tests, slow
};
inline constexpr WordTable<IndexKind, 3> kIndexKindWords{
    "index",
    {{{IndexKind::grid, "grid"}, {IndexKind::kdtree, "kdtree"}, {IndexKind::brute, "brute"}}}};
constexpr const auto& words_of(IndexKind) { return kIndexKindWords; }

//! An axis-aligned box given by two opposite corners.
struct Box {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

namespace detail {
//! A number as the shortest "%g" text that reads back as the same double.
inline std::string exact_number(double value) {
  char text[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value || value != value) break;
  }
  return text;
}

//! The `count` comma-separated numbers in `words`, given for option `name`; or InvalidInput
//! "`drift` '1,2' is not 3 comma-separated numbers".
inline std::vector<double> numbers_in(std::string_view name, std::string_view words, std::size_t count) {
  std::vector<double> values;
  bool numbers = true;
  for (std::size_t start = 0; start <= words.size();) {
    const std::size_t comma = std::min(words.find(',', start), words.size());
    const std::string item(words.substr(start, comma - start));
    char* end = nullptr;
    values.push_back(std::strtod(item.c_str(), &end));
    numbers = numbers && end != item.c_str() && end == item.c_str() + item.size();
    start = comma + 1;
  }
  if (!numbers || values.size() != count)
    throw InvalidInput("`" + std::string(name) + "` '" + std::string(words) + "' is not " + std::to_string(count) +
                       " comma-separated numbers");
  return values;
}

//! "x,y,z", as numbers_in() reads it back.
inline std::string point_words(const Vec3& p) {
  return exact_number(p.x()) + "," + exact_number(p.y()) + "," + exact_number(p.z());
}
}  // namespace detail

// The text forms below read "" as unset (or none), as they print it.

//! A vector "X,Y,Z" in a member of type Vec3 (or std::optional<Vec3>: unset, "").
template <class Options, class Member>
DescribedOption<Options> vector3(std::string_view name, Member Options::*member, std::string_view group,
                                 std::string_view help) {
  return parsed<Options>(
      name, OptionKind::vector, "X,Y,Z", group, help,
      [name, member](Options& o, const std::string& words) {
        if constexpr (!std::is_same_v<Member, Vec3>)
          if (words.empty()) return void(o.*member = std::nullopt);
        const std::vector<double> v = detail::numbers_in(name, words, 3);
        o.*member = Vec3(v[0], v[1], v[2]);
      },
      [member](const Options& o) -> std::string {
        if constexpr (std::is_same_v<Member, Vec3>) return detail::point_words(o.*member);
        else return o.*member ? detail::point_words(*(o.*member)) : "";
      });
}

//! A box "X0,Y0,Z0,X1,Y1,Z1", its two opposite corners, in a member of type std::optional<Box>.
template <class Options>
DescribedOption<Options> box_corners(std::string_view name, std::optional<Box> Options::*member, std::string_view group,
                             std::string_view help) {
  return parsed<Options>(
      name, OptionKind::vector, "X0,Y0,Z0,X1,Y1,Z1", group, help,
      [name, member](Options& o, const std::string& words) {
        if (words.empty()) return void(o.*member = std::nullopt);
        const std::vector<double> b = detail::numbers_in(name, words, 6);
        o.*member = Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
      },
      [member](const Options& o) -> std::string {
        return o.*member ? detail::point_words((o.*member)->min) + "," + detail::point_words((o.*member)->max) : "";
      });
}

//! Points "X,Y,Z", one a value, in a member of type std::optional<std::vector<Vec3>> (unset:
//! none given) or std::vector<Vec3>.
template <class Options, class Member>
DescribedOption<Options> point_list(std::string_view name, Member Options::*member, std::string_view group,
                                std::string_view help) {
  return repeated<Options>(
      name, OptionKind::points, "X,Y,Z", group, help,
      [name, member](Options& o, const std::vector<std::string>& list) {
        if constexpr (!std::is_same_v<Member, std::vector<Vec3>>)
          if (list.empty()) return void(o.*member = std::nullopt);
        std::vector<Vec3> at;
        for (const std::string& words : list) {
          const std::vector<double> v = detail::numbers_in(name, words, 3);
          at.emplace_back(v[0], v[1], v[2]);
        }
        o.*member = at;
      },
      [member](const Options& o) {
        std::vector<std::string> list;
        const std::vector<Vec3>* at;
        if constexpr (std::is_same_v<Member, std::vector<Vec3>>) at = &(o.*member);
        else at = o.*member ? &*(o.*member) : nullptr;
        if (at)
          for (const Vec3& p : *at) list.push_back(detail::point_words(p));
        return list;
      });
}

//! Options of one growth run. Lengths are in scene units; the spacing sets the scale. The
//! ranges and help of the single values: dla_option_table().
struct DlaOptions {
  std::size_t particles = 10000;     //!< particles to attach, seeds not counted
  double spacing = 1.0;              //!< distance between a particle and its parent, and the
                                     //!< contact distance: no two particles come closer;
                                     //!< in [1e-25, 1e25]
  double stickiness = 1.0;           //!< probability of sticking at a contact
  std::uint64_t rng_seed = 1;        //!< seeds every random choice of the run
  int dimensions = 3;                //!< 3, or 2 for growth in the plane z = 0
  std::vector<Vec3> seeds = {Vec3::Zero()};  //!< where the structure starts, one tree per
                                             //!< seed; within kMaxCoordinate spacings of the
                                             //!< origin
  SpawnMode spawn = SpawnMode::sphere;       //!< where walkers start
  Axis spawn_axis = Axis::z;         //!< disk spawn: the disk sits on the + side of this axis
  double disk_radius = 0.25;         //!< disk spawn: radius as a fraction of the launch radius
  std::optional<Box> spawn_box;      //!< box spawn: a fixed box; unset, the cube around the
                                     //!< launch sphere, growing with the structure
  Vec3 drift = Vec3::Zero();         //!< bias added to every step, per unit step length,
                                     //!< |drift| < 1 (gravity, wind)
  //! Bourke's rotation (`--rotate AXIS,DEGREES`): the spawn and the drift turn about this axis
  //! through the seeds' centre, by `rotate_degrees` per 1000 particles attached, as if the
  //! structure turned the other way while it grew. In 2D the axis is z.
  Axis rotate_axis = Axis::z;
  double rotate_degrees = 0.0;       //!< per 1000 particles, [-36000, 36000]; 0: no rotation
  //! With a constraint mesh grown inside: stop once this fraction of the enclosed volume lies
  //! within `fill_distance` spacings of the structure (`--fill F`), in (0, 1]; 0: grow to
  //! `particles`, which stays the cap.
  double fill = 0.0;
  double fill_distance = 3.0;        //!< spacings
  double min_step = 0.5;             //!< step length near the structure, in spacings
  IndexKind index = IndexKind::grid; //!< nearest-particle look-up
  int threads = 1;                   //!< walkers run at once, with the grid index; the
                                     //!< result is the same for every count, byte for byte
};

//! The limits validate() holds options to. Beyond them the arithmetic of the walk breaks down
//! (squared distances overflow or underflow, steps vanish in the rounding of a coordinate) or
//! a walker would take practically for ever to stick. The spacing's limits also keep every
//! position (up to kMaxCoordinate spacings out) a normal float, as the PLY and glTF hold them.
inline constexpr double kMinSpacing = 1e-25, kMaxSpacing = 1e25;
inline constexpr double kMinStickiness = 1e-4;  //!< ~10^4 contacts a particle at the least
inline constexpr double kMinMinStep = 0.01;     //!< ~10^4 near steps a spacing at the most
inline constexpr double kMaxDiskRadius = 1000.0;
//! Largest distance, in spacings, of a seed or a spawn box corner from the origin: a double
//! then still resolves a ten-millionth of a spacing.
inline constexpr double kMaxCoordinate = 1e9;

//! Whether walkers of this mode start from a constraint mesh, so that growth needs one.
constexpr bool spawns_from_mesh(SpawnMode mode) {
  return mode == SpawnMode::inside || mode == SpawnMode::radial || mode == SpawnMode::surface;
}

//! The largest rng seed: every seed up to it is a double's, so the studio's JavaScript and any
//! JSON reader hold it exactly.
inline constexpr double kMaxRngSeed = 1e15;

//! `rng_seed`, as every model describes it.
template <class Options>
DescribedOption<Options> rng_seed_option(std::uint64_t Options::*member, std::string_view group) {
  return integer("rng_seed", member, closed(0, kMaxRngSeed), "", group,
                 "seed of the random generator: the same seed gives the same files");
}

//! DLA's walk options that are single values, described once (option_description.h): the CLI,
//! Python, validate() and `dla3d options` read it.
inline const OptionTable<DlaOptions>& dla_option_table() {
  using O = DlaOptions;
  static const OptionTable<O> table{
      real("stickiness", &O::stickiness, closed(kMinStickiness, 1.0), "", "Growth",
           "probability of sticking at a contact"),
      integer("dimensions", &O::dimensions, closed(2, 3), "", "Growth", "3, or 2 for growth in the plane z = 0"),
      rng_seed_option(&O::rng_seed, "Growth"),
      real("min_step", &O::min_step, closed(kMinMinStep, 1.0), "spacings", "Growth",
           "step length next to the structure"),
      word("index", &O::index, "Growth", "nearest-particle look-up (docs/spatial-index.md)"),
      speed_only(integer("threads", &O::threads, closed(1, 256), "", "Growth",
                         "walkers run at once (grid index); the files do not depend on it")),
      word("spawn_axis", &O::spawn_axis, "Spawn", "disk: the axis the disk sits on"),
      real("disk_radius", &O::disk_radius, open_closed(0.0, kMaxDiskRadius), "", "Spawn",
           "disk: radius as a fraction of the launch radius"),
      real("fill", &O::fill, closed(1e-6, 1.0), "", "Mesh constraint",
           "grow until this fraction of the mesh's volume lies within --fill-distance of the structure; -n then "
           "caps it (default 1e7)",
           SpecialValue{0.0, "grow to the particle count"}),
      real("fill_distance", &O::fill_distance, closed(0.5, 1000.0), "spacings", "Mesh constraint",
           "--fill: how near counts as covered"),
      box_corners("box", &O::spawn_box, "Spawn", "box: a fixed box; default: the cube around the launch sphere"),
      vector3("drift", &O::drift, "Spawn", "bias of every step, per unit step length, length < 1"),
      parsed<O>(
          "rotate", OptionKind::text, "AXIS,DEGREES", "Spawn",
          "turn the spawn and the drift about the seeds' centre by DEGREES per 1000 particles, as if the structure "
          "turned while it grew: spirals; no mesh",
          [](O& o, const std::string& words) {
            if (words.empty()) return void(o.rotate_degrees = 0.0);
            const std::size_t comma = words.find(',');
            if (comma == std::string::npos) throw InvalidInput("`rotate` '" + words + "' is not AXIS,DEGREES (as y,30)");
            try {
              o.rotate_axis = parse_word<Axis>(words.substr(0, comma));
            } catch (const InvalidInput&) {
              throw InvalidInput("`rotate` '" + words + "': its axis is not one of " + accepted_words<Axis>());
            }
            o.rotate_degrees = detail::numbers_in("rotate", std::string_view(words).substr(comma + 1), 1)[0];
          },
          [](const O& o) {
            return o.rotate_degrees == 0.0
                       ? std::string()
                       : std::string(to_string(o.rotate_axis)) + "," + detail::exact_number(o.rotate_degrees);
          }),
  };
  return table;
}

//! Throws InvalidInput with a one-line message at the first option that cannot work.
void validate(const DlaOptions& options);

// ---------------------------------------------------------------------------------------------

namespace detail {
//! A count with its thousands grouped: "64,687".
inline std::string format_count(std::uint64_t value) {
  std::string digits = std::to_string(value);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(static_cast<std::size_t>(i), ",");
  return digits;
}

//! Throws InvalidInput "WHAT VALUE is not in [LOW, HIGH]" unless low <= value <= high (NaN
//! never is).
inline void require_in(const std::string& what, double value, double low, double high) {
  if (!(value >= low && value <= high))
    throw InvalidInput(what + " " + format_number(value) + " is not in [" + format_number(low) + ", " +
                       format_number(high) + "]");
}

//! Throws InvalidInput unless every coordinate of `point` is finite and within
//! kMaxCoordinate spacings of the origin.
inline void require_representable(const std::string& what, const Vec3& point, double spacing) {
  if (!point.allFinite()) throw InvalidInput(what + " is not finite");
  if (point.cwiseAbs().maxCoeff() > kMaxCoordinate * spacing)
    throw InvalidInput(what + " lies more than " + format_number(kMaxCoordinate) +
                       " spacings from the origin, beyond what double precision resolves");
}

//! Throws InvalidInput unless there are seeds, each representable, in z = 0 for 2D, and no two
//! closer than the spacing: what every model that starts from seeds asks of them.
inline void validate_seeds(const std::vector<Vec3>& seeds, double spacing, int dimensions) {
  if (seeds.empty()) throw InvalidInput("there is no seed");
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const Vec3& s = seeds[i];
    require_representable("seed " + std::to_string(i + 1), s, spacing);
    if (dimensions == 2 && s.z() != 0.0)
      throw InvalidInput("seed " + std::to_string(i + 1) + " has z = " + format_number(s.z()) +
                         " but growth in 2 dimensions is in the plane z = 0");
  }
  // Pairs closer than the spacing, swept along x: a surface's thousands of seeds (--seed-surface)
  // in a moment.
  std::vector<std::size_t> order(seeds.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return seeds[a].x() < seeds[b].x(); });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && seeds[order[j]].x() - seeds[order[i]].x() < spacing; ++j)
      if ((seeds[order[j]] - seeds[order[i]]).norm() < spacing)
        throw InvalidInput("seeds " + std::to_string(std::min(order[i], order[j]) + 1) + " and " +
                           std::to_string(std::max(order[i], order[j]) + 1) + " are closer than the spacing " +
                           format_number(spacing));
}

//! What DLA, drop and ballistic ask of their scale and start: a count their 32-bit parents can
//! hold, a spacing in range, 2 or 3 dimensions, and seeds as validate_seeds() asks.
inline void validate_seeded(std::size_t particles, const std::vector<Vec3>& seeds, double spacing, int dimensions) {
  if (particles + seeds.size() > 2'000'000'000u)
    throw InvalidInput("particles " + std::to_string(particles) + " is more than 2e9");
  require_in("spacing", spacing, kMinSpacing, kMaxSpacing);
  if (dimensions != 2 && dimensions != 3) throw InvalidInput("dimensions " + std::to_string(dimensions) + " is not 2 or 3");
  validate_seeds(seeds, spacing, dimensions);
}
}  // namespace detail

inline void validate(const DlaOptions& o) {
  using detail::format_number;
  detail::validate_seeded(o.particles, o.seeds, o.spacing, o.dimensions);
  require_in_ranges(dla_option_table(), o);
  if (o.dimensions == 2 && o.spawn == SpawnMode::disk && o.spawn_axis == Axis::z)
    throw InvalidInput("the disk spawn axis must be x or y in 2 dimensions");
  if (o.spawn_box) {
    const Box& b = *o.spawn_box;
    detail::require_representable("spawn box's min corner", b.min, o.spacing);
    detail::require_representable("spawn box's max corner", b.max, o.spacing);
    const int axes = o.dimensions;
    for (int a = 0; a < axes; ++a)
      if (!(b.min[a] < b.max[a]))
        throw InvalidInput("spawn box is empty: its min corner is not below its max corner");
  }
  if (!o.drift.allFinite() || !(o.drift.norm() < 1.0))
    throw InvalidInput("drift length " + format_number(o.drift.norm()) + " is not below 1");
  if (o.dimensions == 2 && o.drift.z() != 0.0)
    throw InvalidInput("drift has a z component but growth in 2 dimensions is in the plane z = 0");
  detail::require_in("rotation, in degrees per 1000 particles,", o.rotate_degrees, -36000.0, 36000.0);
  if (o.dimensions == 2 && o.rotate_degrees != 0.0 && o.rotate_axis != Axis::z)
    throw InvalidInput("growth in 2 dimensions turns about z, not " + std::string(to_string(o.rotate_axis)));
  if (o.threads > 1 && o.index != IndexKind::grid)
    throw InvalidInput("threads above 1 need the grid index, not " + std::string(to_string(o.index)));
}

}  // namespace dla
