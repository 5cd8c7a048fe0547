// Every model's keywords: one table a model (tables.h), a keyword a field of its run options,
// spelled as the field's C++ name; what several models share is added by the functions first.

#include "tables.h"

#include <algorithm>

namespace dla::python {

namespace {

//! The look and output options every model has (the files themselves are Result.write()'s), in
//! the OutputOptions that `files` gives of the run's options.
template <class Options, class Files>
void add_look(Table<Options>& t, Files files) {
  add_described(t, output_option_table(), files);
}

template <class Options>
void add_look(Table<Options>& t) {
  add_look(t, [](Options& o) -> OutputOptions& { return o.files; });
}

//! --fill and --shell, for the models they mean nothing to: refused with why.
template <class O>
void add_refused(Table<O>& t, const char* model) {
  for (const char* option : {"fill", "shell"})
    t[option] = [model, option](O&, py::handle, Given&) { refuse_for(model, option); };
}

}  // namespace

Table<DlaRunOptions> dla_table() {
  using O = DlaRunOptions;
  Table<O> t;
  add_look(t);
  add_described(t, dla_run_option_table());
  return t;
}

Table<ColonizeRunOptions> colonize_table() {
  using O = ColonizeRunOptions;
  Table<O> t;
  add_look(t);
  add_described(t, colonize_option_table());
  add_refused(t, "colonize");
  return t;
}

Table<DropRunOptions> drop_table() {
  using O = DropRunOptions;
  Table<O> t;
  add_look(t);
  add_described(t, drop_run_option_table());
  add_refused(t, "drop");
  return t;
}

Table<BreakdownRunOptions> breakdown_table() {
  using O = BreakdownRunOptions;
  Table<O> t;
  add_look(t);
  add_described(t, breakdown_run_option_table());
  t["fill"] = [](O&, py::handle, Given&) { refuse_for("breakdown", "fill"); };
  return t;
}

Table<RunOptions> described_table(const Model& model) {
  Table<RunOptions> t;
  add_look(t, [&model](RunOptions& o) -> OutputOptions& { return model.files(o); });
  add_described(t, model.option_table);
  return t;
}

}  // namespace dla::python
