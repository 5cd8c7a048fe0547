// Space colonization's run (run.h): its options checked, the vessel and collision mesh read,
// the attractors scattered or read and the roots placed; grown, summed up and recorded.

#include "model_runs.h"

#include "dla/core/memory.h"
#include "dla/core/random.h"
#include "dla/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace dla {

namespace {

std::string point_text(const Vec3& p) {
  return detail::format_number(p.x()) + "," + detail::format_number(p.y()) + "," + detail::format_number(p.z());
}

//! K roots at random on the sphere around the attractors: the scattering sphere, or the one
//! around the box they lie in (the Hyphae write-up's third test); in z = 0 for 2D.
std::vector<Vec3> roots_around(const ColonizeRunOptions& c, const std::vector<Vec3>& attractors, Rng& rng) {
  const AttractorOptions& a = c.attractors;
  const bool scattered =
      c.attractors_from.empty() && (a.region == AttractorRegion::sphere || a.region == AttractorRegion::box);
  Vec3 lo = a.box_min, hi = a.box_max;
  if (!scattered) {
    lo = hi = attractors.front();
    for (const Vec3& p : attractors) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const bool sphere = scattered && a.region == AttractorRegion::sphere;
  const Vec3 center = sphere ? a.center : Vec3(0.5 * (lo + hi));
  double radius = sphere ? a.radius : 0.5 * (hi - lo).norm();
  const int dimensions = c.colonization.dimensions;
  if (dimensions == 2 && !sphere) radius = 0.5 * (hi - lo).head<2>().norm();
  radius *= c.roots_scale;
  std::vector<Vec3> roots;
  for (std::size_t k = 0; k < c.root_count; ++k) {
    Vec3 root = center + radius * random_direction(rng, dimensions);
    if (dimensions == 2) root.z() = 0.0;
    roots.push_back(root);
  }
  return roots;
}

//! Where one root starts by default: the lowest point (along y) of the scattering sphere or
//! box, or else the lowest attractor.
Vec3 lowest_point(const ColonizeRunOptions& c, const std::vector<Vec3>& attractors) {
  const AttractorOptions& a = c.attractors;
  if (c.attractors_from.empty() && a.region == AttractorRegion::sphere) return a.center - Vec3(0.0, a.radius, 0.0);
  if (c.attractors_from.empty() && a.region == AttractorRegion::box)
    return {0.5 * (a.box_min.x() + a.box_max.x()), a.box_min.y(), 0.5 * (a.box_min.z() + a.box_max.z())};
  return *std::min_element(attractors.begin(), attractors.end(),
                           [](const Vec3& p, const Vec3& q) { return p.y() < q.y(); });
}

}  // namespace

std::vector<Vec3> colonize_roots(const ColonizeRunOptions& options, const std::vector<Vec3>& attractors,
                                 const MeshConstraint* mesh) {
  if (!options.root_at.empty()) return options.root_at;
  if (options.root_count == 0) {
    Vec3 root = lowest_point(options, attractors);
    if (options.colonization.dimensions == 2) root.z() = 0.0;
    return {root};
  }
  Rng rng(options.colonization.rng_seed, 0x726f6f7473ULL);  // a stream of its own: "roots"
  if (options.roots_in == RootRegion::sphere) return roots_around(options, attractors, rng);
  if (!mesh)
    throw InvalidInput("`roots_in` " + std::string(to_string(options.roots_in)) + " needs a mesh: `stl` or `collide`");
  std::vector<Vec3> roots;
  for (std::size_t k = 0; k < options.root_count; ++k)
    roots.push_back(options.roots_in == RootRegion::mesh ? mesh->draw_inside(rng) : mesh->draw_near_surface(rng));
  return roots;
}

namespace {

//! `influence`: 0 given or shown for the unbounded default (infinity, which JSON has not).
DescribedOption<ColonizationOptions> influence_option(std::string_view group) {
  using O = ColonizationOptions;
  DescribedOption<O> row = real("influence", &O::influence, open_closed(0, 1e6), "spacings", group,
                                "an attractor pulls its nearest node only this close, above the kill distance",
                                SpecialValue{0.0, "any; with --venation closed, 4 times --kill-distance"});
  row.set = [about = row.about](O& o, const OptionValue& v) {
    const double value = detail::number_of(about.name, v);
    require_in(about, value);
    o.influence = value == 0.0 ? std::numeric_limits<double>::infinity() : value;
  };
  row.get = [](const O& o) { return OptionValue(std::isinf(o.influence) ? 0.0 : o.influence); };
  return row;
}

}  // namespace

const OptionTable<ColonizeRunOptions>& colonize_option_table() {
  using O = ColonizeRunOptions;
  static const OptionTable<O> table = [] {
    constexpr std::string_view colonizing = "Colonization", attracting = "Attractors and roots",
                               colliding = "Vessel and collision";
    using C = ColonizationOptions;
    OptionTable<O> rows = nested(
        OptionTable<C>{
            with_short_name(integer("max_nodes", &C::max_nodes, closed(1, 2e9), "", colonizing,
                                    "nodes at most, roots included"),
                            "n"),
            integer("max_iterations", &C::max_iterations, closed(1, 1e12), "", colonizing, "growth steps at most"),
            detail::spacing_option(&C::spacing, colonizing, "the step: distance between a node and its parent"),
            influence_option(colonizing),
            parsed<C>(
                "noise", OptionKind::text, "A,S", colonizing,
                "each new node moves by up to A spacings, in features S spacings wide; A in [0, 10], S > 0",
                [](C& o, const std::string& words) {
                  const std::vector<double> n = detail::numbers_in("noise", words, 2);
                  o.noise_amplitude = n[0];
                  o.noise_scale = n[1];
                },
                [](const C& o) {
                  return detail::exact_number(o.noise_amplitude) + "," + detail::exact_number(o.noise_scale);
                }),
            vector3("tropism", &C::tropism, colonizing,
                    "added to each step's unit direction (gravity, light), each in [-10, 10]"),
            rng_seed_option(&C::rng_seed, colonizing),
        },
        &O::colonization);
    const auto add = [&rows](const OptionTable<O>& more) { rows.insert(rows.end(), more.begin(), more.end()); };
    add(nested(colonization_option_table(), &O::colonization));
    using A = AttractorOptions;
    // A count given with --attractors-from asks for a sample of the file's.
    DescribedOption<O> count = nested(
        OptionTable<A>{integer("attractors", &A::count, closed(1, static_cast<double>(kMaxAttractors)), "", attracting,
                               "how many attractors; with --attractors-from, a seeded sample of that many")},
        &O::attractors)[0];
    count.set = [set = count.set](O& o, const OptionValue& v) {
      set(o, v);
      o.sample_attractors = true;
    };
    rows.push_back(count);
    add(nested(attractor_option_table(), &O::attractors));
    add(OptionTable<O>{
        excluding(file("attractors_from", &O::attractors_from, "FILE", attracting,
                       "read them from a file: CSV rows x,y,z (or a header naming x, y, z) or PLY points"),
                  {"attractors_in"}),
    });
    add(nested(
        OptionTable<A>{
            vector3("attractor_center", &A::center, attracting, "the sphere's centre"),
            parsed<A>(
                "attractor_box", OptionKind::vector, "X0,Y0,Z0,X1,Y1,Z1", attracting, "the box",
                [](A& o, const std::string& words) {
                  const std::vector<double> b = detail::numbers_in("attractor_box", words, 6);
                  o.box_min = Vec3(b[0], b[1], b[2]);
                  o.box_max = Vec3(b[3], b[4], b[5]);
                },
                [](const A& o) { return detail::point_words(o.box_min) + "," + detail::point_words(o.box_max); }),
            excluding(needing(with_paint_role(colour("attractor_paint", &A::paint, attracting,
                                                     "with --attractors-in surface: only on the part of the --stl or "
                                                     "--collide mesh painted this colour (a name or ff8000), within "
                                                     "TOLERANCE per channel, [0, 1), default 0.3"),
                                              PaintRole::attractors),
                              "attractors_in", "surface"),
                      {"attractors_from"}),
        },
        &O::attractors));
    add(OptionTable<O>{
        point_list("root_at", &O::root_at, attracting,
                   "a root at x,y,z (repeat for several); default: one at the attractors' lowest point (-y)"),
        excluding(integer("roots", &O::root_count, closed(1, 1e6), "", attracting,
                          "K roots at random, where --roots-in says",
                          SpecialValue{0.0, "one at the attractors' lowest point, unless --root-at or --seeds"}),
                  {"root_at"}),
        word("roots_in", &O::roots_in, attracting,
             "--roots K: on the sphere around the attractors, in the mesh (the vessel, else the collision mesh) or on "
             "its surface"),
        real("roots_scale", &O::roots_scale, closed(0.01, 100), "", attracting,
             "--roots-in sphere: the roots' sphere is this times the attractors'"),
        file("stl", &O::stl, kMeshFileForm, colliding,
             "a vessel (STL, OFF, OBJ or PLY) that growth stays inside: a step that would cross its surface is refused"),
        file("collide", &O::collide, kMeshFileForm, colliding,
             "a collision mesh (STL, OFF, OBJ or PLY) that new nodes are pushed out of or stuck to"),
        word("collision", &O::collision, colliding,
             "push (growth flows around the mesh) or stick (it crawls over its surface)"),
    });
    add(nested(mesh_seeds_option_table(true), &O::seeds));
    return rows;
  }();
  return table;
}

void validate(const ColonizeRunOptions& c) {
  require_in_ranges(colonize_option_table(), c);
  const ColonizationOptions& o = c.colonization;
  validate(c.files, o.dimensions, !c.stl.empty());
  if (c.roots_in != RootRegion::sphere && c.root_count == 0)
    throw InvalidInput("`roots_in` says where `roots` K puts its roots: give `roots`");
  if (c.roots_scale != 1.0 && (c.root_count == 0 || c.roots_in != RootRegion::sphere))
    throw InvalidInput("`roots_scale` sizes the sphere of `roots` K (`roots_in` sphere): give `roots`");
  if (!c.root_at.empty() && c.root_count)
    throw InvalidInput("`root_at` and `roots` both place the roots: give one");
  detail::validate_mesh_seeds(c.seeds, !c.stl.empty() || !c.collide.empty(), "root_at");
  if ((c.seeds.count || c.seeds.on_surface()) && (!c.root_at.empty() || c.root_count))
    throw InvalidInput("`seeds`, `seed_surface`, `seed_paint` and `seed_mesh` place the roots on the mesh; `root_at` "
                       "and `roots` elsewhere: give one");
  const bool on_mesh = c.attractors.region == AttractorRegion::mesh || c.attractors.region == AttractorRegion::surface;
  if ((on_mesh || c.roots_in != RootRegion::sphere) && c.stl.empty() && c.collide.empty())
    throw InvalidInput("attractors or roots in a mesh need one: give `stl` or `collide`");
  const AttractorOptions unset;
  if (c.attractors.region != AttractorRegion::box && (c.attractors.box_min != unset.box_min || c.attractors.box_max != unset.box_max))
    throw InvalidInput("`attractor_box` is for `attractors_in` box, not " + std::string(to_string(c.attractors.region)));
  if (!c.attractors_from.empty() && c.attractors.paint)
    throw InvalidInput("`attractor_paint` picks where `attractors_in` surface scatters them; `attractors_from` reads "
                       "them: give one");
  if (!c.attractors_from.empty() && c.attractors.region != AttractorOptions{}.region)
    throw InvalidInput("`attractors_from` reads the attractors; `attractors_in` scatters them: give one");
  if (!c.stl.empty() && o.dimensions != 3) throw InvalidInput("`stl` needs 3 dimensions");
  if (c.collision != CollisionMode::push && c.collide.empty())
    throw InvalidInput("`collision` says what `collide`'s mesh does: give one");
  if (!c.collide.empty() && o.dimensions != 3) throw InvalidInput("`collide` needs 3 dimensions");
  validate(o);
  validate(c.attractors);
  if (o.dimensions == 2) {
    if (c.attractors.center.z() != 0.0)
      throw InvalidInput("`dimensions` 2 grows in z = 0: the attractors' centre is not");
    for (const Vec3& r : c.root_at)
      if (r.z() != 0.0) throw InvalidInput("`dimensions` 2 grows in z = 0: a `root_at` is not");
  }
  if (c.root_count > o.max_nodes || c.root_at.size() > o.max_nodes)
    throw InvalidInput("more roots than `max_nodes`");
  for (const Vec3& r : c.root_at) detail::require_representable("`root_at` " + point_text(r), r, o.spacing);
}

namespace detail {

namespace {

//! Refuses closed venation among more attractors than this machine's memory holds: each keeps
//! its neighbourhood and its cells, about 200 bytes with its share of the nodes.
void check_closed_memory(std::size_t attractors) {
  constexpr double kBytesPerAttractor = 200.0;
  const double memory = installed_memory();
  const double needed = kBytesPerAttractor * static_cast<double>(attractors);
  if (memory > 0 && needed > memory)
    throw InvalidInput("`venation` closed among " + format_count(attractors) + " attractors needs about " +
                       format_number(needed / 1e9) + " GB of memory; this machine has " + format_number(memory / 1e9) +
                       " GB: " + format_count(static_cast<std::size_t>(memory / kBytesPerAttractor)) + " attractors fit");
}

//! What closed venation will take, where it is long: each node taken in looks at every source
//! within the influence, a share of the attractors' box as the influence's ball is of it.
std::string closed_forecast(const std::vector<Vec3>& attractors, const ColonizationOptions& o) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& a : attractors) lo = lo.cwiseMin(a), hi = hi.cwiseMax(a);
  const double reach = influence_of(o) * o.spacing;
  const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(o.spacing));
  const double box = o.dimensions == 2 ? extent.x() * extent.y() : extent.prod();
  const double ball = o.dimensions == 2 ? 3.14159 * reach * reach : 4.18879 * reach * reach * reach;
  const double pairs = static_cast<double>(o.max_nodes) * static_cast<double>(attractors.size()) * std::min(1.0, ball / box);
  if (attractors.empty() || pairs < 1e10) return "";
  return "`venation` closed may look at up to " + format_number(std::round(pairs / 1e8) / 10.0) +
         " billion node-source pairs within the `influence` of " + format_number(influence_of(o)) + " spacings, " +
         time_for_pairs(pairs) + "; a smaller `influence` looks at fewer";
}

