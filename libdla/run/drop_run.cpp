// The random-drop model's run (run.h): its options checked, the mesh read and the defaults
// it gives taken, the seeds placed; grown, summed up and recorded.

#include "model_runs.h"

#include "dla/mesh/mesh.h"

#include <cstdio>

namespace dla {

const OptionTable<DropRunOptions>& drop_run_option_table() {
  using O = DropRunOptions;
  static const OptionTable<O> table = [] {
    constexpr std::string_view group = "Random drops";
    OptionTable<O> t = nested(
        OptionTable<DropOptions>{
            detail::particles_option(&DropOptions::particles, group),
            detail::dimensions_option(&DropOptions::dimensions, group),
            rng_seed_option(&DropOptions::rng_seed, group),
        },
        &O::drop);
    const auto add = [&t](const OptionTable<O>& rows) { t.insert(t.end(), rows.begin(), rows.end()); };
    add(OptionTable<O>{
        override_of(detail::spacing_option(&DropOptions::spacing, group,
                                           "distance between a particle and its parent; also the contact distance; "
                                           "with a mesh, default: its longest side / 100"),
                    &O::spacing),
        detail::seed_at_option(&O::seed_at, group),
    });
    add(in_group(nested(links_option_table(), &O::links), group));
    add(nested(drop_option_table(), &O::drop));
    add(nested(
        OptionTable<DropOptions>{
            real("zone_radius", &DropOptions::zone_radius, open_closed(0, 1e15), "scene units", group,
                 "ball: a fixed radius about the seeds' centre, 1 to 1e6 spacings",
                 SpecialValue{0.0, "growing, --zone-margin beyond the farthest particle"}),
            box_corners("zone_box", &DropOptions::zone_box, group,
                        "box: a fixed box; default: the square or cube around the ball"),
            parsed<DropOptions>(
                "drop", OptionKind::text, "uniform|circle|same:N|offset:N,R", group,
                "uniform; circle (on the zone's edge); same:N (N drops at one point); offset:N,R (N more, each "
                "within R of the last)",
                [](DropOptions& o, const std::string& words) { o.bias = parse_drop_bias(words); },
                [](const DropOptions& o) { return to_string(o.bias); }),
        },
        &O::drop));
    t.push_back(detail::stl_option(&O::stl));
    for (const DescribedOption<O>& row : nested(constraint_option_table(), &O::constraint))
      if (row.about.name != "shell") t.push_back(row);  // drops fall through space
    add(nested(mesh_seeds_option_table(), &O::seeds));
    t.push_back(detail::scene_mesh_option(&O::scene_mesh));
    return t;
  }();
  return table;
}

void validate(const DropRunOptions& d) {
  require_in_ranges(drop_run_option_table(), d);
  const bool mesh = !d.stl.empty();
  detail::validate_mesh_seeds(d.seeds, mesh, "seed_at");
  if (d.seed_at && (d.seeds.count || d.seeds.on_surface()))
    throw InvalidInput("`seed_at` and `seeds`, `seed_surface`, `seed_paint` or `seed_mesh` both place the seeds: give one");
  if (d.drop.zone == DropZone::mesh && !mesh) throw InvalidInput("`zone` mesh drops inside a mesh: give one with `stl`");
  const ConstraintOptions unset;
  if (!mesh && (d.constraint.side != unset.side || d.constraint.mode != unset.mode))
    throw InvalidInput("`side` and `constraint` say how `stl`'s mesh constrains growth: give one");
  if (!mesh || d.spacing) {  // else once the mesh gives the spacing
    DropOptions drop = d.drop;
    if (d.spacing) drop.spacing = *d.spacing;
    if (d.seed_at) drop.seeds = *d.seed_at;
    validate(drop);
  }
  validate(d.files, d.drop.dimensions, mesh);
  detail::validate_links(d.links);
}

namespace detail {

namespace {

//! Random-drop ballistic aggregation, in or around a mesh if one is given.
class DropRun : public Run {
 public:
  DropRun(const DropRunOptions& o, const MeshReader& read) : options_(o.drop) {
    if (o.spacing) options_.spacing = *o.spacing;
    if (o.seed_at) options_.seeds = *o.seed_at;
    if (o.stl.empty()) {
      files = resolve(o.files, nullptr, false);
    } else {
      // As for DLA: the spacing and the up axis from the mesh's box, one seed on the growing side.
      const TriangleMesh mesh = read(o.stl, nullptr);
      const Box box = bounding_box(mesh);
      if (!o.spacing) options_.spacing = default_spacing(box);
      files = resolve(o.files, &box, false);
      detail::require_in("spacing", options_.spacing, kMinSpacing, kMaxSpacing);
      const std::vector<TriangleMesh> entering = read_all(read, o.seeds.meshes);
      named(o.stl, [&] {
        constraint_ = std::make_unique<MeshConstraint>(mesh, o.constraint, options_.spacing);
        if (!o.seed_at) options_.seeds = seeds_on(*constraint_, o.seeds, options_.rng_seed, entering);
        validate(options_, *constraint_);
      });
      if (!entering.empty() && o.scene_mesh) scene_mesh_ = with_entering(constraint_->mesh(), entering);
      mesh_line = detail::mesh_line(o.stl, *constraint_, options_.spacing);
    }
    total = options_.seeds.size() + options_.particles;
    links = o.links;
    constraint = constraint_.get();
    scene_mesh = !scene_mesh_.triangles.empty() ? &scene_mesh_ : constraint_ && o.scene_mesh ? &constraint_->mesh() : nullptr;
  }

