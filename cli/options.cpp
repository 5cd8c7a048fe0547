#include "options.h"

#include <sstream>

namespace dla::cli {

std::vector<double> parse_numbers(const std::string& flag, const std::string& text, std::size_t count) {
  std::vector<double> values;
  bool numbers = true;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    try {
      values.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    numbers = numbers && used > 0 && used == item.size();
  }
  if (!numbers || values.size() != count)
    throw InvalidInput(flag + " '" + text + "' is not " + std::to_string(count) + " comma-separated numbers");
  return values;
}

Vec3 parse_vec3(const std::string& flag, const std::string& text) {
  const std::vector<double> v = parse_numbers(flag, text, 3);
  return {v[0], v[1], v[2]};
}

std::vector<Vec3> parse_points(const std::string& flag, const std::vector<std::string>& texts) {
  std::vector<Vec3> points;
  for (const std::string& text : texts) points.push_back(parse_vec3(flag, text));
  return points;
}

Box parse_box(const std::string& flag, const std::string& text) {
  const std::vector<double> b = parse_numbers(flag, text, 6);
  return Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
}

std::size_t parse_count(const std::string& flag, long long value) {
  if (value < 0) throw InvalidInput(flag + " " + std::to_string(value) + " is negative");
  return static_cast<std::size_t>(value);
}

OutputWords::OutputWords(CLI::App& app, OutputOptions& f, bool& quiet, std::string formats)
    : up_(to_string(f.pov.up)),
      radius_model_(to_string(f.look.radius.model)),
      color_by_(to_string(f.look.color_by)),
      instance_set_(to_string(f.instances.set)),
      pov_style_(to_string(f.pov.style)),
      ply_format_(to_string(f.ply_encoding)),
      formats_(std::move(formats)),
      solid_shape_(to_string(f.solid.shape)),
      base_radius_(f.look.radius.base_radius),
      tip_radius_(f.look.radius.tip_radius) {
  const char* outputs = "Output";
  app.add_option("-o,--output", f.output, "prefix of the files written")->capture_default_str()->group(outputs);
  app.add_option("--ply-format", ply_format_, "the PLYs as binary (little-endian) or ascii (text: twice the size, "
                                              "three times slower to write)")->capture_default_str()->group(outputs);
  // Binary became the default on 2026-11-24; the old flag still runs the scripts and resumes
  // the checkpoints that name it. Not in --help.
  app.add_flag_callback("--binary", [this] { ply_format_ = "binary"; })->group("");
  app.add_option("--formats", formats_, "files to write, a comma list of pov, csv, ply, json, glb, obj, tips "
                                        "(PREFIX_tips.ply, and with pov PREFIX_tips.inc), svg and png (2D), html (the web viewer), "
                                        "and the watertight solid: stl, 3mf, vdb, solid-glb, solid-obj")->capture_default_str()->group(outputs);
  app.add_option("--png-scale", f.png.pixels_per_spacing, "png: pixels a spacing, [1e-6, 64]")
      ->capture_default_str()->group(outputs);
  app.add_option("--png-bands", f.png.bands, "png: times the white, grey, black bands cycle over the attach "
                                             "order, 1 to 1e6")->capture_default_str()->group(outputs);

  const char* looks = "Look";
  radius_ = app.add_option("--radius", radius_model_, "branch thickness: taper, pipe, boundary (needs a mesh), "
                                                      "seed-distance or uniform; with a mesh, default pipe")
                ->capture_default_str()->group(looks);
  base_radius_option_ = app.add_option("--base-radius", base_radius_, "the thickest branch's radius, in spacings, "
                                                                      "[0.001, 1000]; with a mesh, default 3")
                            ->capture_default_str()->group(looks);
  tip_radius_option_ = app.add_option("--tip-radius", tip_radius_, "the finest branch's radius, in spacings, "
                                                                   "[0.001, 1000]; with a mesh, default 0.05")
                           ->capture_default_str()->group(looks);
  app.add_option("--pipe-exponent", f.look.radius.pipe_exponent, "pipe: e in r = tip * (descendants + 1)^(1/e), "
                                                                  "[1, 10]; 2 keeps the area, 3 is Murray's law")
      ->capture_default_str()->group(looks);
  app.add_option("--color-by", color_by_, "colour the glb, obj, svg and POV-Ray scene by none, age, depth, "
                                          "seed, distance (to the mesh, or to the seeds) or current (what "
                                          "flows through it: a discharge's main channel brightest)")
      ->capture_default_str()->group(looks);
  app.add_option("--look", pov_style_, "POV-Ray: branches (sphere sweeps), blob (metaballs) or glow (emissive "
                                        "branches on black, brightest where the colour value is highest)")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-sides", f.look.tubes.sides, "glb, obj: vertices around a tube, 3-64")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-tolerance", f.look.tubes.tolerance, "glb, obj: leave out strand points the tube "
                                                             "passes within this of, in spacings, [0, 10]")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-min-branch", f.look.tubes.min_branch, "glb, obj: leave out branches of fewer particles "
                                                                "(counting all that grow from them), 1-1000")
      ->capture_default_str()->group(looks);
  app.add_option("--lod", f.lods, "glb: levels of detail beside it, PREFIX_lod1.glb on, each with about half the "
                                  "triangles of the one before, 0-8")
      ->capture_default_str()->group(looks);
  app.add_option("--leaf", f.leaf, "glb: a binary glTF whose mesh goes at each instancing point (as tips picks "
                                  "them), along its direction and scaled by its pscale; its +Y is the leaf's stem")
      ->type_name("FILE.glb")->group(looks);
  app.add_option("--uv-scale", f.look.tubes.uv_scale, "glb, obj: strand length per unit of the texture's v, in "
                                                     "scene units; 0: the base circumference")
      ->capture_default_str()->group(looks);
  app.add_option("--instances", instance_set_, "tips: which particles get instancing points and the scene's "
                                               "DLA_Tip, tips or all (object fill)")
      ->capture_default_str()->group(looks);
  app.add_option("--tips-within", f.instances.within, "tips: only points within this of the mesh's "
                                                      "surface, in spacings, >= 0")->group(looks);
  app.add_option("--tips-every", f.instances.every, "tips: keep one point in K, in attach order (sparser leaves), "
                                                    "1-1000000")->capture_default_str()->group(looks);
  exclude_paint_option_ =
      app.add_option("--tips-exclude-paint", exclude_paint_, "tips: leave out the points whose closest point of the "
                                                             "mesh's surface is painted this colour (a name or ff8000), "
                                                             "within TOLERANCE per channel, [0, 1), default 0.3")
          ->type_name("COLOR[,TOLERANCE]")->group(looks);
  const char* solids = "Solid (stl, 3mf, vdb, solid-glb, solid-obj)";
  app.add_option("--solid-shape", solid_shape_, "what each particle adds: branches (tapered capsules to its parent), "
                                                "spheres (with --solid-smooth: metaballs) or cubes (lattice sites)")
      ->capture_default_str()->group(solids);
  app.add_option("--solid-voxel", f.solid.voxel, "the voxel's edge, in spacings, [0.001, 100]; 0: a third of the "
                                                 "thinnest branch's diameter")->capture_default_str()->group(solids);
  app.add_option("--solid-smooth", f.solid.smooth, "round inner corners to this radius and web branches closer than "
                                                   "twice it, in spacings, [0, 100]: the organic look")
      ->capture_default_str()->group(solids);
  app.add_option("--solid-adaptivity", f.solid.adaptivity, "merge flat parts into larger triangles, [0, 1]")
      ->capture_default_str()->group(solids);
  app.add_option("--print-size", f.solid.print_size, "scale the solid so its longest side is this, in mm, "
                                                     "(0, 10000]; 0 keeps the scene's units")
      ->capture_default_str()->group(solids);
  app.add_option("--min-wall", f.solid.min_wall, "with --print-size: thicken every branch thinner than this, in mm, "
                                                 "[0, 100]")->capture_default_str()->group(solids);
  app.add_flag("--solid-join", f.solid.join_seeds, "join the seeds' trees by bars, so several seeds print as one piece")
      ->group(solids);
  app.add_option("--solid-memory", f.solid.memory, "megabytes the solid may take, [1, 1e9]; 0: half the free memory")
      ->capture_default_str()->group(solids);
  up_option_ = app.add_option("--up", up_, "POV-Ray: the axis that is up in the picture, x, y or z; with a mesh, "
                                           "default: its longest side's")->capture_default_str()->group(outputs);
  app.add_flag("-q,--quiet", quiet, "no progress bar and no summary")->group(outputs);
  // `dla3d frames` (whose default is glb alone) draws a finished CSV: nothing attaches to stream.
  if (formats_ != "glb")
    app.add_option("--stream", "write each particle as it attaches to FILE (a pipe for a live view), binary: "
                               "docs/studio.md#the-stream")
        ->type_name("FILE")->group(outputs);
}