//! Space colonization among attractors scattered or read from a file.
class ColonizeRun : public Run {
 public:
  ColonizeRun(const ColonizeRunOptions& o, const MeshReader& read)
      : options_(o.colonization) {
    files = resolve(o.files, nullptr, false);
    unit = "nodes";
    total = options_.max_nodes;
    grown_with_ = options_;
    if (!o.stl.empty()) {
      vessel_ = with_mesh(read, o.stl, [&](const TriangleMesh& mesh) {
        const ConstraintOptions inside{Side::inside, ConstraintMode::reject};
        return std::make_unique<MeshConstraint>(mesh, inside, options_.spacing);
      });
      grown_with_.vessel = vessel_.get();
    }
    if (!o.collide.empty()) {
      collide_ = with_mesh(read, o.collide, [&](const TriangleMesh& mesh) {
        return std::make_unique<CollisionObject>(mesh, options_.spacing, o.collision);
      });
      grown_with_.collide = collide_.get();
    }
    // Attractors and roots in or on "the mesh": the vessel's, else the collision object's.
    const MeshConstraint* mesh = vessel_ ? vessel_.get() : collide_ ? &collide_->solid() : nullptr;
    if (o.attractors_from.empty()) {
      attractors_ = scatter_attractors(o.attractors, options_.rng_seed, options_.dimensions, mesh);
    } else {
      attractors_ = read_points(o.attractors_from);
      if (o.sample_attractors) attractors_ = sample_attractors(attractors_, o.attractors.count, options_.rng_seed);
      if (attractors_.size() > kMaxAttractors) throw InvalidInput(o.attractors_from + ": more than 1e8 attractors");
      if (options_.dimensions == 2)
        for (const Vec3& a : attractors_)
          if (a.z() != 0.0)
            throw InvalidInput(o.attractors_from + ": `dimensions` 2 grows in z = 0, and an attractor is not");
    }
    if (mesh && (o.seeds.count || o.seeds.on_surface())) {
      const std::vector<TriangleMesh> entering = read_all(read, o.seeds.meshes);
      roots_ = named(mesh == vessel_.get() ? o.stl : o.collide,
                     [&] { return seeds_on(*mesh, o.seeds, options_.rng_seed, entering); });
      if (roots_.size() > options_.max_nodes) throw InvalidInput("more roots than `max_nodes`");
    } else {
      roots_ = colonize_roots(o, attractors_, mesh);
    }
    if (options_.venation == Venation::closed) {
      check_closed_memory(attractors_.size());
      forecast_line = closed_forecast(attractors_, options_);
    }
    attractor_count_ = attractors_.size();
    // The vessel, else the collision mesh, shows in the scene as glass, as a constraint mesh does.
    constraint = vessel_.get();
    scene_mesh = mesh ? &mesh->mesh() : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    return dla::colonize(grown_with_, std::move(attractors_), roots_, progress, stop);
  }

