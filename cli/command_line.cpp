#include "command_line.h"

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
                 : word == "tips" ? &formats.tips : word == "svg" ? &formats.svg : nullptr;
    if (!format)
      throw InvalidInput("--formats '" + text + "': '" + word + "' is not one of pov, csv, ply, json, glb, obj, tips, svg");
    *format = any = true;
  }
  if (!any) throw InvalidInput("--formats is empty: name at least one of pov, csv, ply, json, glb, obj, tips, svg");
  return formats;
}

Vec3 parse_vec3(const std::string& flag, const std::string& text) {
  const std::vector<double> v = parse_numbers(flag, text, 3);
  return {v[0], v[1], v[2]};
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

}  // namespace

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
  std::string box, drift, index = std::string(to_string(options.index));
  std::string side = std::string(to_string(g.constraint.side));
  std::string constraint_mode = std::string(to_string(g.constraint.mode));
  std::string up = std::string(to_string(g.pov.up));
  std::string radius_model = std::string(to_string(g.look.radius.model));
  std::string color_by = std::string(to_string(g.look.color_by));
  std::string instance_set = std::string(to_string(g.instances.set));
  std::string pov_style = std::string(to_string(g.pov.style));
  std::string formats = "pov,csv,ply,json";

  const char* growth = "Growth";
  CLI::Option* particles_option =
      app.add_option("-n,--particles", particles, "particles to attach, seeds not counted; with a mesh, "
                                                  "default 30000")->capture_default_str()->group(growth);
  CLI::Option* spacing = app.add_option(
      "--spacing", options.spacing,
      "distance between a particle and its parent; also the contact distance, in [1e-100, 1e100]; "
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
  app.add_option("--stl,--mesh", g.mesh_path, "grow constrained by this mesh: STL, OFF, OBJ or PLY")
      ->type_name("FILE")->group(meshes);
  app.add_option("--side", side, "inside, outside or both (the mesh is only a wall; not closed)")
      ->capture_default_str()->group(meshes);
  app.add_option("--constraint", constraint_mode, "a branch crossing the mesh: reject (walk on) or clip (end at it)")
      ->capture_default_str()->group(meshes);
  CLI::Option* seeds_option =
      app.add_option("--seeds", g.seed_count, "place this many seeds on the growing side, far apart; default 1")
          ->type_name("K")->group(meshes)->excludes(seed_at_option);
  app.add_flag("--scene-mesh,!--no-scene-mesh", g.scene_mesh, "show the mesh, as glass, in the POV-Ray scene")
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

  const char* outputs = "Output";
  app.add_option("-o,--output", g.output, "prefix of the files written")->capture_default_str()->group(outputs);
  app.add_flag("--binary", g.binary_ply, "write the PLYs as binary (little-endian): half the size, "
                                         "ten times faster")->group(outputs);
  app.add_option("--formats", formats, "files to write, a comma list of pov, csv, ply, json, glb, obj, tips "
                                      "(PREFIX_tips.ply) and svg (2D)")->capture_default_str()->group(outputs);

  const char* looks = "Look";
  CLI::Option* radius_option =
      app.add_option("--radius", radius_model, "branch thickness: taper, pipe, boundary (needs a mesh), "
                                               "seed-distance or uniform; with a mesh, default pipe")
          ->capture_default_str()->group(looks);
  CLI::Option* base_radius_option =
      app.add_option("--base-radius", g.look.radius.base_radius, "the thickest branch's radius, in spacings, "
                                                                 "[0.001, 1000]; with a mesh, default 3")
          ->capture_default_str()->group(looks);
  CLI::Option* tip_radius_option =
      app.add_option("--tip-radius", g.look.radius.tip_radius, "the finest branch's radius, in spacings, "
                                                               "[0.001, 1000]; with a mesh, default 0.05")
          ->capture_default_str()->group(looks);
  app.add_option("--pipe-exponent", g.look.radius.pipe_exponent, "pipe: e in r = tip * (descendants + 1)^(1/e), "
                                                                  "[1, 10]; 2 keeps the area, 3 is Murray's law")
      ->capture_default_str()->group(looks);
  app.add_option("--color-by", color_by, "colour the glb, obj, svg and POV-Ray scene by none, age, depth, "
                                         "seed or distance (to the mesh, or to the seeds)")
      ->capture_default_str()->group(looks);
  app.add_option("--look", pov_style, "POV-Ray: branches (sphere sweeps) or blob (metaballs)")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-sides", g.look.tubes.sides, "glb, obj: vertices around a tube, 3-64")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-tolerance", g.look.tubes.tolerance, "glb, obj: leave out strand points the tube "
                                                             "passes within this of, in spacings, [0, 10]")
      ->capture_default_str()->group(looks);
  app.add_option("--tube-min-branch", g.look.tubes.min_branch, "glb, obj: leave out branches of fewer particles "
                                                                "(counting all that grow from them), 1-1000")
      ->capture_default_str()->group(looks);
  app.add_option("--instances", instance_set, "tips: which particles are instancing points, tips or all")
      ->capture_default_str()->group(looks);
  app.add_option("--tips-within", g.instances.within, "tips: only points within this of the mesh's "
                                                      "surface, in spacings, >= 0")->group(looks);
  CLI::Option* up_option =
      app.add_option("--up", up, "POV-Ray: the axis that is up in the picture, x, y or z; with a mesh, "
                                 "default: its longest side's")->capture_default_str()->group(outputs);
  app.add_flag("-q,--quiet", g.quiet, "no progress bar and no summary")->group(outputs);

  const char* runs = "Long runs";
  app.add_option("--checkpoint", g.checkpoint_path, "save the run to FILE as it goes, and when stopped by Ctrl-C or SIGTERM")
      ->type_name("FILE")->group(runs);
  app.add_option("--checkpoint-every", g.checkpoint_every, "seconds between saves")->capture_default_str()->group(runs);
  CLI::Option* resume_option =
      app.add_option("--resume", line.resume_path, "grow on from a checkpoint, with the options it was started with")
          ->type_name("FILE")->group(runs);

  CLI::App* convert_command =
      app.add_subcommand("convert", "read a mesh (STL, OFF, OBJ, PLY) and write it as binary STL, then stop");
  convert_command->add_option("in", line.convert_in, "the mesh to read")->required();
  convert_command->add_option("out", line.convert_out, "the .stl to write")->required();
  CLI::App* analyze_command = app.add_subcommand(
      "analyze", "print the fractal dimension of a grown structure (by gyration and by mass-radius) as JSON");
  analyze_command->add_option("csv", line.analyze_csv, "a CSV that dla3d wrote")->required();
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
  g.pov.up = parse_axis(up);
  g.pov.style = parse_pov_style(pov_style);
  g.look.radius.model = parse_radius_model(radius_model);
  g.look.color_by = parse_color_by(color_by);
  g.instances.set = parse_instance_set(instance_set);
  g.formats = parse_formats(formats);
  g.particles_given = particles_option->count() > 0;
  g.radius_given = radius_option->count() > 0;
  g.base_radius_given = base_radius_option->count() > 0;
  g.tip_radius_given = tip_radius_option->count() > 0;
  if (!g.mesh_path.empty()) {
    // Inside a mesh, a root system: enough particles to fill a bust at the default spacing,
    // short of the 35,000 or so that cover its skin, where the surface spawn starts walkers;
    // thick trunks and fine tips (docs/look.md shows the main job's picture).
    if (!g.particles_given) options.particles = kMeshParticles;
    if (!g.radius_given) g.look.radius.model = RadiusModel::pipe;
    if (!g.base_radius_given) g.look.radius.base_radius = kMeshBaseRadius;
    if (!g.tip_radius_given) g.look.radius.tip_radius = kMeshTipRadius;
  }
  validate(g.look);
  validate(g.instances);
  if (g.formats.svg && options.dimensions != 2)
    throw InvalidInput("--formats svg draws 2D growth: add --dimensions 2, or leave svg out");
  if (g.mesh_path.empty()) {
    if (g.look.radius.model == RadiusModel::boundary)
      throw InvalidInput("--radius boundary measures to a constraint mesh: give one with --stl");
    if (app.count("--tips-within")) throw InvalidInput("--tips-within measures to a constraint mesh: give one with --stl");
  }
  if (!box.empty()) {
    const std::vector<double> b = parse_numbers("--box", box, 6);
    options.spawn_box = Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    if (options.spawn != SpawnMode::box) throw InvalidInput("--box is for --spawn box, not --spawn " + spawn);
  }
  if (!drift.empty()) options.drift = parse_vec3("--drift", drift);
  if (g.output.empty()) throw InvalidInput("--output is empty");
  if (g.output.back() == '/') throw InvalidInput("--output '" + g.output + "' names a folder, not a file prefix");
  if (g.formats.pov) validate_pov_prefix(g.output);
  g.constraint.side = parse_side(side);
  g.constraint.mode = parse_constraint_mode(constraint_mode);
  g.spacing_given = spacing->count() > 0;
  g.up_given = up_option->count() > 0;
  g.spawn_given = spawn_option->count() > 0;
  g.seeds_given = seed_at_option->count() > 0;
  if (g.mesh_path.empty() && seeds_option->count())
    throw InvalidInput("--seeds places seeds in a mesh given with --stl; without one, use --seed-at");
  if (seeds_option->count() && g.seed_count == 0) throw InvalidInput("--seeds 0: there must be a seed");
  if (g.mesh_path.empty()) {
    validate(options);
    if (spawns_from_mesh(options.spawn))
      throw InvalidInput("spawn " + spawn + " needs a mesh (--stl)");
  } else if (g.spacing_given) {
    detail::require_in("spacing", options.spacing, kMinSpacing, kMaxSpacing);
  }
  return line;
}

}  // namespace dla::cli
