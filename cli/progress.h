#pragma once
// The progress bar dla3d draws on a terminal, and the words its messages share.

#include "dla/run/run.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dla::cli {

using Clock = std::chrono::steady_clock;
using detail::with_commas;

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

//! A stage after growth (the links, the solid) on a terminal, once it has taken a second: its
//! name, its share done, what it does now and an ETA. Called as a StageProgress; the stage's
//! time counts from the first call.
class StageBar {
 public:
  StageBar(std::string name, bool enabled) : name_(std::move(name)), enabled_(enabled) {}
  StageBar(const StageBar&) = delete;
  StageBar& operator=(const StageBar&) = delete;
  ~StageBar() { clear(); }

  void operator()(double fraction, std::string_view doing) {
    const Clock::time_point now = Clock::now();
    if (!started_) {
      start_ = now;
      started_ = true;
    }
    if (!enabled_ || now - start_ < std::chrono::seconds(1) || now - drawn_at_ < std::chrono::milliseconds(100)) return;
    drawn_at_ = now;
    drawn_ = true;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const int left = fraction > 0.0 ? static_cast<int>(elapsed * (1.0 - fraction) / fraction) : 0;
    const std::string what = doing == name_ ? "" : " " + std::string(doing);
    std::fprintf(stderr, "\r\033[Kdla3d: %s: %3d%%%s  ETA %d:%02d", name_.c_str(), static_cast<int>(fraction * 100.0),
                 what.c_str(), left / 60, left % 60);
  }
  //! This stage's progress, for a library call.
  StageProgress progress() {
    return [this](double fraction, std::string_view doing) { (*this)(fraction, doing); };
  }
  void clear() {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    drawn_ = false;
  }

 private:
  std::string name_;
  bool enabled_;
  bool drawn_ = false, started_ = false;
  Clock::time_point start_{};
  Clock::time_point drawn_at_{};
};

inline const char* signal_name(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}

//! The arguments as one line a shell reads back: words with anything but plain characters
//! are single-quoted.
inline std::string command_line(const std::vector<std::string>& args) {
  std::string line = "dla3d";
  for (const std::string& arg : args) {
    const bool plain = !arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789_-+=.,:/@%") == std::string::npos;
    if (plain) {
      line += " " + arg;
      continue;
    }
    line += " '";
    for (const char c : arg) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += "'";
  }
  return line;
}

}  // namespace dla::cli
