// Every growth subcommand's run: the library sets it up (dla/run/run.h), this file grows it
// under the progress bar, saves DLA's checkpoints, writes the files and says what happened.

#include "commands.h"
#include "progress.h"

#include "dla/io/checkpoint.h"

#include <unistd.h>

#include <cstdio>
#include <memory>

namespace dla::cli {

int run(const CommandLine& line, const std::vector<std::string>& args, const Resumed& resumed, const StopFlag& stop,
        const volatile std::sig_atomic_t& stop_signal) {
  const OutputOptions& asked = output_of(line.run);
  check_glb_options(asked);
  check_writable(file_names(asked).front());  // before a mesh's set-up and a long run
  const std::string& checkpoint = line.checkpoint_path;
  if (!checkpoint.empty()) check_writable(checkpoint);
  const std::unique_ptr<Run> prepared = prepare_run(line.run, {}, resumed);
  Run& run = *prepared;
  // Only once every option is known good: bad input gets its one line and nothing else.
  if (!line.quiet && !run.mesh_line.empty()) std::fprintf(stderr, "dla3d: %s\n", run.mesh_line.c_str());

  ProgressBar bar(run.total, !line.quiet && isatty(STDERR_FILENO));
  Clock::time_point saved = Clock::now();
  // A save that fails (a full disk) is reported once and does not stop the run.
  bool save_failed = false;
  const auto save = [&](const Cluster& so_far) {
    if (checkpoint.empty()) return;
    try {
      write_checkpoint({args, run.input_hash, so_far, run.walks() ? *run.walks() : WalkStats{}}, checkpoint);
    } catch (const IOError& e) {
      bar.clear();
      if (!save_failed) std::fprintf(stderr, "dla3d: warning: %s; growth goes on\n", e.what());
      save_failed = true;
    }
  };
  const auto progress = [&](const Cluster& so_far) {
    bar.update(run.done(so_far), run.filled(), run.fill);
    if (stop.load()) return false;
    if (!checkpoint.empty() && Clock::now() - saved >= std::chrono::duration<double>(line.checkpoint_every)) {
      save(so_far);
      saved = Clock::now();
    }
    return true;
  };
  RunRecord record;
  record.command = command_line(args);
  const Cluster cluster = grow_recorded(run, progress, &stop, record);
  bar.clear();
  const int signal = stop_signal;
  const bool failed = !record.stopped_by.empty();  // part way, by an error
  record.stopped_by = failed ? spell_options(record.stopped_by, OptionSpelling::cli)
                      : cluster.complete ? "" : signal_name(signal);
  // The solid's stage and share done, on a terminal, once it has taken a second.
  const bool show_solid = !line.quiet && isatty(STDERR_FILENO) && run.files.formats.solid();
  const Clock::time_point writing = Clock::now();
  Clock::time_point drawn{};
  bool solid_drawn = false;
  const SolidProgress solid_bar = [&](double fraction, std::string_view stage) {
    const Clock::time_point now = Clock::now();
    if (!show_solid || now - writing < std::chrono::seconds(1) || now - drawn < std::chrono::milliseconds(100)) return;
    drawn = now;
    solid_drawn = true;
    const double elapsed = std::chrono::duration<double>(now - writing).count();
    const int left = fraction > 0.0 ? static_cast<int>(elapsed * (1.0 - fraction) / fraction) : 0;
    std::fprintf(stderr, "\r\033[Kdla3d: the solid: %3d%% %.*s  ETA %d:%02d", static_cast<int>(fraction * 100.0),
                 static_cast<int>(stage.size()), stage.data(), left / 60, left % 60);
  };
  try {
    // A first Ctrl-C while the solid builds stops it; after one that stopped growth, a second
    // ends dla3d (the signal's default), and the files already renamed into place stay.
    write_run(run, cluster, record, cluster.complete ? &stop : nullptr, solid_bar);
    if (solid_drawn) std::fprintf(stderr, "\r\033[K");
  } catch (const Interrupted&) {
    if (solid_drawn) std::fprintf(stderr, "\r\033[K");
    std::fprintf(stderr, "dla3d: stopped by %s while the solid was built; the other files are written, no solid file\n",
                 signal_name(stop_signal));
    return 128 + stop_signal;
  } catch (...) {
    if (solid_drawn) std::fprintf(stderr, "\r\033[K");
    throw;
  }
  if (!cluster.complete) save(cluster);  // after the files: they matter more

  const std::string grown = with_commas(static_cast<double>(run.done(cluster)));
  const std::string& output = run.files.output;
  if (failed) {
    std::fprintf(stderr, "dla3d: error: %s; %s.* hold the %s %s grown before it\n", record.stopped_by.substr(7).c_str(),
                 output.c_str(), grown.c_str(), run.unit);
    return 1;
  }
  if (!line.quiet) {
    std::string written;
    for (const std::string& name : file_names(run.files)) written += (written.empty() ? "" : " ") + name;
    const std::string render = run.files.formats.pov ? "; render: povray +W1280 +H960 +A " + output + ".pov" : "";
    std::fprintf(stderr, "dla3d: %s\n", run.summary(cluster, record).c_str());
    if (!cluster.links.empty())
      std::fprintf(stderr, "dla3d: %s links join the branches in %s loops\n",
                   with_commas(static_cast<double>(cluster.links.size())).c_str(),
                   with_commas(static_cast<double>(cycle_count(cluster))).c_str());
    if (!record.lod_triangles.empty()) {
      std::string levels;
      for (std::size_t level = 0; level < record.lod_triangles.size(); ++level)
        levels += (level ? ", " : "") + std::string("lod") + std::to_string(level + 1) + " " +
                  with_commas(static_cast<double>(record.lod_triangles[level]));
      std::fprintf(stderr, "dla3d: levels of detail, in triangles: %s\n", levels.c_str());
    }
    if (record.leaves)
      std::fprintf(stderr, "dla3d: %s leaves in the glb\n", with_commas(static_cast<double>(*record.leaves)).c_str());
    if (record.solid)
      std::fprintf(stderr, "dla3d: %s\n",
                   spell_options(describe(*record.solid, record.printed), OptionSpelling::cli).c_str());
    std::fprintf(stderr, "dla3d: wrote %s%s\n", written.c_str(), render.c_str());
  }
  if (!cluster.complete) {
    const std::string of = run.model == "grow" ? " of " + with_commas(static_cast<double>(run.total)) : "";
    const std::string resume_hint = checkpoint.empty() ? "" : "; go on with: dla3d --resume " + checkpoint;
    std::fprintf(stderr, "dla3d: stopped by %s after %s%s %s; the files hold them%s\n", signal_name(signal),
                 grown.c_str(), of.c_str(), run.unit, resume_hint.c_str());
    return 128 + signal;
  }
  if (!checkpoint.empty()) std::remove(checkpoint.c_str());  // whole: nothing to resume
  return 0;
}

}  // namespace dla::cli
