#pragma once
//! \file stop.h
//! How the stages after growth (links, the look, tubes and levels of detail, the solid, every
//! writer) are stopped and heard. Growth watches its StopFlag itself (cluster.h); the writers
//! watch the flag of a StopScope, set around them by write_files (output.h), so every file
//! format stops within milliseconds without a flag in each writer's signature.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"

#include <functional>
#include <string>
#include <string_view>

namespace dla {

//! How a long stage goes: the fraction of it done (0-1) and what it does now ("links",
//! "smoothing", ...). Called from the thread that started the stage.
using StageProgress = std::function<void(double fraction, std::string_view stage)>;

//! What watches a stage after growth: `stop` ends it (it throws Interrupted), `progress` hears
//! how it goes.
struct StageWatch {
  const StopFlag* stop = nullptr;
  StageProgress progress;
};

//! Whether `stop` is given and set.
inline bool stopped(const StopFlag* stop) { return stop && stop->load(std::memory_order_relaxed); }

namespace detail {

//! The flag the work on this thread watches, or null: set by StopScope.
inline const StopFlag*& scoped_stop() {
  thread_local const StopFlag* stop = nullptr;
  return stop;
}

//! Makes `stop` the flag this thread's writing watches while the scope lasts. A writer's
//! helper threads watch it only if handed scoped_stop() when they start.
class StopScope {
 public:
  explicit StopScope(const StopFlag* stop) : before_(scoped_stop()) { scoped_stop() = stop; }
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;
  ~StopScope() { scoped_stop() = before_; }

 private:
  const StopFlag* before_;
};

//! Throws Interrupted, saying `what` (then `of`) was stopped, once this thread's scoped flag is
//! set. The message is made only then: the writers ask before every 64 kB.
inline void throw_if_stopped(std::string_view what, std::string_view of = {}) {
  if (stopped(scoped_stop())) throw Interrupted(std::string(what).append(of) + " was stopped");
}

}  // namespace detail
}  // namespace dla
