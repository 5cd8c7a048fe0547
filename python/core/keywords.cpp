// The keyword values' readers, and a model's keywords as its run options: its table
// (tables.cpp), then what only all of them decide (keywords.h).

#include "keywords.h"
#include "tables.h"

#include <pybind11/numpy.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>

namespace dla::python {

std::string shown(py::handle value) { return py::repr(value).cast<std::string>(); }

double number(const char* name, py::handle value) {
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)))
    throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a number");
  return value.cast<double>();
}

long long whole(const char* name, py::handle value) {
  if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value))
    throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a whole number");
  try {
    return value.cast<long long>();
  } catch (const py::cast_error&) {
    throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is too large");
  }
}

std::string text(const char* name, py::handle value) {
  if (!py::isinstance<py::str>(value)) throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a string");
  return value.cast<std::string>();
}

//! A file's path: a string or a pathlib path.
std::string path_text(const char* name, py::handle value) {
  if (!py::isinstance<py::str>(value) && py::hasattr(value, "__fspath__"))
    return text(name, value.attr("__fspath__")());
  return text(name, value);
}

bool flag(const char* name, py::handle value) {
  if (!py::isinstance<py::bool_>(value)) throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not True or False");
  return value.cast<bool>();
}

namespace {

bool is_sequence(py::handle value) {
  return !py::isinstance<py::str>(value) && py::hasattr(value, "__len__") && py::hasattr(value, "__iter__");
}

//! A string, a path, or a number (exactly) as the words the library reads.
std::string scalar_words(const char* name, py::handle value) {
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__")) return path_text(name, value);
  if (py::isinstance<py::bool_>(value)) throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a value");
  if (py::isinstance<py::int_>(value) || (py::hasattr(value, "__index__") && !py::hasattr(value, "__len__")))
    return py::str(value.attr("__index__")()).cast<std::string>();
  if (py::hasattr(value, "__float__") && !py::hasattr(value, "__len__")) return detail::exact_number(value.cast<double>());
  throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a string or a number");
}

//! A value as the CLI would spell it: a string as it is, a number exactly, a sequence of them
//! joined by commas ((0, 1.5, 2): "0,1.5,2"; ("y", 30): "y,30").
std::string words_given(const char* name, py::handle value) {
  if (!is_sequence(value)) return scalar_words(name, value);
  std::string words;
  bool first = true;
  for (py::handle item : value) {
    words += (first ? "" : ",") + scalar_words(name, item);
    first = false;
  }
  return words;
}

//! Several values of a repeated option: one value (a string, a path, a point of numbers, (V, F)
//! arrays for a mesh), or a list of them.
template <class One>
std::vector<std::string> each_given(py::handle value, const One& one) {
  const bool single = !is_sequence(value) || py::len(value) == 0 ||
                      (!is_sequence(value[py::int_(0)]) && !py::isinstance<py::str>(value[py::int_(0)])) ||
                      (py::isinstance<py::tuple>(value) && py::len(value) == 2 && py::hasattr(value[py::int_(0)], "shape"));
  if (single) return {one(value)};
  std::vector<std::string> all;
  for (py::handle item : value) all.push_back(one(item));
  return all;
}

}  // namespace

OptionValue described_value(const OptionDescription& about, py::handle value, Given& given) {
  const std::string name(about.name);
  const char* c_name = name.c_str();
  switch (about.kind) {
    case OptionKind::flag: return flag(c_name, value);
    case OptionKind::integer: return static_cast<std::int64_t>(whole(c_name, value));
    case OptionKind::real: return number(c_name, value);
    case OptionKind::word: return text(c_name, value);
    case OptionKind::file:
      if (about.form == kMeshFileForm) {
        const auto one = [&](py::handle v) {
          return py::hasattr(v, "__fspath__") ? path_text(c_name, v) : mesh(c_name, v, given);
        };
        if (about.repeats) return each_given(value, one);
        return one(value);
      }
      if (about.repeats) return each_given(value, [&](py::handle v) { return path_text(c_name, v); });
      return path_text(c_name, value);
    case OptionKind::vector:
    case OptionKind::points:
    case OptionKind::colour:
    case OptionKind::text:
      if (about.repeats) return each_given(value, [&](py::handle v) { return words_given(c_name, v); });
      return words_given(c_name, value);
  }
  return {};
}

