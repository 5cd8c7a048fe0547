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
  const Clock::time_point start = Clock::now();
  Cluster cluster;
  std::string error;  // why growth failed part way, if it did
  try {
    cluster = run.grow(
        [&](const Cluster& so_far) {
          bar.update(so_far.particles.size());
          return !stop.load();
        },
        &stop);
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
  write_run(run, cluster, files, record);

  if (!error.empty()) {
    std::fprintf(stderr, "dla3d: error: %s; %s.* hold the %s %s grown before it\n", error.c_str(), files.output.c_str(),
                 with_commas(static_cast<double>(cluster.particles.size())).c_str(), run.unit);
    return 1;
  }
  if (!files.quiet) {
    std::string written;
    for (const std::string& name : file_names(files)) written += (written.empty() ? "" : " ") + name;
    const std::string render = files.formats.pov ? "; render: povray +W1280 +H960 +A " + files.output + ".pov" : "";
    std::fprintf(stderr, "dla3d: %s\ndla3d: wrote %s%s\n", run.summary(cluster, record).c_str(), written.c_str(),
                 render.c_str());
  }
  if (!cluster.complete) {
    std::fprintf(stderr, "dla3d: stopped by %s after %s %s; the files hold them\n", signal_name(signal),
                 with_commas(static_cast<double>(cluster.particles.size())).c_str(), run.unit);
    return 128 + signal;
  }
  return 0;
}

}  // namespace dla::cli
