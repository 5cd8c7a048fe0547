// `dla3d [options]`: DLA's options, the top level's (Growth, Mesh constraint, Spawn, Long runs),
// turned into the library's DlaRunOptions; and --resume.

#include "options.h"

namespace dla::cli {

namespace {

//! The words of DLA's options that are not values of the run's options as they are.
struct GrowWords {
  long long particles = 10000;
  std::vector<std::string> seed_at;
  std::string spawn = std::string(to_string(SpawnMode::sphere));
  std::string box, drift, rotate;
  std::string side = std::string(to_string(Side::inside));
  std::string constraint_mode = std::string(to_string(ConstraintMode::reject));
  std::string text, font = kDefaultFont;
  std::string links;
  double spacing = 1.0;
  CLI::Option *particles_option, *spacing_option, *seed_at_option, *text_option, *font_option, *shell_option,
      *spawn_option, *threads_option;
  std::vector<OptionDescription> described;
  std::unique_ptr<DescribedOptions<DlaOptions>> walk;  // DLA's single values, from dla_option_table()
  std::unique_ptr<SeedWords> seeds;
  std::unique_ptr<OutputWords> files;
};

//! Only -q, --threads and --stream may go with --resume: every other option comes from the
//! checkpoint.
void check_resume_company(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--resume" || arg == "--threads" || arg == "--stream") ++i;
    else if (arg.rfind("--resume=", 0) != 0 && arg.rfind("--threads=", 0) != 0 && arg.rfind("--stream=", 0) != 0 &&
             arg != "-q" && arg != "--quiet")
      throw InvalidInput("--resume takes no other options but -q, --threads and --stream: they come from the checkpoint");
  }
}

//! DLA's options on `app`; with `dla` false, those of a model that walks as DLA does but has no
//! fill, drift, rotation, index choice or checkpoints (the breakdown model).
void add_options(CLI::App& app, DlaRunOptions& g, CommandLine& line, GrowWords& w, bool dla = true) {
  DlaOptions& options = g.growth;
  const char* growth = "Growth";
  w.particles_option = app.add_option("-n,--particles", w.particles, "particles to attach, seeds not counted; with a mesh, "
                                                                     "default 30000")->capture_default_str()->group(growth);
  w.spacing_option = app.add_option(
      "--spacing", w.spacing,
      "distance between a particle and its parent; also the contact distance, in [1e-25, 1e25]; "
      "with a mesh, default: its longest side / 100")->capture_default_str()->group(growth);
  w.seed_at_option =
      app.add_option("--seed-at", w.seed_at, "a seed at x,y,z (repeat for several); default: one at the origin")
          ->type_name("X,Y,Z")->allow_extra_args(false)->group(growth);
  app.add_option("--rng-seed", options.rng_seed, "seed of the random generator: the same seed gives the same files")
      ->capture_default_str()->group(growth);
  add_links_option(app, growth, w.links);
  // The breakdown model takes all but kNotForBreakdown (models.h).
  w.walk = std::make_unique<DescribedOptions<DlaOptions>>(
      app, dla_option_table(), options, &w.described,
      dla ? std::vector<std::string_view>{} : std::vector<std::string_view>(kNotForBreakdown.begin(), kNotForBreakdown.end()));
  w.threads_option = app.get_option("--threads");

  const char* meshes = "Mesh constraint";
  CLI::Option* stl_option = app.add_option("--stl,--mesh", g.stl, "grow constrained by this mesh: STL, OFF, OBJ or PLY")
                                ->type_name(kMeshFile)->group(meshes);
  w.text_option =
      app.add_option("--text", w.text, "grow in this text, extruded a quarter of its size (lines split at \\n): "
                                       "a mesh, as --stl's; one seed in each letter")
          ->type_name("TEXT")->group(meshes)->excludes(stl_option);
  w.font_option =
      app.add_option("--font", w.font, "--text's font: a TrueType or OpenType file")->capture_default_str()->group(meshes);
  app.add_option("--side", w.side, "inside, outside, both (the mesh is only a wall; not closed) or surface (over "
                                   "it, both sides, in a shell)")
      ->capture_default_str()->group(meshes);
  w.shell_option =
      app.add_option("--shell", g.constraint.shell, "keep growth within T spacings of the surface, on its side, "
                                                    "[1, 1000]: frost, lichen; with --side surface, default 3")
          ->type_name("T")->group(meshes);
  app.add_option("--constraint", w.constraint_mode, "a branch crossing the mesh: reject (walk on) or clip (end at it)")
      ->capture_default_str()->group(meshes);
  w.seeds = std::make_unique<SeedWords>(
      app, g.seeds, meshes, w.seed_at_option,
      "place K seeds on the growing side, far apart (default 1), or all: the surface, the paint or the --seed-mesh "
      "curves at the spacing (their default)",
      "start from the whole surface (or the painted part): seeds a spacing apart, half a spacing off it on the "
      "growing side");
  app.add_flag("--scene-mesh,!--no-scene-mesh", g.scene_mesh, "show the mesh, as glass, in the POV-Ray scene")
      ->capture_default_str()->group(meshes);
  if (dla)
    app.add_option("--fill", options.fill, "grow until this fraction of the mesh's volume lies within "
                                           "--fill-distance of the structure, (0, 1]; -n then caps it (default 1e7)")
        ->type_name("F")->group(meshes);

  const char* spawning = "Spawn";
  w.spawn_option =
      app.add_option("--spawn", w.spawn, "where walkers start: sphere, disk, box, or with a mesh inside, radial or surface; "
                                         "with --side inside, default surface" +
                                             std::string(dla ? "" : "; with a target, walkers leave it instead"))
          ->capture_default_str()->group(spawning);
  app.add_option("--box", w.box, "box: a fixed box; default: the cube around the launch sphere")
      ->type_name("X0,Y0,Z0,X1,Y1,Z1")->group(spawning);
  if (dla) {
    app.add_option("--drift", w.drift, "bias of every step, per unit step length, length < 1")
        ->type_name("X,Y,Z")->group(spawning);
    app.add_option("--rotate", w.rotate, "turn the spawn and the drift about the seeds' centre by DEGREES per 1000 "
                                         "particles, as if the structure turned while it grew: spirals; no mesh")
        ->type_name("AXIS,DEGREES")->group(spawning);
  }

  w.files = std::make_unique<OutputWords>(app, g.files, line.quiet);
  if (!dla) return;

  const char* runs = "Long runs";
  app.add_option("--checkpoint", line.checkpoint_path, "save the run to FILE as it goes, and when stopped by Ctrl-C or SIGTERM")
      ->type_name("FILE")->group(runs);
  app.add_option("--checkpoint-every", line.checkpoint_every, "seconds between saves")->capture_default_str()->group(runs);
  app.add_option("--resume", line.resume_path, "grow on from a checkpoint, with the options it was started with")
      ->type_name("FILE")->group(runs);
}

//! The words as DLA's run options. The checks that need to know what was given, which the run
//! options cannot tell, are made here; the library checks the rest.
void finish(CommandLine& line, DlaRunOptions& g, const GrowWords& w) {
  DlaOptions& options = g.growth;
  if (!(line.checkpoint_every >= 0.0))
    throw InvalidInput("--checkpoint-every " + detail::format_number(line.checkpoint_every) + " is not a number of seconds");
  w.walk->finish(options);
  const std::size_t particles = parse_count("--particles", w.particles);
  if (w.particles_option->count()) g.particles = particles;
  if (w.spacing_option->count()) g.spacing = w.spacing;
  if (w.seed_at_option->count()) g.seed_at = parse_points("--seed-at", w.seed_at);
  const SpawnMode spawn = parse_word<SpawnMode>(w.spawn);
  if (w.spawn_option->count()) g.spawn = spawn;
  g.links = links_of(w.links);
  w.files->finish(g.files);
  if (w.text_option->count()) {
    // "\n" typed in the shell is a line break.
    std::string text = w.text;
    for (std::size_t at = text.find("\\n"); at != std::string::npos; at = text.find("\\n", at + 1)) text.replace(at, 2, "\n");
    g.text = TextOptions{text, w.font};
  } else if (w.font_option->count()) {
    throw InvalidInput("--font is the font of --text: give the text");
  }
  validate(g.files, options.dimensions, g.has_mesh());
  if (!w.box.empty()) options.spawn_box = parse_box("--box", w.box);
  if (!w.drift.empty()) options.drift = parse_vec3("--drift", w.drift);
  if (!w.rotate.empty()) {
    const std::size_t comma = w.rotate.find(',');
    if (comma == std::string::npos) throw InvalidInput("--rotate '" + w.rotate + "' is not AXIS,DEGREES (as y,30)");
    options.rotate_axis = parse_word<Axis>(w.rotate.substr(0, comma));
    options.rotate_degrees = parse_numbers("--rotate's degrees", w.rotate.substr(comma + 1), 1)[0];
  }
  g.constraint.side = parse_word<Side>(w.side);
  g.constraint.mode = parse_word<ConstraintMode>(w.constraint_mode);
  w.seeds->finish(g.seeds, g.has_mesh());
  if (w.shell_option->count()) {
    if (!g.has_mesh()) throw InvalidInput("--shell keeps growth near a mesh's surface: give one with --stl");
    detail::require_in("--shell", g.constraint.shell, 1.0, 1000.0);
  }
  validate(g);
}

}  // namespace

