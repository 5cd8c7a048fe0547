#pragma once
// dla3d._core.grow_run (grow.cpp).

#include "result.h"

#include <memory>
#include <string>

namespace dla::python {

//! Grows the run `keywords` ask of `model`; `command` is what the record says made it. Releases
//! the GIL while growing; every 0.1 s it takes it back to call progress(done, total), whose
//! False stops growth, and to see Ctrl-C, which stops growth or the links after it and returns
//! what grew (without links).
std::shared_ptr<Result> grow_run(const std::string& model, const py::dict& keywords, const std::string& command,
                                 const py::object& progress);

}  // namespace dla::python
