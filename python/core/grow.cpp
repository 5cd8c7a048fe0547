// Growth from Python: the run grown with the GIL released, with progress, the callback's stop
// and Ctrl-C, which returns what grew.

#include "grow.h"
#include "keywords.h"

#include "dla/core/hash.h"

#include <chrono>

namespace dla::python {

using Clock = std::chrono::steady_clock;

std::shared_ptr<Result> grow_run(const std::string& model, const py::dict& keywords, const std::string& command,
                                 const py::object& progress) {
  Given given;
  const RunOptions options = run_options(model, keywords, given);
  auto result = std::make_shared<Result>();
  const MeshReader read = [&](const std::string& path, std::uint64_t* hash) {
    const auto held = given.meshes.find(path);
    if (held == given.meshes.end()) return read_mesh(path, hash);
    const TriangleMesh& mesh = held->second;
    if (hash) *hash = fnv1a({reinterpret_cast<const char*>(mesh.vertices.data()), mesh.vertices.size() * sizeof(Vec3)});
    return mesh;
  };
  {
    py::gil_scoped_release released;  // a mesh's repair and set-up can take seconds
    result->run = prepare_run(options, read);
  }
  Run& run = *result->run;

  StopFlag stop{false};
  std::string stopped_by;
  std::unique_ptr<py::error_already_set> raised;  // from the callback: raised once growth has stopped
  Clock::time_point next_call = Clock::now();
  // Whether Python is due again: growth and the links take the GIL about every 0.1 s.
  const auto due = [&] {
    const Clock::time_point now = Clock::now();
    if (now < next_call) return false;
    next_call = now + std::chrono::milliseconds(100);
    return true;
  };
  // A Python error while the run goes on, which stops it: Ctrl-C (also while the callback's
  // own Python ran) returns what grew, any other is raised once it has stopped.
  const auto take_error = [&](py::error_already_set error) {
    if (error.matches(PyExc_KeyboardInterrupt)) stopped_by = "SIGINT";
    else raised = std::make_unique<py::error_already_set>(std::move(error));
  };
  const auto call_python = [&](const Cluster& so_far) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      take_error(py::error_already_set());
      return false;
    }
    if (progress.is_none()) return true;
    try {
      const py::object go_on = progress(run.done(so_far), run.total);
      if (!go_on.is_none() && !go_on.cast<bool>()) {
        stopped_by = "callback";
        return false;
      }
    } catch (py::error_already_set& error) {
      take_error(std::move(error));
      return false;
    }
    return true;
  };
  result->record.command = command;
  {
    py::gil_scoped_release released;
    const ProgressFn watch = [&](const Cluster& so_far) {
      if (due() && !call_python(so_far)) stop.store(true);
      return !stop.load();
    };
    // The links are made on this thread, which hears Ctrl-C between their parts.
    const StageProgress links_watch = [&](double, std::string_view) {
      if (!due()) return;
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() == 0) return;
      take_error(py::error_already_set());
      stop.store(true);
    };
    result->cluster = grow_recorded(run, watch, &stop, result->record, links_watch);
  }
  if (raised) throw std::move(*raised);
  RunRecord& record = result->record;
  if (!record.stopped_by.empty()) record.stopped_by = spell_options(record.stopped_by, OptionSpelling::python);
  else if (!result->cluster.complete) record.stopped_by = stopped_by.empty() ? "stopped" : stopped_by;
  return result;
}

}  // namespace dla::python
