#pragma once
// A grown structure as Python holds it (dla3d.Result), and the arrays it hands out.

#include "dla/look/look.h"
#include "dla/run/run.h"
#include "interrupt.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <vector>

namespace dla::python {

namespace py = pybind11;

//! A grown structure and the run that grew it (its look and files come from the run's options).
//! The arrays it hands out share its memory and keep it alive.
struct Result {
  Cluster cluster;
  std::shared_ptr<Run> run;
  //! For the JSON: the time growth took, the command, and stopped_by: empty when complete, else
  //! "SIGINT", "callback", "stopped" or "error: ...".
  RunRecord record;

  //! look() for Python, which holds the GIL: computed with it released, Ctrl-C heard.
  const Look& look_for_python() {
    interruptible([this] { look(); });
    return look_;
  }

  //! Computed on first use: growth alone costs no more than the C++ call. Throws Interrupted,
  //! computing nothing, when the StopScope's flag is set (the next call tries again).
  const Look& look() {
    std::call_once(look_once, [&] {
      const std::unique_ptr<SurfaceDistance> surface =
          run->constraint ? std::make_unique<SurfaceDistance>(run->constraint->mesh()) : nullptr;
      look_ = make_look(cluster, run->files.look, {surface.get(), nullptr, run->threads, false});
    });
    return look_;
  }

 private:
  std::once_flag look_once;
  Look look_;
};

//! A read-only array over `data`, kept alive by `owner`.
template <class T>
py::array shared_array(const T* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                       const py::object& owner) {
  py::array array(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

//! A new array of one value per particle.
template <class T, class Value>
py::array_t<T> per_particle(const Result& result, Value&& value) {
  py::array_t<T> array(static_cast<py::ssize_t>(result.cluster.particles.size()));
  T* out = array.mutable_data();
  for (std::size_t i = 0; i < result.cluster.particles.size(); ++i) out[i] = value(i);
  return array;
}

//! Adds dla3d._core.Result, its arrays and measures, to `m`.
void bind_result(py::module_& m);

}  // namespace dla::python