  Cluster grow(const ProgressFn& progress, const StopFlag* stop) override {
    return dla::drop(options_, constraint_.get(), progress, stop, &stats_);
  }

  std::string summary(const Cluster& cluster, const RunRecord& record) const override {
    char line[320];
    std::snprintf(line, sizeof line,
                  "grew %s particles from %s drops in %.2f s%s; %s fell on the structure; bounding radius %.1f",
                  with_commas(static_cast<double>(attached(cluster))).c_str(),
                  with_commas(static_cast<double>(stats_.drops)).c_str(), record.grow_seconds,
                  stats_.zone_full ? " (then the drop zone was full)" : "",
                  with_commas(static_cast<double>(stats_.on_structure)).c_str(), bounding_radius(cluster));
    return line;
  }

  std::vector<Link> make_links(const Cluster& cluster, const StageWatch& watch) const override {
    return links_inside(cluster, links, threads, constraint_.get(), watch);
  }

  //! The spacing a mesh gives.
  void put_resolved(RunOptions& options) const override { options.get<DropRunOptions>().spacing = options_.spacing; }

  ModelRecord own_record() const override {
    ModelRecord out{model, options_.rng_seed};
    out.resolved = [this](RecordWriter& w) { w.points("seed_at", options_.seeds); };
    out.statistics = [this](RecordWriter& w) {
      const DropStats& s = stats_;
      w.open("drops")
          .counts({{"drops", s.drops}, {"on_structure", s.on_structure}, {"refused", s.refused}, {"lost", s.lost},
                   {"mesh_rejected", s.mesh_rejected}, {"clipped", s.clipped}})
          .flag("zone_full", s.zone_full)
          .close();
    };
    return out;
  }

 private:
  DropOptions options_;
  std::unique_ptr<MeshConstraint> constraint_;
  TriangleMesh scene_mesh_;  // the scene's mesh when it is more than the constraint's
  DropStats stats_;
};

}  // namespace

std::unique_ptr<Run> prepare_drop(const DropRunOptions& options, const MeshReader& read, const Resumed&) {
  return std::make_unique<DropRun>(options, read);
}

}  // namespace detail

}  // namespace dla
