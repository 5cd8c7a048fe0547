#include "command_line.h"

#include "dla/io/html_writer.h"

#include "dla/version.h"

#include <CLI/CLI.hpp>

#include <sstream>

namespace dla::cli {

namespace {

//! "x,y,z" (or more numbers for a box) as doubles; throws InvalidInput naming the flag.
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

//! "pov,csv,glb" as the files to write.
Formats parse_formats(const std::string& text) {
  Formats formats;
  formats.pov = formats.csv = formats.ply = formats.json = false;
  std::stringstream in(text);
  std::string word;
  bool any = false;
  while (std::getline(in, word, ',')) {
    bool* format = word == "pov" ? &formats.pov : word == "csv" ? &formats.csv : word == "ply" ? &formats.ply
                 : word == "json" ? &formats.json : word == "glb" ? &formats.glb : word == "obj" ? &formats.obj
                 : word == "tips" ? &formats.tips : word == "svg" ? &formats.svg : word == "png" ? &formats.png
                 : word == "html" ? &formats.html : nullptr;
    if (!format)
      throw InvalidInput("--formats '" + text + "': '" + word + "' is not one of pov, csv, ply, json, glb, obj, tips, svg, png, html");
    *format = any = true;
  }
  if (!any) throw InvalidInput("--formats is empty: name at least one of pov, csv, ply, json, glb, obj, tips, svg, png, html");
  if (formats.html && !has_web_viewer())
    throw InvalidInput("--formats html: this dla3d was built without npm, which fetches the web viewer's three.js; "
                       "install npm and build again");
  return formats;
}

Vec3 parse_vec3(const std::string& flag, const std::string& text) {
  const std::vector<double> v = parse_numbers(flag, text, 3);
  return {v[0], v[1], v[2]};
}

//! The Output and Look options' words, and the options whose defaults depend on a mesh.
struct FileWords {
  std::string up, radius_model, color_by, instance_set, pov_style, ply_format, formats = "pov,csv,ply,json";
  CLI::Option* radius = nullptr;
  CLI::Option* base_radius = nullptr;
  CLI::Option* tip_radius = nullptr;
  CLI::Option* up_option = nullptr;
  CLI::Option* tips_within = nullptr;
};

//! The Output and Look options, the same for every growth model.
void add_file_options(CLI::App& app, FileOptions& f, FileWords& w) {
  w.up = std::string(to_string(f.pov.up));
  w.radius_model = std::string(to_string(f.look.radius.model));
  w.color_by = std::string(to_string(f.look.color_by));
  w.instance_set = std::string(to_string(f.instances.set));
  w.pov_style = std::string(to_string(f.pov.style));
  w.ply_format = std::string(to_string(f.ply_encoding));
  const char* outputs = "Output";
  app.add_option("-o,--output", f.output, "prefix of the files written")->capture_default_str()->group(outputs);
  app.add_option("--ply-format", w.ply_format, "the PLYs as binary (little-endian) or ascii (text: twice the size, "
                                             "three times slower to write)")->capture_default_str()->group(outputs);
  // Binary became the default on 2026-11-24; the old flag still runs the scripts and resumes
  // the checkpoints that name it. Not in --help.
  app.add_flag_callback("--binary", [&w] { w.ply_format = "binary"; })->group("");
  app.add_option("--formats", w.formats, "files to write, a comma list of pov, csv, ply, json, glb, obj, tips "
                                        "(PREFIX_tips.ply, and with pov PREFIX_tips.inc), svg and png (2D), html (the web viewer)")->capture_default_str()->group(outputs);
  app.add_option("--png-scale", f.png.pixels_per_spacing, "png: pixels a spacing, [1e-6, 64]")
      ->capture_default_str()->group(outputs);
  app.add_option("--png-bands", f.png.bands, "png: times the white, grey, black bands cycle over the attach "
                                             "order, 1 to 1e6")->capture_default_str()->group(outputs);

  const char* looks = "Look";
  w.radius = app.add_option("--radius", w.radius_model, "branch thickness: taper, pipe, boundary (needs a mesh), "
                                                        "seed-distance or uniform; with a mesh, default pipe")
                 ->capture_default_str()->group(looks);
  w.base_radius = app.add_option("--base-radius", f.look.radius.base_radius, "the thickest branch's radius, in spacings, "
                                                                             "[0.001, 1000]; with a mesh, default 3")
                      ->capture_default_str()->group(looks);
  w.tip_radius = app.add_option("--tip-radius", f.look.radius.tip_radius, "the finest branch's radius, in spacings, "
                                                                          "[0.001, 1000]; with a mesh, default 0.05")
                     ->capture_default_str()->group(looks);
  app.add_option("--pipe-exponent", f.look.radius.pipe_exponent, "pipe: e in r = tip * (descendants + 1)^(1/e), "
                                                                  "[1, 10]; 2 keeps the area, 3 is Murray's law")
      ->capture_default_str()->group(looks);
  app.add_option("--color-by", w.color_by, "colour the glb, obj, svg and POV-Ray scene by none, age, depth, "
                                           "seed or distance (to the mesh, or to the seeds)")
      ->capture_default_str()->group(looks);
  app.add_option("--look", w.pov_style, "POV-Ray: branches (sphere sweeps) or blob (metaballs)")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-sides", f.look.tubes.sides, "glb, obj: vertices around a tube, 3-64")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-tolerance", f.look.tubes.tolerance, "glb, obj: leave out strand points the tube "
                                                             "passes within this of, in spacings, [0, 10]")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-min-branch", f.look.tubes.min_branch, "glb, obj: leave out branches of fewer particles "
                                                                "(counting all that grow from them), 1-1000")
      ->capture_default_str()->group(looks);
  app.add_option("--instances", w.instance_set, "tips: which particles get instancing points and the scene's "
                                                "DLA_Tip, tips or all (object fill)")
      ->capture_default_str()->group(looks);
  w.tips_within = app.add_option("--tips-within", f.instances.within, "tips: only points within this of the mesh's "
                                                                      "surface, in spacings, >= 0")->group(looks);
  w.up_option = app.add_option("--up", w.up, "POV-Ray: the axis that is up in the picture, x, y or z; with a mesh, "
                                             "default: its longest side's")->capture_default_str()->group(outputs);
  app.add_flag("-q,--quiet", f.quiet, "no progress bar and no summary")->group(outputs);
}

