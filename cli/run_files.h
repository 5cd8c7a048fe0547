#pragma once
// What every growth subcommand shares: the progress bar, the command line echoed in the
// files, the summary's words, and the files themselves (the look, then every writer at once).

#include "command_line.h"

#include "dla/core/cluster.h"
#include "dla/io/run_report.h"
#include "dla/mesh/constraint.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

namespace dla::cli {

using Clock = std::chrono::steady_clock;

//! A non-negative amount rounded to a whole number, thousands grouped.
std::string with_commas(double value);

//! A one-line progress bar on stderr, drawn only on a terminal and only once a run has taken
//! a second.
class ProgressBar {
 public:
  ProgressBar(std::size_t total, bool enabled) : total_(total), enabled_(enabled), start_(Clock::now()) {}

  //! `done` of the total; with a `fill` target (growth until a mesh is filled), the bar shows
  //! the fraction `filled` of it instead, and no ETA (filling slows as it goes).
  void update(std::size_t done, double filled = 0.0, double fill = 0.0) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double fraction = fill > 0.0 ? std::min(filled / fill, 1.0) : total_ ? static_cast<double>(done) / total_ : 1.0;
    const double rate = done / elapsed;
    const double eta = rate > 0 ? (total_ - done) / rate : 0.0;
    constexpr int width = 30;
    const int full = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(full), '=');
    bar.resize(width, ' ');
    if (fill > 0.0)
      std::fprintf(stderr, "\r\033[K%3d%% [%s] filled %.1f%% of %.1f%%  %s particles  %s/s",
                   static_cast<int>(fraction * 100), bar.c_str(), 100.0 * filled, 100.0 * fill,
                   with_commas(done).c_str(), with_commas(rate).c_str());
    else
      std::fprintf(stderr, "\r\033[K%3d%% [%s] %s/%s  %s/s  ETA %d:%02d", static_cast<int>(fraction * 100),
                   bar.c_str(), with_commas(done).c_str(), with_commas(total_).c_str(),
                   with_commas(rate).c_str(), static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
    drawn_ = true;
  }

  void clear() {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    drawn_ = false;
  }

 private:
  std::size_t total_;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_;
  Clock::time_point last_{};
};

//! Fails early, before a long run, if `path` cannot be created (its temporary name is tried).
void check_writable(const std::string& path);

//! The arguments as one line a shell reads back: words with anything but plain characters
//! are single-quoted.
std::string command_line(const std::vector<std::string>& args);

//! The files the options write, in --formats order, for the summary line.
std::vector<std::string> file_names(const FileOptions& files);

const char* signal_name(int signal);

//! With a mesh: a spacing of about a hundredth of its box's longest side, rounded to two digits.
double default_spacing(const Box& box);
//! With a mesh: the axis of its box's longest side, y on a tie, so that standing figures and
//! vessels come out upright.
Axis longest_axis(const Box& box);

//! Makes the look (the distance to `constraint`'s mesh feeds it, when there is one) and writes
//! every file of `files` but the JSON, each on a thread of its own: the same bytes as one by
//! one. With `scene_mesh`, the POV-Ray scene shows it.
void write_files(const Cluster& cluster, const FileOptions& files, const PovOptions& pov, int threads,
                 const MeshConstraint* constraint, const TriangleMesh* scene_mesh);

class ModelRun;

//! Grows `run` under `progress`, keeping what grew when growth fails part way (its reason goes
//! in `error`), and fills `record`: the time taken, the command line `args`, and what stopped
//! growth (the error, else the signal `stop_signal` holds when the structure is incomplete).
Cluster grow_recorded(ModelRun& run, const ProgressFn& progress, const StopFlag& stop,
                      const volatile std::sig_atomic_t& stop_signal, const std::vector<std::string>& args,
                      RunRecord& record, std::string& error);

//! The summary on stderr: the run's line, then the files written and how to render them.
void print_summary(const ModelRun& run, const Cluster& cluster, const FileOptions& files, const RunRecord& record);

}  // namespace dla::cli
