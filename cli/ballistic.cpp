// `dla3d ballistic [options]`: grows by ballistic aggregation (dla/models/ballistic.h) and
// writes the same files as DLA does.

#include "commands.h"
#include "run_files.h"

#include "dla/io/run_report.h"

#include <cstdio>

namespace dla::cli {

int ballistic(const BallisticCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
              const volatile std::sig_atomic_t& stop_signal) {
  const BallisticOptions& options = command.options;
  check_writable(file_names(command).front());
  BallisticStats stats;
  ModelRun run;
  run.total = options.seeds.size() + options.particles;
  return run_model(
      command, args, run, stop, stop_signal,
      [&](const ProgressFn& progress) { return dla::ballistic(options, progress, &stop, &stats); },
      [&](const Cluster& cluster, const PovOptions& pov, const RunRecord& record) {
        write_ballistic_report(cluster, options, stats, command.look, pov, record, command.output + ".json");
      },
      [&](const Cluster& cluster, const RunRecord& record) {
        char line[256];
        std::snprintf(line, sizeof line, "grew %s particles from %s lines (%s missed) in %.2f s; bounding radius %.1f",
                      with_commas(static_cast<double>(attached(cluster))).c_str(),
                      with_commas(static_cast<double>(stats.launched)).c_str(),
                      with_commas(static_cast<double>(stats.missed)).c_str(), record.grow_seconds,
                      bounding_radius(cluster));
        return std::string(line);
      });
}

}  // namespace dla::cli