//! The words of the Output and Look options, as values.
void parse_file_words(FileOptions& f, const FileWords& w) {
  f.pov.up = parse_axis(w.up);
  f.pov.style = parse_pov_style(w.pov_style);
  f.ply_encoding = parse_ply_encoding(w.ply_format);
  f.look.radius.model = parse_radius_model(w.radius_model);
  f.look.color_by = parse_color_by(w.color_by);
  f.instances.set = parse_instance_set(w.instance_set);
  f.formats = parse_formats(w.formats);
  f.pov.tips = f.formats.tips;  // the scene reads its tips from PREFIX_tips.inc
  f.pov.instances = f.instances;  // at the same points as PREFIX_tips.ply
}

//! Checks the Output and Look options, once their mesh defaults are in.
void check_file_options(const FileOptions& f, const FileWords& w, int dimensions, bool with_mesh) {
  validate(f.look);
  validate(f.instances);
  if (f.formats.svg && dimensions != 2)
    throw InvalidInput("--formats svg draws 2D growth: add --dimensions 2, or leave svg out");
  if (f.formats.png && dimensions != 2)
    throw InvalidInput("--formats png draws 2D growth: add --dimensions 2, or leave png out");
  validate(f.png);
  if (!with_mesh) {
    if (f.look.radius.model == RadiusModel::boundary)
      throw InvalidInput("--radius boundary measures to a constraint mesh: give one with --stl");
    if (w.tips_within->count()) throw InvalidInput("--tips-within measures to a constraint mesh: give one with --stl");
  }
  if (f.output.empty()) throw InvalidInput("--output is empty");
  if (f.output.back() == '/') throw InvalidInput("--output '" + f.output + "' names a folder, not a file prefix");
  if (f.formats.pov) validate_pov_prefix(f.output);
}

//! Only -q and --threads may go with --resume: every other option comes from the checkpoint.
void check_resume_company(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--resume" || arg == "--threads") ++i;
    else if (arg.rfind("--resume=", 0) != 0 && arg.rfind("--threads=", 0) != 0 && arg != "-q" && arg != "--quiet")
      throw InvalidInput("--resume takes no other options but -q and --threads: they come from the checkpoint");
  }
}

//! K roots uniform on the sphere around the attractors (around their box, for a box), in
//! z = 0 for 2D: the Hyphae write-up's third test.
//! K roots at random on the sphere around the attractors: the scattering sphere, or the one
//! around the box they lie in.
std::vector<Vec3> roots_around(const ColonizeCommand& c, const std::vector<Vec3>& attractors, Rng& rng) {
  const AttractorOptions& a = c.attractors;
  const bool scattered =
      c.attractors_path.empty() && (a.region == AttractorRegion::sphere || a.region == AttractorRegion::box);
  Vec3 lo = a.box_min, hi = a.box_max;
  if (!scattered) {
    lo = hi = attractors.front();
    for (const Vec3& p : attractors) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const bool sphere = scattered && a.region == AttractorRegion::sphere;
  const Vec3 center = sphere ? a.center : Vec3(0.5 * (lo + hi));
  double radius = sphere ? a.radius : 0.5 * (hi - lo).norm();
  if (c.options.dimensions == 2 && !sphere) radius = 0.5 * (hi - lo).head<2>().norm();
  radius *= c.roots_scale;
  std::vector<Vec3> roots;
  for (std::size_t k = 0; k < c.root_count; ++k) {
    Vec3 root = center + radius * random_direction(rng, c.options.dimensions);
    if (c.options.dimensions == 2) root.z() = 0.0;
    roots.push_back(root);
  }
  return roots;
}

//! Where one root starts by default: the lowest point (along y) of the scattering sphere or
//! box, or else the lowest attractor.
Vec3 lowest_point(const ColonizeCommand& c, const std::vector<Vec3>& attractors) {
  const AttractorOptions& a = c.attractors;
  if (c.attractors_path.empty() && a.region == AttractorRegion::sphere) return a.center - Vec3(0.0, a.radius, 0.0);
  if (c.attractors_path.empty() && a.region == AttractorRegion::box)
    return {0.5 * (a.box_min.x() + a.box_max.x()), a.box_min.y(), 0.5 * (a.box_min.z() + a.box_max.z())};
  return *std::min_element(attractors.begin(), attractors.end(),
                           [](const Vec3& p, const Vec3& q) { return p.y() < q.y(); });
}

}  // namespace

std::string_view to_string(RootRegion region) {
  return region == RootRegion::sphere ? "sphere" : region == RootRegion::mesh ? "mesh" : "surface";
}

RootRegion parse_root_region(std::string_view word) {
  constexpr RootRegion values[] = {RootRegion::sphere, RootRegion::mesh, RootRegion::surface};
  return detail::parse_word(word, values, "root region");
}

