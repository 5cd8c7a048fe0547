// Every model's keywords, from its registration (dla/run/run.h): a keyword a described option,
// spelled as the option's C++ name, with the look's and the files', and the other models'
// options it refuses, each refused with why.

#include "tables.h"

namespace dla::python {

Table<RunOptions> described_table(const Model& model) {
  Table<RunOptions> t;
  add_described(t, output_option_table(), [&model](RunOptions& o) -> OutputOptions& { return model.files(o); });
  add_described(t, model.option_table);
  for (const std::string_view name : model.refuses)
    t[std::string(name)] = [&model, name](RunOptions&, py::handle, Given&) { refuse_for(model.name, name); };
  return t;
}

}  // namespace dla::python