using Vertices = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Faces = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

//! (V, 3) vertices and (F, 3) triangles as a mesh, checked.
TriangleMesh mesh_from_arrays(const std::string& name, const Vertices& vertices, const Faces& faces) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3)
    throw InvalidInput(name + ": the vertices are not an array of shape (V, 3)");
  if (faces.ndim() != 2 || faces.shape(1) != 3) throw InvalidInput(name + ": the faces are not an array of shape (F, 3)");
  TriangleMesh mesh;
  const auto v = vertices.unchecked<2>();
  const auto f = faces.unchecked<2>();
  mesh.vertices.reserve(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    const Vec3 p(v(i, 0), v(i, 1), v(i, 2));
    if (!p.allFinite()) throw InvalidInput(name + ": vertex " + std::to_string(i) + " is not finite");
    mesh.vertices.push_back(p);
  }
  mesh.triangles.reserve(static_cast<std::size_t>(f.shape(0)));
  for (py::ssize_t i = 0; i < f.shape(0); ++i) {
    std::array<std::uint32_t, 3> t;
    for (int k = 0; k < 3; ++k) {
      if (f(i, k) < 0 || f(i, k) >= v.shape(0))
        throw InvalidInput(name + ": face " + std::to_string(i) + " names vertex " + std::to_string(f(i, k)) +
                           ", not one of its " + std::to_string(v.shape(0)));
      t[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(f(i, k));
    }
    mesh.triangles.push_back(t);
  }
  if (mesh.triangles.empty()) throw InvalidInput(name + ": the mesh has no faces");
  return mesh;
}

//! A file's path, or (V, F) arrays held under a name that stands for them.
std::string mesh(const char* name, py::handle value, Given& given) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value))
    throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a file's path or (vertices, faces) arrays");
  if (py::len(value) != 2)
    throw InvalidInput(std::string("`") + name + "` is not a file's path or (vertices, faces) arrays");
  const std::string key = "<" + std::string(name) + " arrays" +
                          (given.meshes.empty() ? "" : " " + std::to_string(given.meshes.size() + 1)) + ">";
  given.meshes[key] = mesh_from_arrays(key, value[py::int_(0)].cast<Vertices>(), value[py::int_(1)].cast<Faces>());
  return key;
}

const Table<SolidOptions>& solid_keywords() {
  static const Table<SolidOptions> t = [] {
    Table<SolidOptions> table;
    add_described(table, solid_option_table());
    return table;
  }();
  return t;
}

namespace {

//! The run options of `model` that `keywords` ask for, from its defaults, with its table of
//! keywords, made once.
RunOptions set_all(const Model& model, const py::dict& keywords, Given& given) {
  static std::map<const Model*, Table<RunOptions>> tables;  // the registry's models stay put
  auto table = tables.find(&model);
  if (table == tables.end()) table = tables.emplace(&model, described_table(model)).first;
  RunOptions run = model.options();
  const std::string name(model.name);
  for (const auto& [key, value] : keywords) {
    const std::string keyword = key.template cast<std::string>();
    const auto setter = table->second.find(keyword);
    if (setter == table->second.end())
      throw InvalidInput(keyword + " is not an option of " + name + "(): see docs/python.md, or `dla3d " +
                         (&model == &models().front() ? "" : name + " ") + "--help`");
    if (!value.is_none()) setter->second(run, value, given);
  }
  return run;
}

}  // namespace

RunOptions run_options(const std::string& model, const py::dict& keywords, Given& given) {
  const Model* found = find_model(model);
  if (!found) {
    std::string names;
    for (const Model& m : models()) names += (names.empty() ? "" : ", ") + std::string(m.name);
    throw InvalidInput("'" + model + "' is not one of " + names);
  }
  RunOptions run = set_all(*found, keywords, given);
  validate(run);
  return run;
}

}  // namespace dla::python
