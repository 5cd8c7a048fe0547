// `dla3d [options]`: grows a structure by DLA (in or around a mesh if one is given;
// model_run.cpp sets the run up) and writes the POV-Ray scene, CSV, PLY and JSON sidecar;
// saves and resumes checkpoints.

#include "commands.h"
#include "model_run.h"
#include "run_files.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <memory>

namespace dla::cli {

int grow(const CommandLine& line, const std::vector<std::string>& args, const Checkpoint* resumed,
         const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal) {
  const GrowCommand& command = line.grow;
  const std::string& output = command.output;
  check_writable(file_names(command).front());  // before a mesh's set-up and a long run
  if (!command.checkpoint_path.empty()) check_writable(command.checkpoint_path);
  const std::unique_ptr<ModelRun> run = prepare_run(line, resumed);
  // Only once every option is known good: bad input gets its one line and nothing else.
  if (!command.quiet && !run->mesh_line.empty()) std::fprintf(stderr, "dla3d: %s\n", run->mesh_line.c_str());

  ProgressBar bar(run->total, !command.quiet && isatty(STDERR_FILENO));
  Clock::time_point saved = Clock::now();
  // A save that fails (a full disk) is reported once and does not stop the run.
  bool save_failed = false;
  const auto save = [&](const Cluster& so_far) {
    if (command.checkpoint_path.empty()) return;
    try {
      write_checkpoint({args, run->input_hash, so_far}, command.checkpoint_path);
    } catch (const IOError& e) {
      bar.clear();
      if (!save_failed) std::fprintf(stderr, "dla3d: warning: %s; growth goes on\n", e.what());
      save_failed = true;
    }
  };
  const auto progress = [&](const Cluster& so_far) {
    bar.update(run->done(so_far), so_far.filled, run->fill);
    if (stop.load()) return false;
    if (!command.checkpoint_path.empty() &&
        Clock::now() - saved >= std::chrono::duration<double>(command.checkpoint_every)) {
      save(so_far);
      saved = Clock::now();
    }
    return true;
  };
  RunRecord record;
  std::string error;  // why growth failed part way, if it did
  const Cluster cluster = grow_recorded(*run, progress, stop, stop_signal, args, record, error);
  bar.clear();
  const int signal = stop_signal;
  write_run(*run, cluster, run->files, record);
  if (!cluster.complete) save(cluster);  // after the files: they matter more

  const std::string resume_hint =
      command.checkpoint_path.empty() ? "" : "; go on with: dla3d --resume " + command.checkpoint_path;
  const std::string grown = with_commas(static_cast<double>(attached(cluster)));
  if (!error.empty()) {
    std::fprintf(stderr, "dla3d: error: %s; %s.* hold the %s particles grown before it\n", error.c_str(),
                 output.c_str(), grown.c_str());
    return 1;
  }
  if (!command.quiet) print_summary(*run, cluster, run->files, record);
  if (!cluster.complete) {
    std::fprintf(stderr, "dla3d: stopped by %s after %s of %s particles; the files hold them%s\n",
                 signal_name(signal), grown.c_str(), with_commas(static_cast<double>(run->total)).c_str(),
                 resume_hint.c_str());
    return 128 + signal;
  }
  if (!command.checkpoint_path.empty()) std::remove(command.checkpoint_path.c_str());  // whole: nothing to resume
  return 0;
}

}  // namespace dla::cli
