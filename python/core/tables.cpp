// Every model's keywords: one table a model (tables.h), a keyword a field of its run options,
// spelled as the field's C++ name; what several models share is added by the functions first.

#include "tables.h"

#include <algorithm>

namespace dla::python {

namespace {

//! The look and output options every model has (the files themselves are Result.write()'s), in
//! the OutputOptions that `files` gives of the run's options.
template <class Options, class Files>
void add_look(Table<Options>& t, Files files) {
  add_described(t, output_option_table(), files);
}

template <class Options>
void add_look(Table<Options>& t) {
  add_look(t, [](Options& o) -> OutputOptions& { return o.files; });
}

//! Where seeds (colonize: roots) go on the mesh, the same for DLA, drop and colonize.
template <class O>
void add_mesh_seeds(Table<O>& t) {
  add_described(t, mesh_seeds_option_table(), [](O& o) -> MeshSeeds& { return o.seeds; });
}

//! --fill and --shell, for the models they mean nothing to: refused with why.
template <class O>
void add_refused(Table<O>& t, const char* model) {
  for (const char* option : {"fill", "shell"})
    t[option] = [model, option](O&, py::handle, Given&) { refuse_for(model, option); };
}

//! What drop and ballistic share: the look, the count, the plane, the random seed, the links.
template <class O, class Model>
void add_seeded(Table<O>& t, Model O::*model) {
  add_look(t);
  add_described(t, links_option_table(), [](O& o) -> LinkOptions& { return o.links; });
  t["particles"] = [=](O& o, py::handle v, Given&) { (o.*model).particles = count("particles", v); };
  t["dimensions"] = [=](O& o, py::handle v, Given&) { (o.*model).dimensions = whole_int("dimensions", v); };
  t["rng_seed"] = [=](O& o, py::handle v, Given&) { (o.*model).rng_seed = count("rng_seed", v); };
  t["n"] = t["particles"];
}

}  // namespace

Table<DlaRunOptions> dla_table() {
  using O = DlaRunOptions;
  Table<O> t;
  add_look(t);
  t["rng_seed"] = [](O& o, py::handle v, Given&) { o.growth.rng_seed = count("rng_seed", v); };
  add_described(t, dla_run_option_table());
  return t;
}

Table<ColonizeRunOptions> colonize_table() {
  using O = ColonizeRunOptions;
  Table<O> t;
  add_look(t);
  add_described(t, colonize_option_table());
  t["max_nodes"] = [](O& o, py::handle v, Given&) { o.colonization.max_nodes = count("max_nodes", v); };
  t["max_iterations"] = [](O& o, py::handle v, Given&) { o.colonization.max_iterations = count("max_iterations", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.colonization.spacing = number("spacing", v); };
  t["influence"] = [](O& o, py::handle v, Given&) { o.colonization.influence = number("influence", v); };
  t["noise"] = [](O& o, py::handle v, Given&) {
    const std::vector<double> n = numbers("noise", v, 2);
    o.colonization.noise_amplitude = n[0];
    o.colonization.noise_scale = n[1];
  };
  t["tropism"] = [](O& o, py::handle v, Given&) { o.colonization.tropism = vec3("tropism", v); };
  t["rng_seed"] = [](O& o, py::handle v, Given&) { o.colonization.rng_seed = count("rng_seed", v); };
  t["attractors"] = [](O& o, py::handle v, Given& g) {
    o.attractors.count = count("attractors", v);
    g.attractors = true;
  };
  t["attractors_from"] = [](O& o, py::handle v, Given&) { o.attractors_from = text("attractors_from", v); };
  t["attractor_center"] = [](O& o, py::handle v, Given&) { o.attractors.center = vec3("attractor_center", v); };
  t["attractor_box"] = [](O& o, py::handle v, Given&) {
    const Box b = box("attractor_box", v);
    o.attractors.box_min = b.min;
    o.attractors.box_max = b.max;
  };
  t["attractor_paint"] = [](O& o, py::handle v, Given&) {
    o.attractors.paint = parse_paint(text("attractor_paint", v), "attractor_paint");
  };
  t["root_at"] = [](O& o, py::handle v, Given&) { o.root_at = points("root_at", v); };
  t["roots"] = [](O& o, py::handle v, Given&) {
    if ((o.root_count = count("roots", v)) == 0) throw InvalidInput("`roots` 0: there must be a root");
  };
  t["stl"] = [](O& o, py::handle v, Given& g) { o.stl = mesh("stl", v, g); };
  t["collide"] = [](O& o, py::handle v, Given& g) { o.collide = mesh("collide", v, g); };
  add_mesh_seeds(t);
  add_refused(t, "colonize");
  t["n"] = t["max_nodes"];
  return t;
}

Table<EdenRunOptions> eden_table() {
  using O = EdenRunOptions;
  Table<O> t;
  add_look(t);
  add_described(t, links_option_table(), [](O& o) -> LinkOptions& { return o.links; });
  t["sites"] = [](O& o, py::handle v, Given&) {
    if ((o.eden.sites = count("sites", v)) == 0) throw InvalidInput("`sites` 0 is not at least 1");
  };
  t["dimensions"] = [](O&, py::handle v, Given& g) { g.eden_dimensions = whole_int("dimensions", v); };
  t["lattice"] = [](O& o, py::handle v, Given& g) {
    o.eden.lattice = word<Lattice>("lattice", v);
    g.lattice = true;
  };
  add_described(t, eden_option_table(), [](O& o) -> EdenOptions& { return o.eden; });
  t["mask"] = [](O& o, py::handle v, Given&) {
    const std::string mask = text("mask", v);
    if (mask.size() == 1 && mask.find_first_of("ABCD") == 0) o.eden.mask = parse_word<EdenMask>(mask);
    else o.mask_file = mask;
  };
  t["mask_threshold"] = [](O& o, py::handle v, Given&) { o.eden.mask_threshold = whole_int("mask_threshold", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.eden.spacing = number("spacing", v); };
  t["rng_seed"] = [](O& o, py::handle v, Given&) { o.eden.rng_seed = count("rng_seed", v); };
  t["n"] = t["sites"];
  return t;
}

Table<DropRunOptions> drop_table() {
  using O = DropRunOptions;
  Table<O> t;
  add_seeded(t, &O::drop);
  add_described(t, drop_option_table(), [](O& o) -> DropOptions& { return o.drop; });
  add_refused(t, "drop");
  t["spacing"] = [](O& o, py::handle v, Given&) { o.spacing = number("spacing", v); };
  t["seed_at"] = [](O& o, py::handle v, Given&) { o.seed_at = points("seed_at", v); };
  t["zone_radius"] = [](O& o, py::handle v, Given&) { o.drop.zone_radius = number("zone_radius", v); };
  t["zone_box"] = [](O& o, py::handle v, Given&) { o.drop.zone_box = box("zone_box", v); };
  t["drop"] = [](O& o, py::handle v, Given&) { o.drop.bias = parse_drop_bias(text("drop", v)); };
  t["stl"] = [](O& o, py::handle v, Given& g) { o.stl = mesh("stl", v, g); };
  t["side"] = [](O& o, py::handle v, Given&) { o.constraint.side = word<Side>("side", v); };
  t["constraint"] = [](O& o, py::handle v, Given&) { o.constraint.mode = word<ConstraintMode>("constraint", v); };
  t["scene_mesh"] = [](O& o, py::handle v, Given&) { o.scene_mesh = flag("scene_mesh", v); };
  add_mesh_seeds(t);
  t["mesh"] = t["stl"];
  return t;
}

Table<BallisticRunOptions> ballistic_table() {
  using O = BallisticRunOptions;
  Table<O> t;
  add_seeded(t, &O::ballistic);
  t["spacing"] = [](O& o, py::handle v, Given&) { o.ballistic.spacing = number("spacing", v); };
  t["seed_at"] = [](O& o, py::handle v, Given&) { o.ballistic.seeds = points("seed_at", v); };
  t["direction"] = [](O& o, py::handle v, Given&) {
    o.ballistic.direction = vec3("direction", v);
    if (o.ballistic.direction.squaredNorm() == 0.0) throw InvalidInput("`direction` (0, 0, 0) has no direction");
  };
  return t;
}

Table<BreakdownRunOptions> breakdown_table() {
  using O = BreakdownRunOptions;
  Table<O> t;
  // DLA's keywords, on the DLA run a breakdown run is, but those it has not.
  for (const auto& [name, set] : dla_table())
    if (std::find(kNotForBreakdown.begin(), kNotForBreakdown.end(), name) == kNotForBreakdown.end())
      t[name] = [set = set](O& o, py::handle v, Given& g) { set(o, v, g); };
  t["fill"] = [](O&, py::handle, Given&) { refuse_for("breakdown", "fill"); };
  add_described(t, breakdown_option_table(), [](O& o) -> BreakdownOptions& { return o.breakdown; });
  t["target_point"] = [](O& o, py::handle v, Given&) {
    o.breakdown.target.kind = TargetKind::point;
    o.breakdown.target.point = vec3("target_point", v);
  };
  t["target_plane"] = [](O& o, py::handle v, Given&) {
    if (py::isinstance<py::str>(v) || !py::hasattr(v, "__len__") || py::len(v) != 2)
      throw InvalidInput("`target_plane` " + shown(v) + " is not (axis, value), as ('y', -60)");
    o.breakdown.target.kind = TargetKind::plane;
    o.breakdown.target.axis = word<Axis>("target_plane", v[py::int_(0)]);
    o.breakdown.target.at = number("target_plane", v[py::int_(1)]);
  };
  t["target_mesh"] = [](O& o, py::handle v, Given& g) { o.target_mesh = mesh("target_mesh", v, g); };
  return t;
}

Table<RunOptions> described_table(const Model& model) {
  Table<RunOptions> t;
  add_look(t, [&model](RunOptions& o) -> OutputOptions& { return model.files(o); });
  add_described(t, model.option_table);
  return t;
}

}  // namespace dla::python
