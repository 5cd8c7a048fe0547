// `dla3d frames PREFIX.csv --count K`: the structure a CSV holds as it grew, K files of each
// format, for tools that cannot reveal growth by the age attribute of one file.

#include "commands.h"
#include "run_files.h"

#include "dla/io/csv_reader.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace dla::cli {

namespace {

//! PREFIX_0007: frame numbers from 1, zero-padded to 4 digits or as many as K has.
std::string frame_prefix(const std::string& output, std::size_t frame, std::size_t count) {
  const std::string number = std::to_string(frame);
  const std::size_t width = std::max<std::size_t>(4, std::to_string(count).size());
  return output + "_" + std::string(width - number.size(), '0') + number;
}

}  // namespace

int frames(const FramesCommand& command, const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal) {
  const Cluster whole = read_csv(command.csv_path);
  if ((command.formats.svg || command.formats.png) && whole.dimensions != 2)
    throw InvalidInput(command.csv_path + " holds 3D growth: --formats svg and png draw 2D growth");
  FileOptions files = command;
  files.output = frame_prefix(command.output, 1, command.count);
  check_writable(file_names(files).front());

  const std::size_t others = attached(whole);
  ProgressBar bar(command.count, !command.quiet && isatty(STDERR_FILENO));
  for (std::size_t k = 1; k <= command.count; ++k) {
    if (stop.load()) {
      bar.clear();
      std::fprintf(stderr, "dla3d: stopped by %s after %zu of %zu frames; they are whole\n", signal_name(stop_signal),
                   k - 1, command.count);
      return 128 + stop_signal;
    }
    // Frame k: the seeds and the first k/K of the rest, rounded to the nearest particle.
    const auto shown = static_cast<std::size_t>(std::llround(static_cast<double>(others) * static_cast<double>(k) /
                                                             static_cast<double>(command.count)));
    Cluster frame;
    frame.particles.assign(whole.particles.begin(),
                           whole.particles.begin() + static_cast<std::ptrdiff_t>(whole.seed_count + shown));
    frame.seed_count = whole.seed_count;
    frame.center = whole.center;
    frame.spacing = whole.spacing;
    frame.dimensions = whole.dimensions;
    files.output = frame_prefix(command.output, k, command.count);
    PovOptions pov = files.pov;
    pov.comment = "frame " + std::to_string(k) + " of " + std::to_string(command.count) + " of " + command.csv_path;
    write_files(frame, files, pov, 1, nullptr, nullptr);
    bar.update(k);
  }
  bar.clear();
  if (!command.quiet) {
    std::fprintf(stderr, "dla3d: wrote %zu frames of growth, %s.* to %s.*; one file with the age attribute "
                         "reveals growth in Blender and Houdini too (docs/animation.md)\n",
                 command.count, frame_prefix(command.output, 1, command.count).c_str(), files.output.c_str());
  }
  return 0;
}

}  // namespace dla::cli
