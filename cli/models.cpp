// `dla3d colonize`, `dla3d eden`, `dla3d drop` and `dla3d ballistic`: each grows its model's
// run (model_run.cpp sets it up) under the progress bar and writes the same files as DLA does.

#include "commands.h"
#include "model_run.h"
#include "run_files.h"

#include <cstdio>

namespace dla::cli {

int run_model(const CommandLine& line, const std::vector<std::string>& args, const StopFlag& stop,
              const volatile std::sig_atomic_t& stop_signal) {
  check_writable(file_names(*line.growth_files()).front());  // before a mesh's set-up and a long run
  const std::unique_ptr<ModelRun> run_owner = prepare_run(line);
  ModelRun& run = *run_owner;
  const FileOptions& files = run.files;
  if (!files.quiet && !run.mesh_line.empty()) std::fprintf(stderr, "dla3d: %s\n", run.mesh_line.c_str());

  ProgressBar bar(run.total, !files.quiet && isatty(STDERR_FILENO));
  const auto progress = [&](const Cluster& so_far) {
    bar.update(run.done(so_far));
    return !stop.load();
  };
  RunRecord record;
  std::string error;  // why growth failed part way, if it did
  const Cluster cluster = grow_recorded(run, progress, stop, stop_signal, args, record, error);
  bar.clear();
  const int signal = stop_signal;
  write_run(run, cluster, files, record);

  if (!error.empty()) {
    std::fprintf(stderr, "dla3d: error: %s; %s.* hold the %s %s grown before it\n", error.c_str(), files.output.c_str(),
                 with_commas(static_cast<double>(cluster.particles.size())).c_str(), run.unit);
    return 1;
  }
  if (!files.quiet) print_summary(run, cluster, files, record);
  if (!cluster.complete) {
    std::fprintf(stderr, "dla3d: stopped by %s after %s %s; the files hold them\n", signal_name(signal),
                 with_commas(static_cast<double>(cluster.particles.size())).c_str(), run.unit);
    return 128 + signal;
  }
  return 0;
}

}  // namespace dla::cli
