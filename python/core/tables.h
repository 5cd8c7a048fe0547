#pragma once
// One keyword table a model (tables.cpp), which keywords.cpp's run_options() reads.

#include "keywords.h"

namespace dla::python {

Table<DlaRunOptions> dla_table();
Table<ColonizeRunOptions> colonize_table();
Table<DropRunOptions> drop_table();
Table<BreakdownRunOptions> breakdown_table();
//! The keywords of a model described whole (run.h's Model::option_table), and the look's.
Table<RunOptions> described_table(const Model& model);

}  // namespace dla::python
