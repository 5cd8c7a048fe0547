// `dla3d frames PREFIX.csv --count K`: the structure a CSV holds as it grew, K files of each
// format, for tools that cannot reveal growth by the age attribute of one file.

#include "commands.h"
#include "options.h"
#include "progress.h"

#include "dla/io/csv_reader.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

namespace dla::cli {

namespace {

//! PREFIX_0007: frame numbers from 1, zero-padded to 4 digits or as many as K has.
std::string frame_prefix(const std::string& output, std::size_t frame, std::size_t count) {
  const std::string number = std::to_string(frame);
  const std::size_t width = std::max<std::size_t>(4, std::to_string(count).size());
  return output + "_" + std::string(width - number.size(), '0') + number;
}

}  // namespace

Subcommand add_frames_command(CLI::App& app) {
  struct Words {
    long long count = 30;
    bool quiet = false;
    std::unique_ptr<DescribedOptions<LinkOptions>> links;
    std::unique_ptr<OutputWords> files;
  };
  auto w = std::make_shared<Words>();
  auto frames = std::make_shared<FramesCommand>();
  CLI::App* command = app.add_subcommand(
      "frames", "write the structure a CSV holds as it grew, K files of each format (PREFIX_0001.glb ...; PREFIX "
                "by default the CSV's, without .csv): growth for tools without an age attribute (docs/animation.md)");
  command->get_formatter()->column_width(34);
  command->add_option("csv", frames->csv_path, "a CSV that dla3d wrote")->required();
  command->add_option("--count", w->count, "frames, 1-100000: frame k of K holds the seeds and k/K of the "
                                           "other particles, in attach order")->capture_default_str();
  w->links = add_links_option(*command);
  frames->files.output.clear();  // the CSV's prefix unless given
  w->files = std::make_unique<OutputWords>(*command, frames->files, w->quiet, "glb");
  return {command, [w, frames](CommandLine& line) {
            FramesCommand& fr = *frames;
            line.kind = CommandLine::Kind::frames;
            if (w->count < 1 || w->count > 100000)
              throw InvalidInput("--count " + std::to_string(w->count) + " is not a number of frames in 1-100000");
            fr.count = static_cast<std::size_t>(w->count);
            fr.links = links_of(*w->links);
            if (fr.links.lattice)
              throw InvalidInput("`links` lattice: a CSV does not say its lattice; dla3d eden makes lattice links");
            w->files->finish(fr.files);
            if (fr.files.output.empty()) {
              fr.files.output = fr.csv_path;
              if (fr.files.output.size() > 4 && fr.files.output.compare(fr.files.output.size() - 4, 4, ".csv") == 0)
                fr.files.output.resize(fr.files.output.size() - 4);
            }
            if (fr.files.formats.json) throw InvalidInput("`formats` json: frames have no run to report; leave json out");
            // svg and png need 2D growth, which only the CSV tells: frames() checks them.
            validate(fr.files, 2, false);
            line.quiet = w->quiet;
            line.frames = fr;
          }};
}

int frames(const FramesCommand& command, bool quiet, const StopSignals& stop) {
  Cluster whole = read_csv(command.csv_path);
  const bool terminal = !quiet && isatty(STDERR_FILENO);
  const auto stopped_by = [&](std::size_t whole_frames) {
    std::fprintf(stderr, "dla3d: stopped by %s after %zu of %zu frames; they are whole\n", signal_name(stop.signal),
                 whole_frames, command.count);
    return 128 + stop.signal;
  };
  if (command.links.any()) {
    StageBar links_bar("links", terminal);
    try {
      whole.links = neighbour_links(whole, command.links, static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u)),
                                    {}, kLoopSteps, {&stop.first, links_bar.progress()});
    } catch (const Interrupted&) {
      links_bar.clear();
      return stopped_by(0);
    }
  }
  if ((command.files.formats.svg || command.files.formats.png) && whole.dimensions != 2)
    throw InvalidInput(command.csv_path + " holds 3D growth: `formats` svg and png draw 2D growth");
  OutputOptions files = command.files;
  files.output = frame_prefix(command.files.output, 1, command.count);
  check_writable(file_names(files).front());
  // The last frame's solid is the largest: refused, before any frame is written, if it would
  // not fit.
  if (files.formats.solid())
    plan_solid(whole, make_look(whole, files.look, {nullptr, nullptr, 1, false}).radii, files.solid);

  const std::size_t others = attached(whole);
  ProgressBar bar(command.count, terminal);
  for (std::size_t k = 1; k <= command.count; ++k) {
    if (stop.first.load()) {
      bar.clear();
      return stopped_by(k - 1);
    }
    // Frame k: the seeds and the first k/K of the rest, rounded to the nearest particle.
    const auto shown = static_cast<std::size_t>(std::llround(static_cast<double>(others) * static_cast<double>(k) /
                                                             static_cast<double>(command.count)));
    const Cluster frame = first_particles(whole, whole.seed_count + shown);
    files.output = frame_prefix(command.files.output, k, command.count);
    try {
      write_files(frame, files, {1, nullptr, nullptr,
                                 "frame " + std::to_string(k) + " of " + std::to_string(command.count) + " of " + command.csv_path,
                                 &stop.first, {}});
    } catch (const Interrupted&) {
      for (const std::string& name : file_names(files)) std::remove(name.c_str());  // the frame's finished files
      bar.clear();
      return stopped_by(k - 1);
    }
    bar.update(k);
  }
  bar.clear();
  if (!quiet) {
    std::fprintf(stderr, "dla3d: wrote %zu frames of growth, %s.* to %s.*; one file with the age attribute "
                         "reveals growth in Blender and Houdini too (docs/animation.md)\n",
                 command.count, frame_prefix(command.files.output, 1, command.count).c_str(), files.output.c_str());
  }
  return 0;
}

}  // namespace dla::cli
