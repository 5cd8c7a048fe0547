#include "interrupt.h"

#include "dla/core/stop.h"

#include <chrono>
#include <future>
#include <optional>

namespace dla::python {

void interruptible(const std::function<void()>& work) {
  StopFlag stop{false};
  std::future<void> done = std::async(std::launch::async, [&] {
    const detail::StopScope watched(&stop);
    work();
  });
  std::optional<pybind11::error_already_set> raised;
  for (;;) {
    std::future_status status;
    {
      pybind11::gil_scoped_release released;
      status = done.wait_for(std::chrono::milliseconds(20));
    }
    if (status == std::future_status::ready) break;
    if (!raised && PyErr_CheckSignals() != 0) {  // a signal's Python handler raised: KeyboardInterrupt
      raised.emplace();
      stop.store(true);
    }
  }
  if (!raised) return done.get();
  try {
    done.get();
  } catch (const Interrupted&) {  // what Ctrl-C asked for: the KeyboardInterrupt says it
  }
  throw std::move(*raised);
}

}  // namespace dla::python
