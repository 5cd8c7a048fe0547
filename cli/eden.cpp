// `dla3d eden [options]`: grows an Eden cluster on a lattice (dla/models/eden.h) and writes the
// same files as DLA does.

#include "commands.h"
#include "run_files.h"

#include "dla/io/run_report.h"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace dla::cli {

int eden(const EdenCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
         const volatile std::sig_atomic_t& stop_signal) {
  EdenOptions options = command.options;
  if (!command.mask_path.empty()) {
    std::ifstream in(command.mask_path, std::ios::binary);
    std::ostringstream text;
    if (!in || !(text << in.rdbuf())) throw IOError("cannot read the mask '" + command.mask_path + "'");
    try {
      options.mask_offsets = parse_mask(text.str());
      validate(options);
    } catch (const InvalidInput& e) {
      throw InvalidInput(command.mask_path + ": " + e.what());
    }
  }
  check_writable(file_names(command).front());

  ModelRun run;
  run.total = options.sites;
  run.unit = "sites";
  return run_model(
      command, args, run, stop, stop_signal,
      [&](const ProgressFn& progress) { return dla::eden(options, progress, &stop); },
      [&](const Cluster& cluster, const PovOptions& pov, const RunRecord& record) {
        write_eden_report(cluster, options, command.mask_path, command.look, pov, record, command.output + ".json");
      },
      [&](const Cluster& cluster, const RunRecord& record) {
        char line[256];
        std::snprintf(line, sizeof line, "grew %s sites on a %s lattice in %.2f s%s; bounding radius %.1f",
                      with_commas(static_cast<double>(cluster.particles.size())).c_str(),
                      std::string(to_string(options.lattice)).c_str(), record.grow_seconds,
                      cluster.complete && cluster.particles.size() < options.sites ? " (then no site could stick)" : "",
                      bounding_radius(cluster));
        return std::string(line);
      });
}

}  // namespace dla::cli