WalkCommand add_walk_options(CLI::App& app, DlaRunOptions& run, bool& quiet, std::vector<OptionDescription>& described) {
  auto words = std::make_shared<GrowWords>();
  auto line = std::make_shared<CommandLine>();
  add_options(app, run, *line, *words, false);
  described.insert(described.end(), words->described.begin(), words->described.end());
  return {[words, line, &run, &quiet] {
    quiet = line->quiet;
    finish(*line, run, *words);
  }};
}

Subcommand add_grow_options(CLI::App& app, const Model&) {
  auto words = std::make_shared<GrowWords>();
  auto run = std::make_shared<DlaRunOptions>();
  auto line = std::make_shared<CommandLine>();  // the Long runs' and the quiet flag's words
  add_options(app, *run, *line, *words);
  return {&app, [words, run, line](CommandLine& out, const std::vector<std::string>& args) {
            out.quiet = line->quiet;
            out.checkpoint_path = line->checkpoint_path;
            out.checkpoint_every = line->checkpoint_every;
            if (!line->resume_path.empty()) {
              check_resume_company(args);
              out.kind = CommandLine::Kind::resume;
              out.resume_path = line->resume_path;
              words->walk->finish(run->growth);  // the thread count, the one growth option given
              if (words->threads_option->count()) out.threads = run->growth.threads;
              validate(run->growth);
              return;
            }
            finish(out, *run, *words);
            out.run = *run;
          },
          words->described};
}

}  // namespace dla::cli