  std::string summary(const Cluster& tree, const RunRecord& record) const override {
    char line[256];
    std::snprintf(line, sizeof line, "grew %s nodes from %s root%s in %.2f s; bounding radius %.1f",
                  with_commas(static_cast<double>(tree.particles.size())).c_str(),
                  with_commas(static_cast<double>(tree.seed_count)).c_str(), tree.seed_count == 1 ? "" : "s",
                  record.grow_seconds, bounding_radius(tree));
    return line;
  }

  //! Closed venation's influence, when none was given.
  void put_resolved(RunOptions& options) const override {
    options.get<ColonizeRunOptions>().colonization.influence = influence_of(options_);
  }

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.resolved = [this](RecordWriter& w) { w.count("attractors", attractor_count_).points("root_at", roots_); };
    return out;
  }

 private:
  ColonizationOptions options_, grown_with_;
  std::unique_ptr<MeshConstraint> vessel_;
  std::unique_ptr<CollisionObject> collide_;
  std::vector<Vec3> attractors_, roots_;
  std::size_t attractor_count_ = 0;  // the attractors_ growth takes away
};

}  // namespace

std::unique_ptr<Run> prepare_colonize(const ColonizeRunOptions& options, const MeshReader& read, const Resumed&) {
  return std::make_unique<ColonizeRun>(options, read);
}

}  // namespace detail

}  // namespace dla
