#pragma once
// One keyword table a model (tables.cpp), which keywords.cpp's run_options() reads.

#include "keywords.h"

namespace dla::python {

//! The keywords of a registered model (run.h's Model): its described options, the look's and
//! the files', and the refusals of other models' options it does not take.
Table<RunOptions> described_table(const Model& model);

}  // namespace dla::python