void OutputWords::finish(OutputOptions& f) const {
  if (up_option_->count()) f.up = parse_word<Axis>(up_);
  f.pov.style = parse_word<PovStyle>(pov_style_);
  f.ply_encoding = parse_word<PlyEncoding>(ply_format_);
  if (radius_->count()) f.radius = parse_word<RadiusModel>(radius_model_);
  if (base_radius_option_->count()) f.base_radius = base_radius_;
  if (tip_radius_option_->count()) f.tip_radius = tip_radius_;
  f.look.color_by = parse_word<ColorBy>(color_by_);
  f.instances.set = parse_word<InstanceSet>(instance_set_);
  if (exclude_paint_option_->count()) f.instances.exclude_paint = parse_paint(exclude_paint_, "tips_exclude_paint");
  f.formats = parse_formats(formats_);
  f.solid.shape = parse_word<SolidShape>(solid_shape_);
}

SeedWords::SeedWords(CLI::App& app, MeshSeeds& seeds, const char* group, CLI::Option* placed_by,
                     const std::string& seeds_help, const std::string& surface_help)
    : placed_by_(placed_by) {
  count_option_ = app.add_option("--seeds", count_, seeds_help)->type_name("K|all")->group(group)->excludes(placed_by);
  CLI::Option* surface = app.add_flag("--seed-surface", seeds.surface, surface_help)
                             ->group(group)->excludes(count_option_)->excludes(placed_by);
  paint_option_ = app.add_option("--seed-paint", paint_, "seeds on the part of the surface painted this colour (a name or "
                                                         "ff8000), within TOLERANCE per channel, [0, 1), default 0.3")
                      ->type_name("COLOR[,TOLERANCE]")->group(group)->excludes(placed_by);
  app.add_option("--seed-mesh", seeds.meshes, "seeds where this mesh's surface meets the mesh (repeat for "
                                              "several): growth from where objects enter")
      ->type_name("FILE")->allow_extra_args(false)->group(group)->excludes(placed_by)
      ->excludes(paint_option_)->excludes(surface);
}

