// `dla3d colonize [options]`: grows a tree by space colonization (dla/models/colonization.h)
// among attractors scattered or read from a file, and writes the same files as DLA does.

#include "commands.h"
#include "run_files.h"

#include "dla/mesh/mesh.h"
#include "dla/io/run_report.h"

#include <unistd.h>

#include <cstdio>
#include <memory>

namespace dla::cli {

int colonize(const ColonizeCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
             const volatile std::sig_atomic_t& stop_signal) {
  const ColonizationOptions& options = command.options;
  check_writable(file_names(command).front());
  ColonizationOptions grown_with = options;
  const auto read_solid = [](const std::string& path, const auto& make) {
    try {
      return make(read_mesh(path));
    } catch (const InvalidInput& e) {
      throw InvalidInput(path + ": " + e.what());
    }
  };
  std::unique_ptr<MeshConstraint> vessel;
  if (!command.vessel_path.empty()) {
    vessel = read_solid(command.vessel_path, [&](const TriangleMesh& mesh) {
      const ConstraintOptions inside{Side::inside, ConstraintMode::reject};
      return std::make_unique<MeshConstraint>(mesh, inside, options.spacing);
    });
    grown_with.vessel = vessel.get();
  }
  std::unique_ptr<CollisionObject> collide;
  if (!command.collide_path.empty()) {
    collide = read_solid(command.collide_path, [&](const TriangleMesh& mesh) {
      return std::make_unique<CollisionObject>(mesh, options.spacing, command.collision);
    });
    grown_with.collide = collide.get();
  }
  // Attractors and roots in or on "the mesh": the vessel's, else the collision object's.
  const MeshConstraint* mesh = vessel ? vessel.get() : collide ? &collide->solid() : nullptr;

  std::vector<Vec3> attractors;
  if (command.attractors_path.empty()) {
    attractors = scatter_attractors(command.attractors, options.rng_seed, options.dimensions, mesh);
  } else {
    attractors = read_points(command.attractors_path);
    if (command.sample_attractors)
      attractors = sample_attractors(attractors, command.attractors.count, options.rng_seed);
    if (attractors.size() > kMaxAttractors)
      throw InvalidInput(command.attractors_path + ": more than 1e8 attractors");
    if (options.dimensions == 2)
      for (const Vec3& a : attractors)
        if (a.z() != 0.0)
          throw InvalidInput(command.attractors_path + ": --dimensions 2 grows in z = 0, and an attractor is not");
  }
  const std::vector<Vec3> roots = colonize_roots(command, attractors, mesh);
  ColonizationInputs inputs{command.attractors_path, attractors.size(), command.vessel_path, command.collide_path,
                            command.collision};

  ProgressBar bar(options.max_nodes, !command.quiet && isatty(STDERR_FILENO));
  const Clock::time_point start = Clock::now();
  const Cluster tree = dla::colonize(
      grown_with, std::move(attractors), roots,
      [&](const Cluster& so_far) {
        bar.update(so_far.particles.size());
        return !stop.load();
      },
      &stop);
  bar.clear();
  RunRecord record;
  record.grow_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  record.command = command_line(args);
  const int signal = stop_signal;
  if (!tree.complete) record.stopped_by = signal_name(signal);

  PovOptions pov = command.pov;
  pov.comment = record.command;
  const Clock::time_point write_start = Clock::now();
  // The vessel, else the collision mesh, shows in the scene as glass, as a constraint mesh does.
  write_files(tree, command, pov, 1, vessel.get(), mesh ? &mesh->mesh() : nullptr);
  record.write_seconds = std::chrono::duration<double>(Clock::now() - write_start).count();
  if (command.formats.json)
    write_colonization_report(tree, options, command.attractors, command.look, pov, record, command.output + ".json",
                              inputs);

  const std::string nodes = with_commas(static_cast<double>(tree.particles.size()));
  if (!command.quiet) {
    std::string written;
    for (const std::string& name : file_names(command)) written += (written.empty() ? "" : " ") + name;
    const std::string render =
        command.formats.pov ? "; render: povray +W1280 +H960 +A " + command.output + ".pov" : "";
    std::fprintf(stderr, "dla3d: grew %s nodes from %s root%s in %.2f s; bounding radius %.1f\n"
                         "dla3d: wrote %s%s\n",
                 nodes.c_str(), with_commas(static_cast<double>(tree.seed_count)).c_str(),
                 tree.seed_count == 1 ? "" : "s", record.grow_seconds, bounding_radius(tree), written.c_str(),
                 render.c_str());
  }
  if (!tree.complete) {
    std::fprintf(stderr, "dla3d: stopped by %s after %s nodes; the files hold them\n", signal_name(signal),
                 nodes.c_str());
    return 128 + signal;
  }
  return 0;
}

}  // namespace dla::cli