std::vector<Vec3> colonize_roots(const ColonizeCommand& command, const std::vector<Vec3>& attractors,
                                 const MeshConstraint* mesh) {
  if (!command.roots.empty()) return command.roots;
  if (command.root_count == 0) {
    Vec3 root = lowest_point(command, attractors);
    if (command.options.dimensions == 2) root.z() = 0.0;
    return {root};
  }
  Rng rng(command.options.rng_seed, 0x726f6f7473ULL);  // a stream of its own: "roots"
  if (command.roots_in == RootRegion::sphere) return roots_around(command, attractors, rng);
  if (!mesh)
    throw InvalidInput("--roots-in " + std::string(to_string(command.roots_in)) + " needs a mesh: --stl or --collide");
  std::vector<Vec3> roots;
  for (std::size_t k = 0; k < command.root_count; ++k)
    roots.push_back(command.roots_in == RootRegion::mesh ? mesh->draw_inside(rng) : mesh->draw_near_surface(rng));
  return roots;
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
  CommandLine line;
  GrowCommand& g = line.grow;
  GrowthOptions& options = g.options;
  CLI::App app{"Grows a branching structure by off-lattice diffusion-limited aggregation and writes\n"
               "it as a POV-Ray scene (PREFIX.pov, PREFIX.inc), PREFIX.csv, PREFIX.ply and PREFIX.json.",
               "dla3d"};
  app.set_version_flag("--version", std::string("dla3d ") + version);
  app.get_formatter()->column_width(34);

  long long particles = static_cast<long long>(options.particles);
  std::vector<std::string> seed_at;
  std::string spawn = std::string(to_string(options.spawn));
  std::string spawn_axis = std::string(to_string(options.spawn_axis));
  std::string box, drift, rotate, index = std::string(to_string(options.index));
  std::string side = std::string(to_string(g.constraint.side));
  std::string constraint_mode = std::string(to_string(g.constraint.mode));

  const char* growth = "Growth";
  CLI::Option* particles_option =
      app.add_option("-n,--particles", particles, "particles to attach, seeds not counted; with a mesh, "
                                                  "default 30000")->capture_default_str()->group(growth);
  CLI::Option* spacing = app.add_option(
      "--spacing", options.spacing,
      "distance between a particle and its parent; also the contact distance, in [1e-25, 1e25]; "
      "with a mesh, default: its longest side / 100")->capture_default_str()->group(growth);
  app.add_option("--stickiness", options.stickiness, "probability of sticking at a contact, in [1e-4, 1]")
      ->capture_default_str()->group(growth);
  app.add_option("--dimensions", options.dimensions, "3, or 2 for growth in the plane z = 0")
      ->capture_default_str()->group(growth);
  CLI::Option* seed_at_option =
      app.add_option("--seed-at", seed_at, "a seed at x,y,z (repeat for several); default: one at the origin")
          ->type_name("X,Y,Z")->allow_extra_args(false)->group(growth);
  app.add_option("--rng-seed", options.rng_seed, "seed of the random generator: the same seed gives the same files")
      ->capture_default_str()->group(growth);
  app.add_option("--min-step", options.min_step, "step length next to the structure, in spacings, [0.01, 1]")
      ->capture_default_str()->group(growth);
  app.add_option("--index", index, "nearest-particle look-up: grid, kdtree or brute")
      ->capture_default_str()->group(growth);
  app.add_option("--threads", options.threads,
                 "walkers run at once, 1-256 (grid index); the files do not depend on it")
      ->capture_default_str()->group(growth);

  const char* meshes = "Mesh constraint";
  CLI::Option* stl_option = app.add_option("--stl,--mesh", g.mesh_path, "grow constrained by this mesh: STL, OFF, OBJ or PLY")
                                ->type_name("FILE")->group(meshes);
  std::string text, font = kDefaultFont;
  CLI::Option* text_option =
      app.add_option("--text", text, "grow in this text, extruded a quarter of its size (lines split at \\n): "
                                     "a mesh, as --stl's; one seed in each letter")
          ->type_name("TEXT")->group(meshes)->excludes(stl_option);
  CLI::Option* font_option =
      app.add_option("--font", font, "--text's font: a TrueType or OpenType file")->capture_default_str()->group(meshes);
  app.add_option("--side", side, "inside, outside, both (the mesh is only a wall; not closed) or surface (over "
                                 "it, both sides, in a shell)")
      ->capture_default_str()->group(meshes);
  CLI::Option* shell_option =
      app.add_option("--shell", g.constraint.shell, "keep growth within T spacings of the surface, on its side, "
                                                    "[1, 1000]: frost, lichen; with --side surface, default 3")
          ->type_name("T")->group(meshes);
  app.add_option("--constraint", constraint_mode, "a branch crossing the mesh: reject (walk on) or clip (end at it)")
      ->capture_default_str()->group(meshes);
  std::string seeds, seed_paint;
  CLI::Option* seeds_option =
      app.add_option("--seeds", seeds, "place K seeds on the growing side, far apart (default 1), or all: the "
                                       "surface, the paint or the --seed-mesh curves at the spacing (their default)")
          ->type_name("K|all")->group(meshes)->excludes(seed_at_option);
  CLI::Option* seed_surface_option =
      app.add_flag("--seed-surface", g.seed_surface, "start from the whole surface (or the painted part): seeds a "
                                                     "spacing apart, half a spacing off it on the growing side")
          ->group(meshes)->excludes(seeds_option)->excludes(seed_at_option);
  CLI::Option* seed_paint_option =
      app.add_option("--seed-paint", seed_paint, "seeds on the part of the surface painted this colour (a name or "
                                                 "ff8000), within TOLERANCE per channel, [0, 1), default 0.3")
          ->type_name("COLOR[,TOLERANCE]")->group(meshes)->excludes(seed_at_option);
  app.add_option("--seed-mesh", g.seed_mesh_paths, "seeds where this mesh's surface meets the mesh (repeat for "
                                                   "several): growth from where objects enter")
      ->type_name("FILE")->allow_extra_args(false)->group(meshes)->excludes(seed_at_option)
      ->excludes(seed_paint_option)->excludes(seed_surface_option);
  app.add_flag("--scene-mesh,!--no-scene-mesh", g.scene_mesh, "show the mesh, as glass, in the POV-Ray scene")
      ->capture_default_str()->group(meshes);
  CLI::Option* fill_option =
      app.add_option("--fill", options.fill, "grow until this fraction of the mesh's volume lies within "
                                             "--fill-distance of the structure, (0, 1]; -n then caps it (default 1e7)")
          ->type_name("F")->group(meshes);
  app.add_option("--fill-distance", options.fill_distance, "--fill: how near counts as covered, in spacings, [0.5, 1000]")
      ->capture_default_str()->group(meshes);

  const char* spawning = "Spawn";
  CLI::Option* spawn_option =
      app.add_option("--spawn", spawn, "where walkers start: sphere, disk, box, or with a mesh inside, radial or surface; "
                                       "with --side inside, default surface")
          ->capture_default_str()->group(spawning);
  app.add_option("--spawn-axis", spawn_axis, "disk: the axis the disk sits on, x, y or z")
      ->capture_default_str()->group(spawning);
  app.add_option("--disk-radius", options.disk_radius, "disk: radius as a fraction of the launch radius, (0, 1000]")
      ->capture_default_str()->group(spawning);
  app.add_option("--box", box, "box: a fixed box; default: the cube around the launch sphere")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(spawning);
  app.add_option("--drift", drift, "bias of every step, per unit step length, length < 1")
      ->type_name("X,Y,Z")->group(spawning);
  app.add_option("--rotate", rotate, "turn the spawn and the drift about the seeds' centre by DEGREES per 1000 "
                                     "particles, as if the structure turned while it grew: spirals; no mesh")
      ->type_name("AXIS,DEGREES")->group(spawning);

  FileWords words;
  add_file_options(app, g, words);

  const char* runs = "Long runs";
  app.add_option("--checkpoint", g.checkpoint_path, "save the run to FILE as it goes, and when stopped by Ctrl-C or SIGTERM")
      ->type_name("FILE")->group(runs);
  app.add_option("--checkpoint-every", g.checkpoint_every, "seconds between saves")->capture_default_str()->group(runs);
  CLI::Option* resume_option =
      app.add_option("--resume", line.resume_path, "grow on from a checkpoint, with the options it was started with")
          ->type_name("FILE")->group(runs);

  ColonizeCommand& c = line.colonize;
  CLI::App* colonize_command = app.add_subcommand(
      "colonize", "grow a tree by space colonization: attractor points pull its nearest nodes (docs/colonization.md)");
  colonize_command->get_formatter()->column_width(34);
  const char* colonizing = "Colonization";
  std::vector<std::string> root_at;
  std::string attractor_region = std::string(to_string(c.attractors.region)), attractor_center, attractor_box,
              noise, tropism;
  long long max_nodes = static_cast<long long>(c.options.max_nodes), attractor_count = static_cast<long long>(c.attractors.count),
            max_iterations = static_cast<long long>(c.options.max_iterations), root_count = 0;
  colonize_command->add_option("-n,--max-nodes", max_nodes, "nodes at most, roots included")
      ->capture_default_str()->group(colonizing);
  colonize_command->add_option("--max-iterations", max_iterations, "growth steps at most")
      ->capture_default_str()->group(colonizing);
  colonize_command->add_option("--spacing", c.options.spacing, "the step: distance between a node and its parent, "
                                                                "[1e-25, 1e25]")->capture_default_str()->group(colonizing);
  colonize_command->add_option("--kill-distance", c.options.kill_distance, "an attractor dies once a node is this close, "
                                                                            "in spacings, [1, 1e6]")
      ->capture_default_str()->group(colonizing);
  colonize_command->add_option("--influence", c.options.influence, "an attractor pulls its nearest node only this close, "
                                                                    "in spacings, above the kill distance; default: any")
      ->group(colonizing);
  colonize_command->add_option("--noise", noise, "each new node moves by up to A spacings, in features S spacings wide; "
                                                 "A in [0, 10], S > 0")->type_name("A,S")->group(colonizing);
  colonize_command->add_option("--tropism", tropism, "added to each step's unit direction (gravity, light), "
                                                     "each in [-10, 10]")->type_name("X,Y,Z")->group(colonizing);
  colonize_command->add_option("--dimensions", c.options.dimensions, "3, or 2 for venation in the plane z = 0")
      ->capture_default_str()->group(colonizing);
  colonize_command->add_option("--rng-seed", c.options.rng_seed, "seeds the attractors, the roots and the noise")
      ->capture_default_str()->group(colonizing);
  const char* attracting = "Attractors and roots";
  colonize_command->add_option("--attractors", attractor_count, "how many attractors, [1, 1e8]")
      ->capture_default_str()->group(attracting);
  CLI::Option* attractors_in =
      colonize_command->add_option("--attractors-in", attractor_region, "where they lie: sphere, box, mesh (inside "
                                                                        "the --stl vessel, else the --collide mesh) or "
                                                                        "surface (on it)")
          ->capture_default_str()->group(attracting);
  colonize_command->add_option("--attractors-from", c.attractors_path, "read them from a file: CSV rows x,y,z (or a "
                                                                      "header naming x, y, z) or PLY points; with "
                                                                      "--attractors N, a seeded sample of N")
      ->type_name("FILE")->group(attracting)->excludes(attractors_in);
  colonize_command->add_option("--attractor-center", attractor_center, "the sphere's centre; default the origin")
      ->type_name("X,Y,Z")->group(attracting);
  colonize_command->add_option("--attractor-radius", c.attractors.radius, "the sphere's radius, scene units, > 0")
      ->capture_default_str()->group(attracting);
  colonize_command->add_option("--attractor-box", attractor_box, "the box; default -50,-50,-50,50,50,50")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(attracting);
  colonize_command->add_option("--attractor-falloff", c.attractors.falloff, "grading towards the sphere's centre, "
                                                                            "[0, 100]; 0 is uniform")
      ->capture_default_str()->group(attracting);
  CLI::Option* root_at_option =
      colonize_command->add_option("--root-at", root_at, "a root at x,y,z (repeat for several); default: one at "
                                                         "the attractors' lowest point (-y)")
          ->type_name("X,Y,Z")->allow_extra_args(false)->group(attracting);
  colonize_command->add_option("--roots", root_count, "K roots at random, where --roots-in says")
      ->type_name("K")->group(attracting)->excludes(root_at_option);
  std::string roots_in = std::string(to_string(c.roots_in));
  colonize_command->add_option("--roots-in", roots_in, "--roots K: on the sphere around the attractors, in the mesh "
                                                       "(the vessel, else the collision mesh) or on its surface")
      ->capture_default_str()->group(attracting);
  colonize_command->add_option("--roots-scale", c.roots_scale, "--roots-in sphere: the roots' sphere is this times "
                                                                "the attractors', [0.01, 100]")
      ->capture_default_str()->group(attracting);
  std::string collision = std::string(to_string(c.collision));
  const char* colliding = "Vessel and collision";
  colonize_command->add_option("--stl", c.vessel_path, "a vessel (STL, OFF, OBJ or PLY) that growth stays inside: a "
                                                       "step that would cross its surface is refused")
      ->type_name("FILE")->group(colliding);
  colonize_command->add_option("--collide", c.collide_path, "a collision mesh (STL, OFF, OBJ or PLY) that new nodes "
                                                           "are pushed out of or stuck to")
      ->type_name("FILE")->group(colliding);
  colonize_command->add_option("--collision", collision, "push (growth flows around the mesh) or stick (it crawls "
                                                         "over its surface)")
      ->capture_default_str()->group(colliding);
  FileWords colonize_words;
  add_file_options(*colonize_command, c, colonize_words);

  EdenCommand& e = line.eden;
  CLI::App* eden_command = app.add_subcommand(
      "eden", "grow an Eden cluster on a lattice: sites join at random on its edge, or where a mask counts "
              "enough of it (docs/eden.md)");
  eden_command->get_formatter()->column_width(34);
  const char* eden_group = "Eden";
  long long sites = static_cast<long long>(e.options.sites);
  int eden_dimensions = 2;
  std::string lattice, eden_mode = std::string(to_string(e.options.mode)), mask;
  eden_command->add_option("-n,--sites", sites, "sites at most, the seed included")->capture_default_str()->group(eden_group);
  CLI::Option* dimensions_option =
      eden_command->add_option("--dimensions", eden_dimensions, "2, or 3 for a cubic lattice")
          ->capture_default_str()->group(eden_group);
  eden_command->add_option("--lattice", lattice, "square4, square8 or hex in 2D; cubic6, cubic18 or cubic26 in 3D "
                                                 "(the number: neighbours); default square4, in 3D cubic6")
      ->group(eden_group);
  eden_command->add_option("--mode", eden_mode, "perimeter (a random empty neighbour joins) or drop (a random site "
                                                "joins where the mask counts enough of the cluster)")
      ->capture_default_str()->group(eden_group);
  eden_command->add_option("--mask", mask, "drop: A, B, C or D (the paper's masks: 4, 8, 12 and 24 sites around), "
                                           "or a file drawing one; default A")->group(eden_group);
  eden_command->add_option("--mask-threshold", e.options.mask_threshold, "drop: occupied mask sites a site needs, "
                                                                         "1 to the mask's size")
      ->capture_default_str()->group(eden_group);
  eden_command->add_option("--seed-radius", e.options.seed_radius, "the cluster starts as every site within this "
                                                                   "many spacings of the seed, [0, 100]")
      ->capture_default_str()->group(eden_group);
  eden_command->add_option("--spacing", e.options.spacing, "distance between neighbouring sites, [1e-25, 1e25]")
      ->capture_default_str()->group(eden_group);
  eden_command->add_option("--rng-seed", e.options.rng_seed, "seed of the random generator: the same seed gives "
                                                             "the same files")
      ->capture_default_str()->group(eden_group);
  FileWords eden_words;
  add_file_options(*eden_command, e, eden_words);

  // What drop and ballistic share with DLA: the count, the plane, the scale, the seeds.
  struct SeededWords {
    long long particles = 10000;
    std::vector<std::string> seed_at;
  };
  const auto add_seeded_options = [](CLI::App& command, const char* group, SeededWords& w, int& dimensions,
                                     double& spacing, std::uint64_t& rng_seed, const std::string& spacing_help) {
    command.add_option("-n,--particles", w.particles, "particles to attach, seeds not counted")
        ->capture_default_str()->group(group);
    command.add_option("--dimensions", dimensions, "3, or 2 for growth in the plane z = 0")->capture_default_str()->group(group);
    command.add_option("--spacing", spacing, "distance between a particle and its parent; no two come closer; "
                                             "[1e-25, 1e25]" + spacing_help)->capture_default_str()->group(group);
    command.add_option("--seed-at", w.seed_at, "a seed at x,y,z (repeat for several); default: one at the origin "
                                                "(with a mesh, one on its growing side)")
        ->type_name("X,Y,Z")->allow_extra_args(false)->group(group);
    command.add_option("--rng-seed", rng_seed, "seed of the random generator: the same seed gives the same files")
        ->capture_default_str()->group(group);
  };
  const auto parse_seeded = [](const SeededWords& w, std::size_t& particles, std::vector<Vec3>& seeds) {
    if (w.particles < 0) throw InvalidInput("--particles " + std::to_string(w.particles) + " is negative");
    particles = static_cast<std::size_t>(w.particles);
    if (!w.seed_at.empty()) {
      seeds.clear();
      for (const std::string& at : w.seed_at) seeds.push_back(parse_vec3("--seed-at", at));
    }
  };

  DropCommand& d = line.drop;
  CLI::App* drop_command = app.add_subcommand(
      "drop", "grow by random-drop ballistic aggregation: particles dropped at random join the closest particle "
              "(docs/drop.md)");
  drop_command->get_formatter()->column_width(34);
  const char* dropping = "Random drops";
  SeededWords drop_words;
  std::string zone = std::string(to_string(d.options.zone)), zone_box, drop_bias = "uniform";
  std::string drop_side = std::string(to_string(d.constraint.side)), drop_constraint = std::string(to_string(d.constraint.mode));
  add_seeded_options(*drop_command, dropping, drop_words, d.options.dimensions, d.options.spacing, d.options.rng_seed,
                     "; with a mesh, default: its longest side / 100");
  drop_command->add_option("--stickiness", d.options.stickiness, "chance of sticking on reaching the structure, "
                                                                 "[1e-4, 1]; else a random step and again")
      ->capture_default_str()->group(dropping);
  drop_command->add_option("--zone", zone, "where particles drop: ball (a disk in 2D), box, or mesh (inside --stl)")
      ->capture_default_str()->group(dropping);
  drop_command->add_option("--zone-radius", d.options.zone_radius, "ball: a fixed radius about the seeds' centre, "
                                                                   "scene units; default: growing, see --zone-margin")
      ->group(dropping);
  drop_command->add_option("--zone-margin", d.options.zone_margin, "growing ball: spacings beyond the farthest "
                                                                   "particle, [0.5, 1e6]")
      ->capture_default_str()->group(dropping);
  drop_command->add_option("--zone-box", zone_box, "box: a fixed box; default: the square or cube around the ball")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(dropping);
  drop_command->add_option("--drop", drop_bias, "uniform; circle (on the zone's edge); same:N (N drops at one "
                                                "point); offset:N,R (N more, each within R of the last)")
      ->capture_default_str()->group(dropping);
  const char* drop_meshes = "Mesh constraint";
  drop_command->add_option("--stl,--mesh", d.mesh_path, "grow constrained by this mesh: STL, OFF, OBJ or PLY")
      ->type_name("FILE")->group(drop_meshes);
  drop_command->add_option("--side", drop_side, "inside, outside or both (the mesh is only a wall)")
      ->capture_default_str()->group(drop_meshes);
  drop_command->add_option("--constraint", drop_constraint, "a branch crossing the mesh: reject (drop again) or clip "
                                                            "(end at it)")->capture_default_str()->group(drop_meshes);
  drop_command->add_flag("--scene-mesh,!--no-scene-mesh", d.scene_mesh, "show the mesh, as glass, in the POV-Ray scene")
      ->capture_default_str()->group(drop_meshes);
  FileWords drop_file_words;
  add_file_options(*drop_command, d, drop_file_words);

  BallisticCommand& b = line.ballistic;
  CLI::App* ballistic_command = app.add_subcommand(
      "ballistic", "grow by ballistic aggregation: particles fly in straight lines and stick where they first touch "
                   "(docs/ballistic.md)");
  ballistic_command->get_formatter()->column_width(34);
  const char* flying = "Ballistic";
  SeededWords ballistic_words;
  std::string direction;
  add_seeded_options(*ballistic_command, flying, ballistic_words, b.options.dimensions, b.options.spacing,
                     b.options.rng_seed, "");
  ballistic_command->add_option("--direction", direction, "deposition: every particle flies along x,y,z; "
                                                          "default: each from a random direction")
      ->type_name("X,Y,Z")->group(flying);
  FileWords ballistic_file_words;
  add_file_options(*ballistic_command, b, ballistic_file_words);

  CLI::App* convert_command =
      app.add_subcommand("convert", "read a mesh (STL, OFF, OBJ, PLY) and write it as binary STL, then stop");
  convert_command->add_option("in", line.convert_in, "the mesh to read")->required();
  convert_command->add_option("out", line.convert_out, "the .stl to write")->required();
  CLI::App* analyze_command = app.add_subcommand(
      "analyze", "print the fractal dimension of a grown structure (by gyration and by mass-radius) as JSON");
  analyze_command->add_option("csv", line.analyze_csv, "a CSV that dla3d wrote")->required();
  FramesCommand& fr = line.frames;
  CLI::App* frames_command = app.add_subcommand(
      "frames", "write the structure a CSV holds as it grew, K files of each format (PREFIX_0001.glb ...): "
                "growth for tools without an age attribute (docs/animation.md)");
  frames_command->get_formatter()->column_width(34);
  frames_command->add_option("csv", fr.csv_path, "a CSV that dla3d wrote")->required();
  long long frame_count = static_cast<long long>(fr.count);
  frames_command->add_option("--count", frame_count, "frames, 1-100000: frame k of K holds the seeds and k/K of the "
                                                     "other particles, in attach order")->capture_default_str();
  FileWords frames_words;
  frames_words.formats = "glb";
  add_file_options(*frames_command, fr, frames_words);
  frames_command->get_option("--output")->description("prefix of the files written, each PREFIX_NNNN.EXT; "
                                                      "default: the CSV's, without .csv");
  app.require_subcommand(0, 1);

  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    line.kind = CommandLine::Kind::print;
    line.text = app.help();
    return line;
  } catch (const CLI::CallForAllHelp&) {
    line.kind = CommandLine::Kind::print;
    line.text = app.help("", CLI::AppFormatMode::All);
    return line;
  } catch (const CLI::CallForVersion&) {
    line.kind = CommandLine::Kind::print;
    line.text = std::string("dla3d ") + version + "\n";
    return line;
  } catch (const CLI::ParseError& e) {
    throw InvalidInput(std::string(e.what()) + " (see dla3d --help)");
  }

  if (drop_command->parsed()) {
    line.kind = CommandLine::Kind::drop;
    parse_seeded(drop_words, d.options.particles, d.options.seeds);
    d.options.zone = parse_drop_zone(zone);
    d.options.bias = parse_drop_bias(drop_bias);
    if (!zone_box.empty()) {
      const std::vector<double> v = parse_numbers("--zone-box", zone_box, 6);
      d.options.zone_box = Box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    }
    d.spacing_given = drop_command->count("--spacing") > 0;
    d.seeds_given = !drop_words.seed_at.empty();
    d.up_given = drop_command->count("--up") > 0;
    d.constraint.side = parse_side(drop_side);
    d.constraint.mode = parse_constraint_mode(drop_constraint);
    const bool with_mesh = !d.mesh_path.empty();
    if (!with_mesh && (drop_command->count("--side") || drop_command->count("--constraint")))
      throw InvalidInput("--side and --constraint say how --stl's mesh constrains growth: give one");
    if (d.options.zone == DropZone::mesh && !with_mesh)
      throw InvalidInput("--zone mesh drops inside a mesh: give one with --stl");
    if (!with_mesh || d.spacing_given) validate(d.options);  // else once the mesh sets the spacing
    parse_file_words(d, drop_file_words);
    check_file_options(d, drop_file_words, d.options.dimensions, with_mesh);
    return line;
  }

  if (ballistic_command->parsed()) {
    line.kind = CommandLine::Kind::ballistic;
    parse_seeded(ballistic_words, b.options.particles, b.options.seeds);
    if (!direction.empty()) {
      b.options.direction = parse_vec3("--direction", direction);
      if (b.options.direction.squaredNorm() == 0.0) throw InvalidInput("--direction 0,0,0 has no direction");
    }
    validate(b.options);
    parse_file_words(b, ballistic_file_words);
    check_file_options(b, ballistic_file_words, b.options.dimensions, false);
    return line;
  }

  if (eden_command->parsed()) {
    line.kind = CommandLine::Kind::eden;
    if (sites < 1) throw InvalidInput("--sites " + std::to_string(sites) + " is not at least 1");
    e.options.sites = static_cast<std::size_t>(sites);
    if (eden_dimensions != 2 && eden_dimensions != 3)
      throw InvalidInput("--dimensions " + std::to_string(eden_dimensions) + " is not 2 or 3");
    e.options.lattice = lattice.empty() ? (eden_dimensions == 3 ? Lattice::cubic6 : Lattice::square4) : parse_lattice(lattice);
    if (!lattice.empty() && dimensions_option->count() && dimensions_of(e.options.lattice) != eden_dimensions)
      throw InvalidInput("--lattice " + lattice + " is not a lattice in " + std::to_string(eden_dimensions) + "D");
    e.options.mode = parse_eden_mode(eden_mode);
    if (e.options.mode == EdenMode::perimeter) {
      if (!mask.empty() || eden_command->count("--mask-threshold"))
        throw InvalidInput("--mask and --mask-threshold are for --mode drop");
    } else if (mask.size() == 1 && mask.find_first_of("ABCD") == 0) {
      e.options.mask = parse_eden_mask(mask);
    } else {
      e.mask_path = mask;  // read, and checked, before growth
    }
    parse_file_words(e, eden_words);
    check_file_options(e, eden_words, dimensions_of(e.options.lattice), false);
    if (e.mask_path.empty()) validate(e.options);
    return line;
  }

  if (colonize_command->parsed()) {
    line.kind = CommandLine::Kind::colonize;
    parse_file_words(c, colonize_words);
    check_file_options(c, colonize_words, c.options.dimensions, !c.vessel_path.empty());
    if (max_nodes < 1) throw InvalidInput("--max-nodes " + std::to_string(max_nodes) + " is not at least 1");
    if (max_iterations < 1) throw InvalidInput("--max-iterations " + std::to_string(max_iterations) + " is not at least 1");
    if (attractor_count < 1) throw InvalidInput("--attractors " + std::to_string(attractor_count) + " is not at least 1");
    if (colonize_command->count("--roots") && root_count < 1)
      throw InvalidInput("--roots " + std::to_string(root_count) + ": there must be a root");
    c.options.max_nodes = static_cast<std::size_t>(max_nodes);
    c.options.max_iterations = static_cast<std::size_t>(max_iterations);
    c.attractors.count = static_cast<std::size_t>(attractor_count);
    c.root_count = static_cast<std::size_t>(root_count);
    c.attractors.region = parse_attractor_region(attractor_region);
    c.sample_attractors = colonize_command->count("--attractors") > 0 && !c.attractors_path.empty();
    c.roots_in = parse_root_region(roots_in);
    if (colonize_command->count("--roots-in") && root_count == 0)
      throw InvalidInput("--roots-in says where --roots K puts its roots: give --roots");
    detail::require_in("--roots-scale", c.roots_scale, 0.01, 100.0);
    if (colonize_command->count("--roots-scale") && (root_count == 0 || c.roots_in != RootRegion::sphere))
      throw InvalidInput("--roots-scale sizes the sphere of --roots K (--roots-in sphere): give --roots");
    const bool on_mesh =
        c.attractors.region == AttractorRegion::mesh || c.attractors.region == AttractorRegion::surface;
    if ((on_mesh || c.roots_in != RootRegion::sphere) && c.vessel_path.empty() && c.collide_path.empty())
      throw InvalidInput("attractors or roots in a mesh need one: give --stl or --collide");
    if (!c.vessel_path.empty() && c.options.dimensions != 3) throw InvalidInput("--stl needs 3 dimensions");
    c.collision = parse_collision_mode(collision);
    if (colonize_command->count("--collision") && c.collide_path.empty())
      throw InvalidInput("--collision says what --collide's mesh does: give one");
    if (!c.collide_path.empty() && c.options.dimensions != 3)
      throw InvalidInput("--collide needs 3 dimensions");
    if (!attractor_center.empty()) c.attractors.center = parse_vec3("--attractor-center", attractor_center);
    if (!attractor_box.empty()) {
      const std::vector<double> b = parse_numbers("--attractor-box", attractor_box, 6);
      c.attractors.box_min = {b[0], b[1], b[2]};
      c.attractors.box_max = {b[3], b[4], b[5]};
      if (c.attractors.region != AttractorRegion::box)
        throw InvalidInput("--attractor-box is for --attractors-in box, not " + attractor_region);
    }
    if (!noise.empty()) {
      const std::vector<double> n = parse_numbers("--noise", noise, 2);
      c.options.noise_amplitude = n[0];
      c.options.noise_scale = n[1];
    }
    if (!tropism.empty()) c.options.tropism = parse_vec3("--tropism", tropism);
    for (const std::string& r : root_at) c.roots.push_back(parse_vec3("--root-at", r));
    validate(c.options);
    validate(c.attractors);
    if (c.options.dimensions == 2) {
      if (c.attractors.center.z() != 0.0) throw InvalidInput("--dimensions 2 grows in z = 0: the attractors' centre is not");
      for (const Vec3& r : c.roots)
        if (r.z() != 0.0) throw InvalidInput("--dimensions 2 grows in z = 0: a --root-at is not");
    }
    if (c.root_count > c.options.max_nodes || c.roots.size() > c.options.max_nodes)
      throw InvalidInput("more roots than --max-nodes");
    for (std::size_t i = 0; i < c.roots.size(); ++i)
      detail::require_representable("--root-at " + root_at[i], c.roots[i], c.options.spacing);
    return line;
  }
  if (convert_command->parsed()) {
    line.kind = CommandLine::Kind::convert;
    const std::string& out = line.convert_out;
    if (out.size() < 4 || (out.compare(out.size() - 4, 4, ".stl") != 0 && out.compare(out.size() - 4, 4, ".STL") != 0))
      throw InvalidInput("convert writes binary STL: '" + out + "' does not end in .stl");
    return line;
  }
  if (analyze_command->parsed()) {
    line.kind = CommandLine::Kind::analyze;
    return line;
  }
  if (frames_command->parsed()) {
    line.kind = CommandLine::Kind::frames;
    if (frame_count < 1 || frame_count > 100000)
      throw InvalidInput("--count " + std::to_string(frame_count) + " is not a number of frames in 1-100000");
    fr.count = static_cast<std::size_t>(frame_count);
    if (!frames_command->count("--output")) {
      fr.output = fr.csv_path;
      if (fr.output.size() > 4 && fr.output.compare(fr.output.size() - 4, 4, ".csv") == 0) fr.output.resize(fr.output.size() - 4);
    }
    parse_file_words(fr, frames_words);
    if (fr.formats.json) throw InvalidInput("--formats json: frames have no run to report; leave json out");
    // svg and png need 2D growth, which only the CSV tells: frames() checks them.
    check_file_options(fr, frames_words, 2, false);
    return line;
  }
  if (resume_option->count()) {
    check_resume_company(args);
    line.kind = CommandLine::Kind::resume;
    line.threads_given = app.count("--threads") > 0;
    validate(options);  // the thread count, the one growth option given
    return line;
  }

  if (!(g.checkpoint_every >= 0.0))
    throw InvalidInput("--checkpoint-every " + detail::format_number(g.checkpoint_every) + " is not a number of seconds");
  if (particles < 0) throw InvalidInput("--particles " + std::to_string(particles) + " is negative");
  options.particles = static_cast<std::size_t>(particles);
  if (!seed_at.empty()) {
    options.seeds.clear();
    for (const std::string& s : seed_at) options.seeds.push_back(parse_vec3("--seed-at", s));
  }
  options.spawn = parse_spawn_mode(spawn);
  options.spawn_axis = parse_axis(spawn_axis);
  options.index = parse_index_kind(index);
  parse_file_words(g, words);
  g.particles_given = particles_option->count() > 0;
  g.radius_given = words.radius->count() > 0;
  g.base_radius_given = words.base_radius->count() > 0;
  g.tip_radius_given = words.tip_radius->count() > 0;
  if (text_option->count()) {
    // "\n" typed in the shell is a line break.
    for (std::size_t at = text.find("\\n"); at != std::string::npos; at = text.find("\\n", at + 1)) text.replace(at, 2, "\n");
    g.text = TextOptions{text, font};
  } else if (font_option->count()) {
    throw InvalidInput("--font is the font of --text: give the text");
  }
  if (g.has_mesh()) {
    // Inside a mesh, a root system: enough particles to fill a bust at the default spacing,
    // short of the 35,000 or so that cover its skin, where the surface spawn starts walkers;
    // thick trunks and fine tips (docs/look.md shows the main job's picture).
    if (!g.particles_given) options.particles = fill_option->count() ? kFillParticles : kMeshParticles;
    if (!g.radius_given) g.look.radius.model = RadiusModel::pipe;
    if (!g.base_radius_given) g.look.radius.base_radius = kMeshBaseRadius;
    if (!g.tip_radius_given) g.look.radius.tip_radius = kMeshTipRadius;
  }
  check_file_options(g, words, options.dimensions, g.has_mesh());
  if (!box.empty()) {
    const std::vector<double> b = parse_numbers("--box", box, 6);
    options.spawn_box = Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    if (options.spawn != SpawnMode::box) throw InvalidInput("--box is for --spawn box, not --spawn " + spawn);
  }
  if (!drift.empty()) options.drift = parse_vec3("--drift", drift);
  if (!rotate.empty()) {
    const std::size_t comma = rotate.find(',');
    if (comma == std::string::npos) throw InvalidInput("--rotate '" + rotate + "' is not AXIS,DEGREES (as y,30)");
    options.rotate_axis = parse_axis(rotate.substr(0, comma));
    options.rotate_degrees = parse_numbers("--rotate's degrees", rotate.substr(comma + 1), 1)[0];
  }
  g.constraint.side = parse_side(side);
  g.constraint.mode = parse_constraint_mode(constraint_mode);
  g.spacing_given = spacing->count() > 0;
  g.up_given = words.up_option->count() > 0;
  g.spawn_given = spawn_option->count() > 0;
  g.seeds_given = seed_at_option->count() > 0;
  if (!g.has_mesh() && seeds_option->count())
    throw InvalidInput("--seeds places seeds in a mesh given with --stl; without one, use --seed-at");
  if (!g.has_mesh() && g.seed_surface) throw InvalidInput("--seed-surface seeds a mesh's surface: give one with --stl");
  if (!g.has_mesh() && seed_paint_option->count())
    throw InvalidInput("--seed-paint seeds the painted part of a mesh: give one with --stl");
  if (!g.has_mesh() && !g.seed_mesh_paths.empty())
    throw InvalidInput("--seed-mesh seeds where a mesh meets the one given with --stl: give one");
  if (seed_paint_option->count()) g.seed_paint = parse_paint(seed_paint);
  if (seeds == "all") {
    // Without paint or other meshes, all of the surface.
    g.seed_surface = !g.seed_paint && g.seed_mesh_paths.empty();
  } else if (seeds_option->count()) {
    const bool digits = !seeds.empty() && seeds.size() <= 9 && seeds.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) throw InvalidInput("--seeds '" + seeds + "' is neither a count of seeds nor all");
    g.seed_count = std::stoul(seeds);
    if (g.seed_count == 0) throw InvalidInput("--seeds 0: there must be a seed");
  }
  if (!fill_option->count() && app.count("--fill-distance")) throw InvalidInput("--fill-distance is for --fill");
  if (shell_option->count()) {
    if (!g.has_mesh()) throw InvalidInput("--shell keeps growth near a mesh's surface: give one with --stl");
    detail::require_in("--shell", g.constraint.shell, 1.0, 1000.0);
  }
  if (!g.has_mesh()) {
    validate(options);
    if (spawns_from_mesh(options.spawn))
      throw InvalidInput("spawn " + spawn + " needs a mesh (--stl)");
    if (fill_option->count()) throw InvalidInput("--fill fills a mesh's volume: give one with --stl");
  } else if (g.spacing_given) {
    detail::require_in("spacing", options.spacing, kMinSpacing, kMaxSpacing);
  }
  return line;
}

}  // namespace dla::cli