void SeedWords::finish(MeshSeeds& seeds, bool has_mesh) const {
  if (!has_mesh && count_option_->count())
    throw InvalidInput("--seeds places seeds in a mesh given with --stl; without one, use " + placed_by_->get_name());
  if (!has_mesh && seeds.surface) throw InvalidInput("--seed-surface seeds a mesh's surface: give one with --stl");
  if (!has_mesh && paint_option_->count())
    throw InvalidInput("--seed-paint seeds the painted part of a mesh: give one with --stl");
  if (paint_option_->count()) seeds.paint = parse_paint(paint_);
  if (count_ == "all") {
    // Without paint or other meshes, all of the surface.
    seeds.surface = !paint_option_->count() && seeds.meshes.empty();
  } else if (count_option_->count()) {
    const bool digits = !count_.empty() && count_.size() <= 9 && count_.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) throw InvalidInput("--seeds '" + count_ + "' is neither a count of seeds nor all");
    seeds.count = std::stoul(count_);
    if (seeds.count == 0) throw InvalidInput("--seeds 0: there must be a seed");
  }
}

void add_refused_mesh_controls(CLI::App& app, const char* group, std::string_view model) {
  for (const char* option : {"fill", "shell"}) {
    app.add_option_function<std::string>(
           std::string("--") + option, [model, option](const std::string&) { refuse_for(model, option); },
           std::string(option) == "fill" ? "DLA's: grow until a mesh is full (not for " + std::string(model) + ")"
                                         : "DLA's: keep growth near the surface (not for " + std::string(model) + ")")
        ->type_name(std::string(option) == "fill" ? "F" : "T")->group(group);
  }
}

void add_links_option(CLI::App& command, const char* group, std::string& words, bool lattice) {
  command
      .add_option("--links", words,
                  std::string("also link each particle, as it attaches, to up to K (default 1) earlier ones within D "
                              "spacings and at least 8 tree steps away: loops (docs/loops.md)") +
                      (lattice ? "; lattice: every pair of neighbouring sites" : ""))
      ->type_name(lattice ? "D[,K]|lattice" : "D[,K]")
      ->group(group);
}

void add_seeded_options(CLI::App& command, const char* group, SeededWords& w, int& dimensions, double& spacing,
                        std::uint64_t& rng_seed, const std::string& spacing_help) {
  command.add_option("-n,--particles", w.particles, "particles to attach, seeds not counted")
      ->capture_default_str()->group(group);
  command.add_option("--dimensions", dimensions, "3, or 2 for growth in the plane z = 0")->capture_default_str()->group(group);
  w.spacing = command.add_option("--spacing", spacing, "distance between a particle and its parent; no two come closer; "
                                                       "[1e-25, 1e25]" + spacing_help)->capture_default_str()->group(group);
  w.seed_at_option = command.add_option("--seed-at", w.seed_at, "a seed at x,y,z (repeat for several); default: one at the origin "
                                                                "(with a mesh, one on its growing side)")
      ->type_name("X,Y,Z")->allow_extra_args(false)->group(group);
  command.add_option("--rng-seed", rng_seed, "seed of the random generator: the same seed gives the same files")
      ->capture_default_str()->group(group);
  add_links_option(command, group, w.links);
}

}  // namespace dla::cli
