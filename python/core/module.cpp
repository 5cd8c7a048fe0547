// dla3d._core: dla3d's growth runs (dla/run/run.h), grown from Python. Keyword arguments set
// the library's run options (dla/run/models.h) through one table a model, spelled as the
// options' C++ names; the library checks them, and its messages name the options as Python
// spells them. Growth runs with the GIL released (grow.cpp), and the structure goes to numpy
// without copying it (result.cpp). See docs/python.md.

#include "grow.h"
#include "keywords.h"
#include "result.h"

#include <pybind11/stl.h>

namespace dla::python {

PYBIND11_MODULE(_core, m) {
  m.doc() = "dla3d's growth models, grown from Python (see the dla3d package)";
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, spell_options(e.what(), OptionSpelling::python).c_str());
    } catch (const IOError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });

  bind_result(m);

  m.def(
      "models",
      [] {
        py::list names;
        for (const Model& model : models())
          names.append(py::make_tuple(std::string(model.name), std::string(model.summary)));
        return names;
      },
      "(name, summary) of every growth model, in the order dla3d --help lists them");
  m.def("grow_run", &grow_run, py::arg("model"), py::arg("keywords"), py::arg("command"), py::arg("progress"),
        "grows the run the keywords ask of the model (grow, colonize, eden, drop, ballistic)");
  m.def(
      "check", [](const std::string& model, const py::dict& keywords) {
        Given given;
        run_options(model, keywords, given);
      },
      py::arg("model"), py::arg("keywords"), "raises ValueError for keywords the model refuses");
}

}  // namespace dla::python
