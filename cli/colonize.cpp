// `dla3d colonize [options]`: grows a tree by space colonization (dla/models/colonization.h)
// among attractors scattered or read from a file, and writes the same files as DLA does.

#include "commands.h"
#include "run_files.h"

#include "dla/mesh/mesh.h"
#include "dla/io/run_report.h"


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

  ModelRun run;
  run.total = options.max_nodes;
  run.unit = "nodes";
  // The vessel, else the collision mesh, shows in the scene as glass, as a constraint mesh does.
  run.constraint = vessel.get();
  run.scene_mesh = mesh ? &mesh->mesh() : nullptr;
  return run_model(
      command, args, run, stop, stop_signal,
      [&](const ProgressFn& progress) { return dla::colonize(grown_with, std::move(attractors), roots, progress, &stop); },
      [&](const Cluster& tree, const PovOptions& pov, const RunRecord& record) {
        write_colonization_report(tree, options, command.attractors, command.look, pov, record,
                                  command.output + ".json", inputs);
      },
      [&](const Cluster& tree, const RunRecord& record) {
        char line[256];
        std::snprintf(line, sizeof line, "grew %s nodes from %s root%s in %.2f s; bounding radius %.1f",
                      with_commas(static_cast<double>(tree.particles.size())).c_str(),
                      with_commas(static_cast<double>(tree.seed_count)).c_str(), tree.seed_count == 1 ? "" : "s",
                      record.grow_seconds, bounding_radius(tree));
        return std::string(line);
      });
}

}  // namespace dla::cli
