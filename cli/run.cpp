// Every growth subcommand's run: the library sets it up (dla/run/run.h), this file grows it
// under the progress bar, saves DLA's checkpoints, writes the files and says what happened.

#include "commands.h"
#include "progress.h"
#include "stream.h"

#include "dla/io/checkpoint.h"

#include <unistd.h>

#include <cstdio>
#include <memory>

namespace dla::cli {

namespace {

//! The command without --stream: where a live view read the run is no part of what it grew, so
//! the JSON's command and a checkpoint's leave it out.
std::vector<std::string> without_stream(const std::vector<std::string>& args) {
  std::vector<std::string> kept;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--stream") ++i;
    else if (args[i].rfind("--stream=", 0) != 0) kept.push_back(args[i]);
  }
  return kept;
}

}  // namespace

int run(const CommandLine& line, const std::vector<std::string>& given, const Resumed& resumed, const StopSignals& stop) {
  const std::vector<std::string> args = without_stream(given);
  const OutputOptions& asked = output_of(line.run);
  check_glb_options(asked);
  check_writable(file_names(asked).front());  // before a mesh's set-up and a long run
  const std::string& checkpoint = line.checkpoint_path;
  if (!checkpoint.empty()) check_writable(checkpoint);
  check_stream_path(line.stream_path);
  const std::unique_ptr<Run> prepared = prepare_run(line.run, {}, resumed);
  Run& run = *prepared;
  // A reader that closes the pipe ends the stream with EPIPE, not the run with SIGPIPE.
  if (!line.stream_path.empty()) std::signal(SIGPIPE, SIG_IGN);
  ParticleStream stream(line.stream_path);
  // Only once every option is known good: bad input gets its one line and nothing else.
  if (!line.quiet && !run.mesh_line.empty()) std::fprintf(stderr, "dla3d: %s\n", run.mesh_line.c_str());
  if (!line.quiet && !run.forecast_line.empty())
    std::fprintf(stderr, "dla3d: %s\n", spell_options(run.forecast_line, OptionSpelling::cli).c_str());

  const bool terminal = !line.quiet && isatty(STDERR_FILENO);
  ProgressBar bar(run.total, terminal);
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
    stream.send(so_far, run.done(so_far), run.total);
    if (stop.first.load()) return false;
    if (!checkpoint.empty() && Clock::now() - saved >= std::chrono::duration<double>(line.checkpoint_every)) {
      save(so_far);
      saved = Clock::now();
    }
    return true;
  };
  RunRecord record;
  record.command = command_line(args);
  StageBar links_bar("links", terminal);
  const Cluster cluster = [&] {
    try {
      return grow_recorded(run, progress, &stop.first, record, links_bar.progress());
    } catch (const InvalidInput&) {
      stream.discard();
      throw;
    }
  }();
  bar.clear();
  links_bar.clear();
  stream.send(cluster, run.done(cluster), run.total);
  const bool failed = !record.stopped_by.empty();  // part way, by an error
  // A stop in growth or links: what grew is written, but not the solid or the levels of detail,
  // which take seconds to minutes; a second signal stops the writing too. Otherwise the first
  // stops the writing.
  const bool stopped_early = !record.stopped_in.empty();
  record.stopped_by = failed ? spell_options(record.stopped_by, OptionSpelling::cli)
                      : stopped_early ? signal_name(stop.signal) : "";
  OutputOptions files = run.files;
  const bool solid_left_out = stopped_early && files.formats.solid(), lods_left_out = stopped_early && files.lods > 0;
  if (solid_left_out) files.formats.leave_out_solid();
  if (lods_left_out) files.lods = 0;
  try {
    StageBar solid_bar("the solid", terminal && files.formats.solid());
    write_run(run, cluster, files, record, stopped_early ? &stop.second : &stop.first, solid_bar.progress());
  } catch (const Interrupted&) {
    std::fprintf(stderr, "dla3d: stopped by %s while the files were written; those finished are whole, no other is "
                 "written\n", signal_name(stop.signal));
    if (stopped_early) save(cluster);
    return 128 + stop.signal;
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
    for (const std::string& name : file_names(files)) written += (written.empty() ? "" : " ") + name;
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
  if (stopped_early) {
    const std::string of = run.model == "grow" ? " of " + with_commas(static_cast<double>(run.total)) : "";
    const std::string resume_hint = checkpoint.empty() ? "" : "; go on with: dla3d --resume " + checkpoint;
    const std::string when = record.stopped_in == "links" ? "while the links were made, " : "";
    const std::string without = std::string(run.links.any() ? ", without links" : "") +
                                (solid_left_out || lods_left_out
                                     ? std::string(", and no ") + (solid_left_out ? "solid" : "") +
                                           (solid_left_out && lods_left_out ? " or " : "") +
                                           (lods_left_out ? "levels of detail" : "") + ": they are made for a whole run"
                                     : "");
    std::fprintf(stderr, "dla3d: stopped by %s %safter %s%s %s; the files hold them%s%s\n", signal_name(stop.signal),
                 when.c_str(), grown.c_str(), of.c_str(), run.unit, without.c_str(), resume_hint.c_str());
    return 128 + stop.signal;
  }
  if (!checkpoint.empty()) std::remove(checkpoint.c_str());  // whole: nothing to resume
  return 0;
}

}  // namespace dla::cli
