// `dla3d [options]`: grows a structure (in or around a mesh if one is given) and writes the
// POV-Ray scene, CSV, PLY and JSON sidecar; saves and resumes checkpoints.

#include "commands.h"
#include "run_files.h"

#include "dla/mesh/constraint.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/text.h"
#include "dla/core/hash.h"
#include "dla/io/run_report.h"

#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>

namespace dla::cli {

namespace {

//! Refuses, before growing, a run that cannot fit in this machine's memory: a structure takes
//! about 45 bytes a particle while it grows (docs/performance.md).
void check_memory(std::size_t particles) {
  constexpr double bytes_per_particle = 48.0;
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double memory = pages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double needed = bytes_per_particle * static_cast<double>(particles);
  if (pages > 0 && needed > memory)
    throw InvalidInput("--particles " + detail::format_count(particles) + " needs about " +
                       detail::format_number(needed / 1e9) + " GB of memory; this machine has " +
                       detail::format_number(memory / 1e9) + " GB");
}

}  // namespace

int grow(const GrowCommand& command, const std::vector<std::string>& args, const Checkpoint* resumed,
         const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal) {
  GrowthOptions options = command.options;
  PovOptions pov = command.pov;
  const std::string& output = command.output;
  std::unique_ptr<MeshConstraint> constraint;
  TriangleMesh scene_mesh;  // the scene's mesh when it is more than the constraint's
  std::uint64_t input_hash = 0;
  const std::string mesh_name = command.text ? "the text '" + command.text->text + "'" : command.mesh_path;
  {
    check_writable(file_names(command).front());  // before a mesh's set-up and a long run
    if (!command.checkpoint_path.empty()) check_writable(command.checkpoint_path);
    if (command.has_mesh()) {
      TriangleMesh mesh;
      std::vector<Vec3> letter_seeds;
      if (command.text) {
        TextMesh text = text_mesh(*command.text);
        mesh = std::move(text.mesh);
        letter_seeds = std::move(text.glyph_seeds);
        // The text's own hash: the same words in another font are another mesh.
        input_hash = fnv1a({reinterpret_cast<const char*>(mesh.vertices.data()), mesh.vertices.size() * sizeof(Vec3)});
      } else {
        mesh = read_mesh(command.mesh_path, &input_hash);
      }
      if (resumed && resumed->input_hash != input_hash)
        throw InvalidInput(mesh_name + " has changed since the checkpoint was written: the run cannot go on");
      const Box box = bounding_box(mesh);
      // Text is long and thin: a hundredth of its em leaves strokes some 17 spacings wide.
      if (!command.spacing_given) options.spacing = command.text ? command.text->size / 100 : default_spacing(box);
      // Text reads upright with y up; a scan stands on its longest axis.
      if (!command.up_given) pov.up = command.text ? Axis::y : longest_axis(box);
      detail::require_in("spacing", options.spacing, kMinSpacing, kMaxSpacing);
      try {
        constraint = std::make_unique<MeshConstraint>(mesh, command.constraint, options.spacing);
      } catch (const InvalidInput& e) {
        throw InvalidInput(mesh_name + ": " + e.what());
      }
      // From the skin inside: thin parts (horns, fingers) get walkers by their surface. To fill
      // the volume, or to grow from seeds lining the skin, from anywhere in the volume: the
      // skin, covered, would stop walkers from the surface long before the inside is full.
      const bool whole_surface = command.seed_surface && !command.seed_paint;
      // In a shell, anywhere in it: walkers reach the structure over the surface.
      if (!command.spawn_given)
        options.spawn = constraint->shell() > 0.0                ? SpawnMode::inside
                        : command.constraint.side != Side::inside ? SpawnMode::sphere
                        : options.fill > 0.0 || whole_surface     ? SpawnMode::inside
                                                                  : SpawnMode::surface;
      if (command.seed_surface || command.seed_paint || !command.seed_mesh_paths.empty()) {
        std::vector<TriangleMesh> entering;
        for (const std::string& path : command.seed_mesh_paths) entering.push_back(read_mesh(path));
        // The scene shows the meshes that enter with the one they enter, to see where growth starts.
        if (!entering.empty() && command.scene_mesh) {
          scene_mesh = constraint->mesh();
          for (const TriangleMesh& other : entering) append(scene_mesh, other);
        }
        try {
          const std::vector<Vec3> cover =
              entering.empty() ? constraint->sample_surface(options.rng_seed, command.seed_paint ? &*command.seed_paint : nullptr)
                               : constraint->sample_intersection(entering, options.rng_seed);
          options.seeds = command.seed_count ? farthest_apart(cover, command.seed_count) : cover;
        } catch (const InvalidInput& e) {
          throw InvalidInput(mesh_name + ": " + e.what());
        }
      } else if (command.text && !command.seeds_given && !command.seed_count) {
        // Each letter is a volume of its own: a seed deep in each, or in a shell (whose parts
        // around letters far apart do not meet) or around the text, half a spacing off its front.
        options.seeds = letter_seeds;
        if (command.constraint.side != Side::inside || constraint->shell() > 0.0)
          for (Vec3& seed : options.seeds)
            seed.z() = command.text->depth + (command.constraint.side == Side::inside ? -0.5 : 0.5) * options.spacing;
      } else if (!command.seeds_given) {
        options.seeds = constraint->place_seeds(command.seed_count ? command.seed_count : 1, options.rng_seed);
      }
      validate(options, *constraint);
    }
    check_memory(options.particles);
    // Only once every option is known good: bad input gets its one line and nothing else.
    if (constraint && !command.quiet)
      std::fprintf(stderr, "dla3d: %s: %s triangles; %s; spacing %g\n", mesh_name.c_str(),
                   with_commas(static_cast<double>(constraint->repair_report().input_triangles)).c_str(),
                   constraint->repair_report().summary().c_str(), options.spacing);
  }

  ProgressBar bar(options.particles, !command.quiet && isatty(STDERR_FILENO));
  const Clock::time_point start = Clock::now();
  Clock::time_point saved = start;
  // A save that fails (a full disk) is reported once and does not stop the run.
  bool save_failed = false;
  const auto save = [&](const Cluster& so_far) {
    if (command.checkpoint_path.empty()) return;
    try {
      write_checkpoint({args, input_hash, so_far}, command.checkpoint_path);
    } catch (const IOError& e) {
      bar.clear();
      if (!save_failed) std::fprintf(stderr, "dla3d: warning: %s; growth goes on\n", e.what());
      save_failed = true;
    }
  };
  const auto progress = [&](const Cluster& so_far) {
    bar.update(attached(so_far), so_far.filled, options.fill);
    if (stop.load()) return false;
    if (!command.checkpoint_path.empty() &&
        Clock::now() - saved >= std::chrono::duration<double>(command.checkpoint_every)) {
      save(so_far);
      saved = Clock::now();
    }
    return true;
  };
  Cluster cluster;
  std::string error;  // why growth failed part way, if it did
  try {
    cluster = resumed ? (constraint ? resume(options, *constraint, resumed->cluster, progress, &stop)
                                    : resume(options, resumed->cluster, progress, &stop))
                      : (constraint ? dla::grow(options, *constraint, progress, &stop)
                                    : dla::grow(options, progress, &stop));
  } catch (const PartialGrowth& e) {
    cluster = e.partial();
    error = e.what();
  }
  bar.clear();
  RunRecord record;
  record.grow_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  record.command = command_line(args);
  const int signal = stop_signal;
  if (!error.empty()) record.stopped_by = "error: " + error;
  else if (!cluster.complete) record.stopped_by = signal_name(signal);

  pov.comment = record.command;
  const Clock::time_point write_start = Clock::now();
  write_files(cluster, command, pov, options.threads, constraint.get(),
              !scene_mesh.triangles.empty()            ? &scene_mesh
              : constraint && command.scene_mesh ? &constraint->mesh()
                                                 : nullptr);
  record.write_seconds = std::chrono::duration<double>(Clock::now() - write_start).count();
  if (command.formats.json)
    write_run_report(cluster, options, command.look, pov, record, output + ".json", constraint.get(), mesh_name);
  if (!cluster.complete) save(cluster);  // after the files: they matter more

  const std::string resume_hint =
      command.checkpoint_path.empty() ? "" : "; go on with: dla3d --resume " + command.checkpoint_path;
  const std::string grown = with_commas(static_cast<double>(attached(cluster)));
  if (!error.empty()) {
    std::fprintf(stderr, "dla3d: error: %s; %s.* hold the %s particles grown before it\n", error.c_str(),
                 output.c_str(), grown.c_str());
    return 1;
  }
  if (!command.quiet) {
    const double count = static_cast<double>(attached(cluster));
    std::string written;
    for (const std::string& name : file_names(command)) written += (written.empty() ? "" : " ") + name;
    const std::string render = command.formats.pov ? "; render: povray +W1280 +H960 +A " + output + ".pov" : "";
    char filled[160] = "";
    if (options.fill > 0.0)
      std::snprintf(filled, sizeof filled, "; %.1f%% of the mesh's volume within %g spacings of it%s",
                    100.0 * cluster.filled, options.fill_distance,
                    cluster.filled >= options.fill ? "" : ", short of the fill asked (-n ended growth)");
    std::fprintf(stderr,
                 "dla3d: grew %s particles in %.2f s (%s particles/s); bounding radius %.1f, "
                 "radius of gyration %.1f%s\n"
                 "dla3d: wrote %s%s\n",
                 grown.c_str(), record.grow_seconds,
                 with_commas(record.grow_seconds > 0 ? count / record.grow_seconds : 0.0).c_str(),
                 bounding_radius(cluster), radius_of_gyration(cluster), filled, written.c_str(), render.c_str());
  }
  if (!cluster.complete) {
    std::fprintf(stderr, "dla3d: stopped by %s after %s of %s particles; the files hold them%s\n",
                 signal_name(signal), grown.c_str(), with_commas(static_cast<double>(options.particles)).c_str(),
                 resume_hint.c_str());
    return 128 + signal;
  }
  if (!command.checkpoint_path.empty()) std::remove(command.checkpoint_path.c_str());  // whole: nothing to resume
  return 0;
}

}  // namespace dla::cli
