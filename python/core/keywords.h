#pragma once
// Keyword arguments as the run's options (dla/run/models.h): a value of the right kind, or one
// line naming it. One table a model (tables.cpp), spelled as the options' C++ names.

#include "dla/core/option_description.h"
#include "dla/run/run.h"

#include <pybind11/pybind11.h>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dla::python {

namespace py = pybind11;

//! Each reads a keyword's value as the option `name` needs it, or throws InvalidInput with one
//! line naming it.
std::string shown(py::handle value);
double number(const char* name, py::handle value);
long long whole(const char* name, py::handle value);
std::string text(const char* name, py::handle value);
//! A file's path: a string or a pathlib path.
std::string path_text(const char* name, py::handle value);
bool flag(const char* name, py::handle value);

//! A word of a mode, parsed as the library parses it.
template <class Mode>
Mode word(const char* name, py::handle value) {
  return parse_word<Mode>(text(name, value));
}

//! What a run's keywords set besides its options: the meshes handed over as arrays, under the
//! names that stand for them.
struct Given {
  std::map<std::string, TriangleMesh> meshes;
};

//! A file's path, or (V, F) arrays held under a name that stands for them.
std::string mesh(const char* name, py::handle value, Given& given);

template <class Options>
using Setter = std::function<void(Options& options, py::handle value, Given& given)>;
template <class Options>
using Table = std::map<std::string, Setter<Options>>;

//! A keyword's value as the option `about` describes it (option_description.h): True or False,
//! a whole number, a number or a word; for the text forms, the words the CLI would take (a
//! string, or numbers and words in a tuple or list, joined by commas), a list of them for one
//! that repeats, and for a mesh (V, F) arrays too, held in `given`; or InvalidInput naming it.
OptionValue described_value(const OptionDescription& about, py::handle value, Given& given);

//! The keywords of a table of described options, setting the `Described` that `part` gives of
//! the run's options; an option's one-letter name and alias (`n`, `mesh`) are keywords too.
template <class Options, class Described, class Part>
void add_described(Table<Options>& t, const OptionTable<Described>& table, Part part) {
  for (const DescribedOption<Described>& option : table) {
    const Setter<Options> set = [&option, part](Options& o, py::handle v, Given& given) {
      option.set(part(o), described_value(option.about, v, given));
    };
    for (const std::string_view name : {option.about.name, option.about.short_name, option.about.alias})
      if (!name.empty()) t[std::string(name)] = set;
  }
}

//! The keywords of a table that describes the options the keywords set, whole.
template <class Options>
void add_described(Table<Options>& t, const OptionTable<Options>& table) {
  add_described(t, table, [](Options& o) -> Options& { return o; });
}

//! The solid's keywords (solid.h): in every model's table, and Result.solid()'s.
const Table<SolidOptions>& solid_keywords();

//! The run options that `keywords` ask of the model named `model`, checked; `given` receives
//! the meshes handed over as arrays.
RunOptions run_options(const std::string& model, const py::dict& keywords, Given& given);

}  // namespace dla::python
