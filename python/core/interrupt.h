#pragma once
// Ctrl-C in every C++ stage a Python call runs (interrupt.cpp).

#include <pybind11/pybind11.h>

#include <functional>

namespace dla::python {

//! Runs `work` on a thread of its own, with the GIL released, while this thread, Python's main
//! one, hears Ctrl-C: KeyboardInterrupt sets the flag of `work`'s StopScope (dla/core/stop.h),
//! which ends the look's measures, tubes, the solid and every writer within milliseconds, and
//! is raised once `work` has ended. Call it holding the GIL; `work` must not touch Python.
void interruptible(const std::function<void()>& work);

}  // namespace dla::python
