// DLA's run (run.h): its options checked, the mesh or text read and the defaults they give
// taken, the seeds placed; grown, summed up and recorded.

#include "dla_run.h"

namespace dla {

DlaOptions walk_options(const DlaRunOptions& o) {
  DlaOptions g = o.growth;
  if (o.particles) g.particles = *o.particles;
  if (o.spacing) g.spacing = *o.spacing;
  if (o.spawn) g.spawn = *o.spawn;
  if (o.seed_at) g.seeds = *o.seed_at;
  return g;
}

const OptionTable<DlaRunOptions>& dla_run_option_table() {
  using O = DlaRunOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{
        override_of(detail::particles_option(&DlaOptions::particles, "Growth",
                                             "particles to attach, seeds not counted; with a mesh, default 30000"),
                    &O::particles),
        override_of(detail::spacing_option(&DlaOptions::spacing, "Growth",
                                           "distance between a particle and its parent; also the contact distance; "
                                           "with a mesh, default: its longest side / 100"),
                    &O::spacing),
        detail::seed_at_option(&O::seed_at, "Growth"),
    };
    const auto add = [&t](const auto& rows) { t.insert(t.end(), rows.begin(), rows.end()); };
    add(nested(links_option_table(), &O::links));
    // The spawn heads its group, which the walk's table goes on with.
    t.push_back(override_of(word("spawn", &DlaOptions::spawn, "Spawn",
                                 "where walkers start; radial, inside and surface with a mesh inside; with --side "
                                 "inside, default surface"),
                            &O::spawn));
    add(nested(dla_option_table(), &O::growth));
    add(OptionTable<O>{
        detail::stl_option(&O::stl),
        excluding(parsed<O>(
            "text", OptionKind::text, "TEXT", "Mesh constraint",
            "grow in this text, extruded a quarter of its size (lines split at \\n): a mesh, as --stl's; one seed "
            "in each letter",
            [](O& o, const std::string& words) {
              if (!o.text) o.text = TextOptions{};
              o.text->text = words;
              // "\n" typed in a shell is a line break.
              for (std::size_t at = o.text->text.find("\\n"); at != std::string::npos; at = o.text->text.find("\\n", at + 1))
                o.text->text.replace(at, 2, "\n");
            },
            [](const O& o) { return o.text ? o.text->text : std::string(); }),
            {"stl"}),
        parsed<O>(
            "font", OptionKind::file, "FILE", "Mesh constraint", "--text's font: a TrueType or OpenType file",
            [](O& o, const std::string& path) {
              if (!o.text) o.text = TextOptions{};
              o.text->font = path;
            },
            [](const O& o) { return o.text ? o.text->font : std::string(kDefaultFont); }),
    });
    add(nested(constraint_option_table(), &O::constraint));
    add(nested(mesh_seeds_option_table(), &O::seeds));
    t.push_back(detail::scene_mesh_option(&O::scene_mesh));
    return t;
  }();
  return table;
}

void validate(const DlaRunOptions& o) {
  const bool mesh = o.has_mesh();
  require_in_ranges(dla_run_option_table(), o);
  if (!o.stl.empty() && o.text) throw InvalidInput("`stl` and `text` are both the mesh to grow in: give one");
  if (o.text && o.text->text.empty()) throw InvalidInput("`text` is empty: give the text to grow in (`font` is its font)");
  validate(o.files, o.growth.dimensions, mesh);
  detail::validate_links(o.links);
  if (o.growth.fill == 0.0 && o.growth.fill_distance != DlaOptions{}.fill_distance)
    throw InvalidInput("`fill_distance` is for `fill`");
  if (o.growth.spawn_box && o.spawn.value_or(o.growth.spawn) != SpawnMode::box)
    throw InvalidInput("`box` is for `spawn` box, not `spawn` " + std::string(to_string(o.spawn.value_or(o.growth.spawn))));
  detail::validate_mesh_seeds(o.seeds, mesh, "seed_at");
  if (!mesh) {
    if (o.constraint.shell != 0.0) throw InvalidInput("`shell` keeps growth near a mesh's surface: give one with `stl`");
    const DlaOptions growth = walk_options(o);
    validate(growth);
    if (spawns_from_mesh(growth.spawn))
      throw InvalidInput("spawn " + std::string(to_string(growth.spawn)) + " needs a mesh (`stl`)");
    if (growth.fill != 0.0) throw InvalidInput("`fill` fills a mesh's volume: give one with `stl`");
    return;
  }
  if (o.constraint.shell != 0.0) detail::require_in("`shell`", o.constraint.shell, 1.0, 1000.0);
  if (o.seed_at && o.seeds.count) throw InvalidInput("`seeds` and `seed_at` both place the seeds: give one");
  if (o.seed_at && o.seeds.on_surface())
    throw InvalidInput("`seed_at` and `seed_surface`, `seed_paint` or `seed_mesh` both place the seeds: give one");
  if (o.spacing) detail::require_in("spacing", *o.spacing, kMinSpacing, kMaxSpacing);
}

namespace detail {

std::unique_ptr<Run> prepare_dla(const DlaRunOptions& options, const MeshReader& read, const Resumed& resumed) {
  return std::make_unique<DlaRun>(options, read, resumed);
}

}  // namespace detail

}  // namespace dla
