// `dla3d drop [options]`: grows by random-drop ballistic aggregation (dla/models/drop.h),
// constrained by a mesh if one is given, and writes the same files as DLA does.

#include "commands.h"
#include "run_files.h"

#include "dla/io/run_report.h"
#include "dla/mesh/mesh.h"

#include <cstdio>
#include <memory>

namespace dla::cli {

int drop(const DropCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
         const volatile std::sig_atomic_t& stop_signal) {
  DropCommand files = command;  // the scene's up axis may come from the mesh
  DropOptions& options = files.options;
  check_writable(file_names(command).front());
  std::unique_ptr<MeshConstraint> constraint;
  if (!command.mesh_path.empty()) {
    // As for DLA: the spacing and the up axis from the mesh's box, one seed on the growing side.
    const TriangleMesh mesh = read_mesh(command.mesh_path);
    const Box box = bounding_box(mesh);
    if (!command.spacing_given) options.spacing = default_spacing(box);
    if (!command.up_given) files.pov.up = longest_axis(box);
    detail::require_in("spacing", options.spacing, kMinSpacing, kMaxSpacing);
    try {
      constraint = std::make_unique<MeshConstraint>(mesh, command.constraint, options.spacing);
      if (!command.seeds_given) options.seeds = constraint->place_seeds(1, options.rng_seed);
      validate(options, *constraint);
    } catch (const InvalidInput& e) {
      throw InvalidInput(command.mesh_path + ": " + e.what());
    }
    if (!command.quiet)
      std::fprintf(stderr, "dla3d: %s: %s triangles; %s; spacing %g\n", command.mesh_path.c_str(),
                   with_commas(static_cast<double>(constraint->repair_report().input_triangles)).c_str(),
                   constraint->repair_report().summary().c_str(), options.spacing);
  }

  DropStats stats;
  ModelRun run;
  run.total = options.seeds.size() + options.particles;
  run.constraint = constraint.get();
  run.scene_mesh = constraint && command.scene_mesh ? &constraint->mesh() : nullptr;
  return run_model(
      files, args, run, stop, stop_signal,
      [&](const ProgressFn& progress) { return dla::drop(options, constraint.get(), progress, &stop, &stats); },
      [&](const Cluster& cluster, const PovOptions& pov, const RunRecord& record) {
        write_drop_report(cluster, options, stats, constraint.get(), command.mesh_path, command.look, pov, record,
                          command.output + ".json");
      },
      [&](const Cluster& cluster, const RunRecord& record) {
        char line[320];
        std::snprintf(line, sizeof line, "grew %s particles from %s drops in %.2f s%s; %s fell on the structure; "
                                         "bounding radius %.1f",
                      with_commas(static_cast<double>(attached(cluster))).c_str(),
                      with_commas(static_cast<double>(stats.drops)).c_str(), record.grow_seconds,
                      stats.zone_full ? " (then the drop zone was full)" : "",
                      with_commas(static_cast<double>(stats.on_structure)).c_str(), bounding_radius(cluster));
        return std::string(line);
      });
}

}  // namespace dla::cli
