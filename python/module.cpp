// dla3d._core: dla3d's growth runs (dla/run/run.h), grown from Python. Keyword arguments set
// the library's run options (dla/run/models.h) through one table a model, spelled as the
// options' C++ names; the library checks them, and its messages name the options as Python
// spells them. This file grows the run with the GIL released and hands the structure to numpy
// without copying it. See docs/python.md.

#include "dla/core/analysis.h"
#include "dla/core/hash.h"
#include "dla/look/look.h"
#include "dla/look/solid.h"
#include "dla/look/tubes.h"
#include "dla/mesh/surface_distance.h"
#include "dla/run/run.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

namespace py = pybind11;

namespace dla::python {

namespace {

using Clock = std::chrono::steady_clock;
using detail::with_commas;

//! A grown structure and the run that grew it (its look and files come from the run's options).
//! The arrays it hands out share its memory and keep it alive.
struct Result {
  Cluster cluster;
  std::shared_ptr<Run> run;
  //! For the JSON: the time growth took, the command, and stopped_by: empty when complete, else
  //! "SIGINT", "callback", "stopped" or "error: ...".
  RunRecord record;

  //! Computed on first use: growth alone costs no more than the C++ call.
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

// ---------------------------------------------------------------------------------------------
// Keyword arguments as the run's options: a value of the right kind, or one line naming it.

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

//! A whole number for an int option: one beyond an int is refused here, not wrapped into range.
int whole_int(const char* name, py::handle value) {
  const long long n = whole(name, value);
  if (n < std::numeric_limits<int>::min() || n > std::numeric_limits<int>::max())
    throw InvalidInput(std::string("`") + name + "` " + std::to_string(n) +
                       (n > 0 ? " is too large" : " is too small"));
  return static_cast<int>(n);
}

std::size_t count(const char* name, py::handle value) {
  const long long n = whole(name, value);
  if (n < 0) throw InvalidInput(std::string("`") + name + "` " + std::to_string(n) + " is negative");
  return static_cast<std::size_t>(n);
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

//! `count` numbers: a tuple, a list or an array of them.
std::vector<double> numbers(const char* name, py::handle value, std::size_t count) {
  const std::string wanted = std::to_string(count) + " numbers";
  if (py::isinstance<py::str>(value) || !py::hasattr(value, "__len__") || py::len(value) != count)
    throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not " + wanted);
  std::vector<double> values;
  for (py::handle item : value) values.push_back(number(name, item));
  return values;
}

Vec3 vec3(const char* name, py::handle value) {
  const std::vector<double> v = numbers(name, value, 3);
  return {v[0], v[1], v[2]};
}

//! One point (x, y, z), or a list or (N, 3) array of them.
std::vector<Vec3> points(const char* name, py::handle value) {
  // A sequence of numbers is one point, however many it holds.
  const bool one = py::hasattr(value, "__len__") && !py::isinstance<py::str>(value) && py::len(value) > 0 &&
                   !py::hasattr(value[py::int_(0)], "__len__");
  std::vector<Vec3> all;
  if (one) return {vec3(name, value)};
  if (py::isinstance<py::str>(value) || !py::hasattr(value, "__iter__"))
    throw InvalidInput(std::string("`") + name + "` " + shown(value) + " is not a point (x, y, z) or a list of them");
  for (py::handle item : value) all.push_back(vec3(name, item));
  return all;
}

Box box(const char* name, py::handle value) {
  const std::vector<double> b = numbers(name, value, 6);
  return Box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
}

//! A word of an enum, parsed as the library parses it.
template <class Parse>
auto word(const char* name, py::handle value, Parse&& parse) {
  return parse(text(name, value));
}

//! `links`: D spacings, (D, K), or a word as dla3d writes it: "D,K" or "lattice".
LinkOptions links(const char* name, py::handle value) {
  if (py::isinstance<py::str>(value)) return parse_links(text(name, value));
  const bool pair = py::hasattr(value, "__len__");
  const std::vector<double> dk = pair ? numbers(name, value, 2) : std::vector<double>{number(name, value), 1.0};
  if (!(dk[0] > 0.0)) throw InvalidInput("`links` " + shown(value) + ": the distance is not above 0");
  if (!(dk[1] >= 1 && dk[1] <= static_cast<double>(kMaxLinksEach) && dk[1] == std::floor(dk[1])))
    throw InvalidInput("`links` " + shown(value) + ": K " + detail::format_number(dk[1]) + " is not a whole number in 1-64");
  LinkOptions o;
  o.distance = dk[0];
  o.most = static_cast<std::size_t>(dk[1]);
  validate(o);
  return o;
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

//! What a run's keywords set besides its options: the meshes handed over as arrays, under the
//! names that stand for them, and what only all the keywords together decide.
struct Given {
  std::map<std::string, TriangleMesh> meshes;
  bool seeds_all = false;         //!< seeds="all"
  bool attractors = false;        //!< attractors=N, a sample of attractors_from's
  std::optional<int> eden_dimensions;
  bool lattice = false;
};

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

template <class Options>
using Setter = std::function<void(Options& options, py::handle value, Given& given)>;
template <class Options>
using Table = std::map<std::string, Setter<Options>>;

//! The look and output options every model has (the files themselves are Result.write()'s).
template <class Options>
void add_look(Table<Options>& t) {
  const auto files = [](Options& o) -> OutputOptions& { return o.files; };
  t["ply_format"] = [=](Options& o, py::handle v, Given&) { files(o).ply_encoding = word("ply_format", v, parse_ply_encoding); };
  t["png_scale"] = [=](Options& o, py::handle v, Given&) { files(o).png.pixels_per_spacing = number("png_scale", v); };
  t["png_bands"] = [=](Options& o, py::handle v, Given&) { files(o).png.bands = whole_int("png_bands", v); };
  t["radius"] = [=](Options& o, py::handle v, Given&) { files(o).radius = word("radius", v, parse_radius_model); };
  t["base_radius"] = [=](Options& o, py::handle v, Given&) { files(o).base_radius = number("base_radius", v); };
  t["tip_radius"] = [=](Options& o, py::handle v, Given&) { files(o).tip_radius = number("tip_radius", v); };
  t["pipe_exponent"] = [=](Options& o, py::handle v, Given&) { files(o).look.radius.pipe_exponent = number("pipe_exponent", v); };
  t["color_by"] = [=](Options& o, py::handle v, Given&) { files(o).look.color_by = word("color_by", v, parse_color_by); };
  t["look"] = [=](Options& o, py::handle v, Given&) { files(o).pov.style = word("look", v, parse_pov_style); };
  t["tube_sides"] = [=](Options& o, py::handle v, Given&) { files(o).look.tubes.sides = whole_int("tube_sides", v); };
  t["tube_tolerance"] = [=](Options& o, py::handle v, Given&) { files(o).look.tubes.tolerance = number("tube_tolerance", v); };
  t["uv_scale"] = [=](Options& o, py::handle v, Given&) { files(o).look.tubes.uv_scale = number("uv_scale", v); };
  t["lod"] = [=](Options& o, py::handle v, Given&) { files(o).lods = whole_int("lod", v); };
  t["leaf"] = [=](Options& o, py::handle v, Given&) { files(o).leaf = path_text("leaf", v); };
  t["tube_min_branch"] = [=](Options& o, py::handle v, Given&) {
    files(o).look.tubes.min_branch = whole_int("tube_min_branch", v);
  };
  t["instances"] = [=](Options& o, py::handle v, Given&) { files(o).instances.set = word("instances", v, parse_instance_set); };
  t["tips_within"] = [=](Options& o, py::handle v, Given&) { files(o).instances.within = number("tips_within", v); };
  t["tips_exclude_paint"] = [=](Options& o, py::handle v, Given&) {
    files(o).instances.exclude_paint = parse_paint(text("tips_exclude_paint", v), "tips_exclude_paint");
  };
  t["tips_every"] = [=](Options& o, py::handle v, Given&) { files(o).instances.every = whole_int("tips_every", v); };
  t["up"] = [=](Options& o, py::handle v, Given&) { files(o).up = word("up", v, parse_axis); };
  t["solid_shape"] = [=](Options& o, py::handle v, Given&) { files(o).solid.shape = word("solid_shape", v, parse_solid_shape); };
  t["solid_voxel"] = [=](Options& o, py::handle v, Given&) { files(o).solid.voxel = number("solid_voxel", v); };
  t["solid_smooth"] = [=](Options& o, py::handle v, Given&) { files(o).solid.smooth = number("solid_smooth", v); };
  t["solid_adaptivity"] = [=](Options& o, py::handle v, Given&) { files(o).solid.adaptivity = number("solid_adaptivity", v); };
  t["print_size"] = [=](Options& o, py::handle v, Given&) { files(o).solid.print_size = number("print_size", v); };
  t["min_wall"] = [=](Options& o, py::handle v, Given&) { files(o).solid.min_wall = number("min_wall", v); };
  t["solid_join"] = [=](Options& o, py::handle v, Given&) { files(o).solid.join_seeds = flag("solid_join", v); };
  t["solid_memory"] = [=](Options& o, py::handle v, Given&) { files(o).solid.memory = number("solid_memory", v); };
}

//! Where seeds (colonize: roots) go on the mesh, the same for DLA, drop and colonize.
template <class O>
void add_mesh_seeds(Table<O>& t) {
  t["seeds"] = [](O& o, py::handle v, Given& g) {
    if (py::isinstance<py::str>(v) && v.cast<std::string>() == "all") g.seeds_all = true;
    else if ((o.seeds.count = count("seeds", v)) == 0) throw InvalidInput("`seeds` 0: there must be a seed");
  };
  t["seed_surface"] = [](O& o, py::handle v, Given&) { o.seeds.surface = flag("seed_surface", v); };
  t["seed_paint"] = [](O& o, py::handle v, Given&) { o.seeds.paint = parse_paint(text("seed_paint", v)); };
  t["seed_mesh"] = [](O& o, py::handle v, Given& g) {
    const bool one = py::isinstance<py::str>(v) || (py::isinstance<py::tuple>(v) && py::len(v) == 2 &&
                                                    py::hasattr(v[py::int_(0)], "shape"));
    if (one) o.seeds.meshes.push_back(mesh("seed_mesh", v, g));
    else
      for (py::handle item : v) o.seeds.meshes.push_back(mesh("seed_mesh", item, g));
  };
}

//! --fill and --shell, for the models they mean nothing to: refused with why.
template <class O>
void add_refused(Table<O>& t, const char* model) {
  for (const char* option : {"fill", "shell"})
    t[option] = [model, option](O&, py::handle, Given&) { refuse_for(model, option); };
}

Table<DlaRunOptions> dla_table() {
  using O = DlaRunOptions;
  Table<O> t;
  add_look(t);
  t["particles"] = [](O& o, py::handle v, Given&) { o.particles = count("particles", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.spacing = number("spacing", v); };
  t["stickiness"] = [](O& o, py::handle v, Given&) { o.growth.stickiness = number("stickiness", v); };
  t["dimensions"] = [](O& o, py::handle v, Given&) { o.growth.dimensions = whole_int("dimensions", v); };
  t["seed_at"] = [](O& o, py::handle v, Given&) { o.seed_at = points("seed_at", v); };
  t["rng_seed"] = [](O& o, py::handle v, Given&) { o.growth.rng_seed = count("rng_seed", v); };
  t["min_step"] = [](O& o, py::handle v, Given&) { o.growth.min_step = number("min_step", v); };
  t["links"] = [](O& o, py::handle v, Given&) { o.links = links("links", v); };
  t["index"] = [](O& o, py::handle v, Given&) { o.growth.index = word("index", v, parse_index_kind); };
  t["threads"] = [](O& o, py::handle v, Given&) { o.growth.threads = whole_int("threads", v); };
  t["stl"] = [](O& o, py::handle v, Given& g) { o.stl = mesh("stl", v, g); };
  t["text"] = [](O& o, py::handle v, Given&) {
    const std::string font = o.text ? o.text->font : kDefaultFont;
    o.text = TextOptions{text("text", v), font};
  };
  t["font"] = [](O& o, py::handle v, Given&) {
    if (!o.text) o.text = TextOptions{};
    o.text->font = text("font", v);
  };
  t["side"] = [](O& o, py::handle v, Given&) { o.constraint.side = word("side", v, parse_side); };
  t["shell"] = [](O& o, py::handle v, Given&) { o.constraint.shell = number("shell", v); };
  t["constraint"] = [](O& o, py::handle v, Given&) { o.constraint.mode = word("constraint", v, parse_constraint_mode); };
  add_mesh_seeds(t);
  t["scene_mesh"] = [](O& o, py::handle v, Given&) { o.scene_mesh = flag("scene_mesh", v); };
  t["fill"] = [](O& o, py::handle v, Given&) { o.growth.fill = number("fill", v); };
  t["fill_distance"] = [](O& o, py::handle v, Given&) { o.growth.fill_distance = number("fill_distance", v); };
  t["spawn"] = [](O& o, py::handle v, Given&) { o.spawn = word("spawn", v, parse_spawn_mode); };
  t["spawn_axis"] = [](O& o, py::handle v, Given&) { o.growth.spawn_axis = word("spawn_axis", v, parse_axis); };
  t["disk_radius"] = [](O& o, py::handle v, Given&) { o.growth.disk_radius = number("disk_radius", v); };
  t["box"] = [](O& o, py::handle v, Given&) { o.growth.spawn_box = box("box", v); };
  t["drift"] = [](O& o, py::handle v, Given&) { o.growth.drift = vec3("drift", v); };
  t["rotate"] = [](O& o, py::handle v, Given&) {
    if (py::isinstance<py::str>(v) || !py::hasattr(v, "__len__") || py::len(v) != 2)
      throw InvalidInput("`rotate` " + shown(v) + " is not (axis, degrees), as ('y', 30)");
    o.growth.rotate_axis = word("rotate", v[py::int_(0)], parse_axis);
    o.growth.rotate_degrees = number("rotate", v[py::int_(1)]);
  };
  t["n"] = t["particles"];
  t["mesh"] = t["stl"];
  return t;
}

Table<ColonizeRunOptions> colonize_table() {
  using O = ColonizeRunOptions;
  Table<O> t;
  add_look(t);
  t["max_nodes"] = [](O& o, py::handle v, Given&) { o.colonization.max_nodes = count("max_nodes", v); };
  t["max_iterations"] = [](O& o, py::handle v, Given&) { o.colonization.max_iterations = count("max_iterations", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.colonization.spacing = number("spacing", v); };
  t["kill_distance"] = [](O& o, py::handle v, Given&) { o.colonization.kill_distance = number("kill_distance", v); };
  t["influence"] = [](O& o, py::handle v, Given&) { o.colonization.influence = number("influence", v); };
  t["venation"] = [](O& o, py::handle v, Given&) { o.colonization.venation = word("venation", v, parse_venation); };
  t["noise"] = [](O& o, py::handle v, Given&) {
    const std::vector<double> n = numbers("noise", v, 2);
    o.colonization.noise_amplitude = n[0];
    o.colonization.noise_scale = n[1];
  };
  t["tropism"] = [](O& o, py::handle v, Given&) { o.colonization.tropism = vec3("tropism", v); };
  t["dimensions"] = [](O& o, py::handle v, Given&) { o.colonization.dimensions = whole_int("dimensions", v); };
  t["rng_seed"] = [](O& o, py::handle v, Given&) { o.colonization.rng_seed = count("rng_seed", v); };
  t["attractors"] = [](O& o, py::handle v, Given& g) {
    o.attractors.count = count("attractors", v);
    g.attractors = true;
  };
  t["attractors_in"] = [](O& o, py::handle v, Given&) { o.attractors.region = word("attractors_in", v, parse_attractor_region); };
  t["attractors_from"] = [](O& o, py::handle v, Given&) { o.attractors_from = text("attractors_from", v); };
  t["attractor_center"] = [](O& o, py::handle v, Given&) { o.attractors.center = vec3("attractor_center", v); };
  t["attractor_radius"] = [](O& o, py::handle v, Given&) { o.attractors.radius = number("attractor_radius", v); };
  t["attractor_box"] = [](O& o, py::handle v, Given&) {
    const Box b = box("attractor_box", v);
    o.attractors.box_min = b.min;
    o.attractors.box_max = b.max;
  };
  t["attractor_falloff"] = [](O& o, py::handle v, Given&) { o.attractors.falloff = number("attractor_falloff", v); };
  t["root_at"] = [](O& o, py::handle v, Given&) { o.root_at = points("root_at", v); };
  t["roots"] = [](O& o, py::handle v, Given&) {
    if ((o.root_count = count("roots", v)) == 0) throw InvalidInput("`roots` 0: there must be a root");
  };
  t["roots_in"] = [](O& o, py::handle v, Given&) { o.roots_in = word("roots_in", v, parse_root_region); };
  t["roots_scale"] = [](O& o, py::handle v, Given&) { o.roots_scale = number("roots_scale", v); };
  t["stl"] = [](O& o, py::handle v, Given& g) { o.stl = mesh("stl", v, g); };
  t["collide"] = [](O& o, py::handle v, Given& g) { o.collide = mesh("collide", v, g); };
  t["collision"] = [](O& o, py::handle v, Given&) { o.collision = word("collision", v, parse_collision_mode); };
  add_mesh_seeds(t);
  add_refused(t, "colonize");
  t["n"] = t["max_nodes"];
  return t;
}

Table<EdenRunOptions> eden_table() {
  using O = EdenRunOptions;
  Table<O> t;
  add_look(t);
  t["links"] = [](O& o, py::handle v, Given&) { o.links = links("links", v); };
  t["sites"] = [](O& o, py::handle v, Given&) {
    if ((o.eden.sites = count("sites", v)) == 0) throw InvalidInput("`sites` 0 is not at least 1");
  };
  t["dimensions"] = [](O&, py::handle v, Given& g) { g.eden_dimensions = whole_int("dimensions", v); };
  t["lattice"] = [](O& o, py::handle v, Given& g) {
    o.eden.lattice = word("lattice", v, parse_lattice);
    g.lattice = true;
  };
  t["mode"] = [](O& o, py::handle v, Given&) { o.eden.mode = word("mode", v, parse_eden_mode); };
  t["mask"] = [](O& o, py::handle v, Given&) {
    const std::string mask = text("mask", v);
    if (mask.size() == 1 && mask.find_first_of("ABCD") == 0) o.eden.mask = parse_eden_mask(mask);
    else o.mask_file = mask;
  };
  t["mask_threshold"] = [](O& o, py::handle v, Given&) { o.eden.mask_threshold = whole_int("mask_threshold", v); };
  t["seed_radius"] = [](O& o, py::handle v, Given&) { o.eden.seed_radius = number("seed_radius", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.eden.spacing = number("spacing", v); };
  t["rng_seed"] = [](O& o, py::handle v, Given&) { o.eden.rng_seed = count("rng_seed", v); };
  t["n"] = t["sites"];
  return t;
}

//! What drop and ballistic share: the count, the plane, the scale, the seeds.
template <class O, class Model>
void add_seeded(Table<O>& t, Model O::*model) {
  t["particles"] = [=](O& o, py::handle v, Given&) { (o.*model).particles = count("particles", v); };
  t["dimensions"] = [=](O& o, py::handle v, Given&) { (o.*model).dimensions = whole_int("dimensions", v); };
  t["rng_seed"] = [=](O& o, py::handle v, Given&) { (o.*model).rng_seed = count("rng_seed", v); };
  t["n"] = t["particles"];
}

Table<DropRunOptions> drop_table() {
  using O = DropRunOptions;
  Table<O> t;
  add_look(t);
  add_seeded(t, &O::drop);
  t["links"] = [](O& o, py::handle v, Given&) { o.links = links("links", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.spacing = number("spacing", v); };
  t["seed_at"] = [](O& o, py::handle v, Given&) { o.seed_at = points("seed_at", v); };
  t["stickiness"] = [](O& o, py::handle v, Given&) { o.drop.stickiness = number("stickiness", v); };
  t["zone"] = [](O& o, py::handle v, Given&) { o.drop.zone = word("zone", v, parse_drop_zone); };
  t["zone_radius"] = [](O& o, py::handle v, Given&) { o.drop.zone_radius = number("zone_radius", v); };
  t["zone_margin"] = [](O& o, py::handle v, Given&) { o.drop.zone_margin = number("zone_margin", v); };
  t["zone_box"] = [](O& o, py::handle v, Given&) { o.drop.zone_box = box("zone_box", v); };
  t["drop"] = [](O& o, py::handle v, Given&) { o.drop.bias = parse_drop_bias(text("drop", v)); };
  t["stl"] = [](O& o, py::handle v, Given& g) { o.stl = mesh("stl", v, g); };
  t["side"] = [](O& o, py::handle v, Given&) { o.constraint.side = word("side", v, parse_side); };
  t["constraint"] = [](O& o, py::handle v, Given&) { o.constraint.mode = word("constraint", v, parse_constraint_mode); };
  t["scene_mesh"] = [](O& o, py::handle v, Given&) { o.scene_mesh = flag("scene_mesh", v); };
  add_mesh_seeds(t);
  add_refused(t, "drop");
  t["mesh"] = t["stl"];
  return t;
}

Table<BallisticRunOptions> ballistic_table() {
  using O = BallisticRunOptions;
  Table<O> t;
  add_look(t);
  add_seeded(t, &O::ballistic);
  t["links"] = [](O& o, py::handle v, Given&) { o.links = links("links", v); };
  t["spacing"] = [](O& o, py::handle v, Given&) { o.ballistic.spacing = number("spacing", v); };
  t["seed_at"] = [](O& o, py::handle v, Given&) { o.ballistic.seeds = points("seed_at", v); };
  t["direction"] = [](O& o, py::handle v, Given&) {
    o.ballistic.direction = vec3("direction", v);
    if (o.ballistic.direction.squaredNorm() == 0.0) throw InvalidInput("`direction` (0, 0, 0) has no direction");
  };
  return t;
}

//! What only all the keywords together decide.
void settle(RunOptions& run, const Given& given) {
  const auto all = [&](MeshSeeds& seeds) {
    if (given.seeds_all) seeds.surface = !seeds.paint && seeds.meshes.empty();
  };
  if (auto* o = std::get_if<DlaRunOptions>(&run)) {
    all(o->seeds);
  } else if (auto* o = std::get_if<DropRunOptions>(&run)) {
    all(o->seeds);
  } else if (auto* o = std::get_if<ColonizeRunOptions>(&run)) {
    all(o->seeds);
    o->sample_attractors = given.attractors && !o->attractors_from.empty();
  } else if (auto* o = std::get_if<EdenRunOptions>(&run)) {
    const int dimensions = given.eden_dimensions.value_or(2);
    if (dimensions != 2 && dimensions != 3) throw InvalidInput("`dimensions` " + std::to_string(dimensions) + " is not 2 or 3");
    if (!given.lattice) o->eden.lattice = dimensions == 3 ? Lattice::cubic6 : Lattice::square4;
    else if (given.eden_dimensions && dimensions_of(o->eden.lattice) != dimensions)
      throw InvalidInput("`lattice` " + std::string(to_string(o->eden.lattice)) + " is not a lattice in " +
                         std::to_string(dimensions) + "D");
  }
}

//! The run options of `model` that `keywords` ask for, from its defaults, with `table`.
template <class Options>
RunOptions set_all(const Table<Options>& table, const Model& model, const py::dict& keywords, Given& given) {
  RunOptions run = model.options();
  Options& options = std::get<Options>(run);
  const std::string name(model.name);
  for (const auto& [key, value] : keywords) {
    const std::string keyword = key.template cast<std::string>();
    const auto setter = table.find(keyword);
    if (setter == table.end())
      throw InvalidInput(keyword + " is not an option of " + name + "(): see docs/python.md, or `dla3d " +
                         (name == "grow" ? "" : name + " ") + "--help`");
    if (!value.is_none()) setter->second(options, value, given);
  }
  return run;
}

template <class Options, Table<Options> (*make_table)()>
RunOptions keywords_of(const Model& model, const py::dict& keywords, Given& given) {
  static const Table<Options> table = make_table();
  return set_all(table, model, keywords, given);
}

using Keywords = RunOptions (*)(const Model& model, const py::dict& keywords, Given& given);

//! Each model's keywords, by its name in the library's registry (dla/run/run.h).
Keywords keywords_of(const Model& model) {
  static const std::pair<std::string_view, Keywords> tables[] = {
      {"grow", keywords_of<DlaRunOptions, dla_table>},
      {"colonize", keywords_of<ColonizeRunOptions, colonize_table>},
      {"eden", keywords_of<EdenRunOptions, eden_table>},
      {"drop", keywords_of<DropRunOptions, drop_table>},
      {"ballistic", keywords_of<BallisticRunOptions, ballistic_table>},
  };
  for (const auto& [name, set] : tables)
    if (name == model.name) return set;
  throw std::logic_error("the model " + std::string(model.name) + " has no keywords in Python");
}

RunOptions run_options(const std::string& model, const py::dict& keywords, Given& given) {
  const Model* found = find_model(model);
  if (!found) {
    std::string names;
    for (const Model& m : models()) names += (names.empty() ? "" : ", ") + std::string(m.name);
    throw InvalidInput("'" + model + "' is not one of " + names);
  }
  RunOptions run = keywords_of(*found)(*found, keywords, given);
  settle(run, given);
  validate(run);
  return run;
}

//! Grows the run `keywords` ask of `model`; `command` is what the record says made it. Releases
//! the GIL while growing; every 0.1 s it takes it back to call progress(done, total), whose
//! False stops growth, and to see Ctrl-C, which stops growth and returns what grew.
std::shared_ptr<Result> grow_run(const std::string& model, const py::dict& keywords, const std::string& command,
                                 const py::object& progress) {
  Given given;
  const RunOptions options = run_options(model, keywords, given);
  auto result = std::make_shared<Result>();
  const MeshReader read = [&](const std::string& path, std::uint64_t* hash) {
    const auto held = given.meshes.find(path);
    if (held == given.meshes.end()) return read_mesh(path, hash);
    const TriangleMesh& mesh = held->second;
    if (hash) *hash = fnv1a({reinterpret_cast<const char*>(mesh.vertices.data()), mesh.vertices.size() * sizeof(Vec3)});
    return mesh;
  };
  {
    py::gil_scoped_release released;  // a mesh's repair and set-up can take seconds
    result->run = prepare_run(options, read);
  }
  Run& run = *result->run;

  StopFlag stop{false};
  std::string stopped_by;
  std::unique_ptr<py::error_already_set> raised;  // from the callback: raised once growth has stopped
  Clock::time_point next_call = Clock::now();
  const auto call_python = [&](const Cluster& so_far) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      auto error = std::make_unique<py::error_already_set>();
      if (error->matches(PyExc_KeyboardInterrupt)) stopped_by = "SIGINT";
      else raised = std::move(error);
      return false;
    }
    if (progress.is_none()) return true;
    try {
      const py::object go_on = progress(run.done(so_far), run.total);
      if (!go_on.is_none() && !go_on.cast<bool>()) {
        stopped_by = "callback";
        return false;
      }
    } catch (py::error_already_set& error) {
      // Ctrl-C while the callback's own Python ran is Ctrl-C all the same: what grew comes back.
      if (error.matches(PyExc_KeyboardInterrupt)) stopped_by = "SIGINT";
      else raised = std::make_unique<py::error_already_set>(std::move(error));
      return false;
    }
    return true;
  };
  result->record.command = command;
  {
    py::gil_scoped_release released;
    const ProgressFn watch = [&](const Cluster& so_far) {
      const Clock::time_point now = Clock::now();
      if (now < next_call) return true;
      next_call = now + std::chrono::milliseconds(100);
      if (!call_python(so_far)) stop.store(true);
      return !stop.load();
    };
    result->cluster = grow_recorded(run, watch, &stop, result->record);
  }
  if (raised) throw std::move(*raised);
  RunRecord& record = result->record;
  if (!record.stopped_by.empty()) record.stopped_by = spell_options(record.stopped_by, OptionSpelling::python);
  else if (!result->cluster.complete) record.stopped_by = stopped_by.empty() ? "stopped" : stopped_by;
  return result;
}

//! Every tube of the structure as one mesh: float32 vertices, normals, texture coordinates and
//! tangents, uint32 triangles, and the particle each vertex belongs to.
py::tuple tubes(Result& result, std::optional<int> sides, std::optional<double> tolerance,
                std::optional<int> min_branch, std::optional<double> uv_scale) {
  TubeOptions options = result.run->files.look.tubes;  // the run's, where not given
  if (sides) options.sides = *sides;
  if (tolerance) options.tolerance = *tolerance;
  if (min_branch) options.min_branch = *min_branch;
  if (uv_scale) options.uv_scale = *uv_scale;
  validate(options);
  const Look& look = result.look();
  std::vector<float> positions, normals, uvs, tangents;
  std::vector<std::uint32_t> triangles;
  std::vector<std::int32_t> particles;
  {
    py::gil_scoped_release released;
    for_each_tube(result.cluster, look.attributes, look.radii(result.cluster), options, [&](const TubePiece& piece) {
      const auto base = static_cast<std::uint32_t>(particles.size());
      for (std::size_t k = 0; k < piece.positions.size(); ++k) {
        positions.insert(positions.end(), piece.positions[k].data(), piece.positions[k].data() + 3);
        normals.insert(normals.end(), piece.normals[k].data(), piece.normals[k].data() + 3);
        uvs.insert(uvs.end(), piece.uvs[k].data(), piece.uvs[k].data() + 2);
        tangents.insert(tangents.end(), piece.tangents[k].data(), piece.tangents[k].data() + 4);
      }
      particles.insert(particles.end(), piece.particles.begin(), piece.particles.end());
      for (const auto& t : piece.triangles) triangles.insert(triangles.end(), {base + t[0], base + t[1], base + t[2]});
    });
  }
  const auto array = [](auto& values, py::ssize_t columns) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    const auto rows = static_cast<py::ssize_t>(values.size()) / columns;
    py::array_t<T> out(columns == 1 ? std::vector<py::ssize_t>{rows} : std::vector<py::ssize_t>{rows, columns});
    if (!values.empty()) std::memcpy(out.mutable_data(), values.data(), values.size() * sizeof(T));
    return out;
  };
  return py::make_tuple(array(positions, 3), array(normals, 3), array(triangles, 3), array(particles, 1),
                        array(uvs, 2), array(tangents, 4));
}

//! The instancing points of the run's options, as PREFIX_tips.ply and the glb's leaves have
//! them: float64 positions and unit directions, scales, and the particles.
py::tuple instances(Result& result) {
  const Run& run = *result.run;
  const OutputOptions& files = run.files;
  std::vector<Instance> points;
  {
    py::gil_scoped_release released;
    const Look look = make_look(result.cluster, files.look,
                                {run.constraint ? &run.constraint->surface() : nullptr, nullptr, run.threads,
                                 picks_every_tip(files.instances),
                                 files.instances.exclude_paint ? &*files.instances.exclude_paint : nullptr,
                                 run.constraint ? &run.constraint->mesh() : nullptr});
    points = instancing_points(result.cluster, look.attributes, files.instances);
  }
  const auto rows = static_cast<py::ssize_t>(points.size());
  py::array_t<double> positions({rows, py::ssize_t{3}}), directions({rows, py::ssize_t{3}}), scales(rows);
  py::array_t<std::int32_t> particles(rows);
  for (py::ssize_t k = 0; k < rows; ++k) {
    const Instance& point = points[static_cast<std::size_t>(k)];
    for (py::ssize_t a = 0; a < 3; ++a) {
      positions.mutable_at(k, a) = point.position[a];
      directions.mutable_at(k, a) = point.direction[a];
    }
    scales.mutable_at(k) = point.scale;
    particles.mutable_at(k) = point.particle;
  }
  return py::make_tuple(positions, directions, scales, particles);
}

//! The strands (strands.h) as one array of particle ids and the offsets where each starts (one
//! more offset at the end): a Blender curve's poly splines, a Houdini primitive each.
py::tuple strands(Result& result) {
  const Look& look = result.look();
  std::vector<std::int32_t> ids;
  std::vector<std::int64_t> starts{0};
  for_each_strand(
      result.cluster, [&](std::size_t i) { return look.attributes.continues_strand(i); },
      [&](const Strand& strand) {
        ids.insert(ids.end(), strand.begin(), strand.end());
        starts.push_back(static_cast<std::int64_t>(ids.size()));
      });
  return py::make_tuple(py::array_t<std::int32_t>(static_cast<py::ssize_t>(ids.size()), ids.data()),
                        py::array_t<std::int64_t>(static_cast<py::ssize_t>(starts.size()), starts.data()));
}

//! Writes the files `formats` names (the formats' words) as PREFIX.EXT, with the look the run's
//! options ask for; the JSON records how the run was made.
//! The structure's solid (solid.h) with the run's solid options but those given: float32
//! vertices, uint32 triangles, each vertex's nearest particle, and the measures.
py::tuple solid(Result& result, const py::dict& given) {
  SolidOptions options = result.run->files.solid;
  for (const auto& [key, value] : given) {
    const std::string name = key.cast<std::string>();
    if (name == "solid_shape") options.shape = word("solid_shape", value, parse_solid_shape);
    else if (name == "solid_voxel") options.voxel = number("solid_voxel", value);
    else if (name == "solid_smooth") options.smooth = number("solid_smooth", value);
    else if (name == "solid_adaptivity") options.adaptivity = number("solid_adaptivity", value);
    else if (name == "print_size") options.print_size = number("print_size", value);
    else if (name == "min_wall") options.min_wall = number("min_wall", value);
    else if (name == "solid_join") options.join_seeds = flag("solid_join", value);
    else if (name == "solid_memory") options.memory = number("solid_memory", value);
    else throw InvalidInput(name + " is not an option of solid()");
  }
  const Look& look = result.look();
  Solid built;
  std::vector<std::int32_t> nearest;
  {
    py::gil_scoped_release released;
    built = build_solid(result.cluster, look.radii(result.cluster), options);
    nearest = nearest_particles(result.cluster, built, built.mesh.vertices);
  }
  py::array_t<float> vertices({static_cast<py::ssize_t>(built.mesh.vertices.size()), py::ssize_t{3}});
  py::array_t<std::uint32_t> faces({static_cast<py::ssize_t>(built.mesh.triangles.size()), py::ssize_t{3}});
  py::array_t<std::int32_t> particle(static_cast<py::ssize_t>(nearest.size()));
  if (!built.mesh.vertices.empty()) std::memcpy(vertices.mutable_data(), built.mesh.vertices.data(), built.mesh.vertices.size() * 12);
  if (!built.mesh.triangles.empty()) std::memcpy(faces.mutable_data(), built.mesh.triangles.data(), built.mesh.triangles.size() * 12);
  if (!nearest.empty()) std::memcpy(particle.mutable_data(), nearest.data(), nearest.size() * 4);
  const SolidMeasures& m = built.measures;
  py::dict measures;
  measures["units"] = options.print_size > 0 ? "mm" : "scene";
  measures["volume"] = m.volume;
  measures["area"] = m.area;
  measures["shells"] = m.shells;
  measures["thinnest_wall"] = m.thinnest_wall;
  measures["thickened"] = m.thickened;
  measures["voxel"] = m.voxel;
  measures["scale"] = m.scale;
  measures["origin"] = py::make_tuple(built.origin.x(), built.origin.y(), built.origin.z());
  return py::make_tuple(vertices, faces, particle, measures);
}

void write(Result& result, const std::string& prefix, const std::vector<std::string>& formats) {
  std::string words;
  for (const std::string& format : formats) words += (words.empty() ? "" : ",") + format;
  OutputOptions files = result.run->files;
  files.output = prefix;
  files.formats = parse_formats(words);
  validate(files, result.cluster.dimensions, result.run->constraint != nullptr);
  check_glb_options(files);
  check_writable(file_names(files).front());
  RunRecord record = result.record;  // the growth's time, command and end; the writing's own time
  py::gil_scoped_release released;
  write_run(*result.run, result.cluster, files, record);
}

}  // namespace

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

  py::class_<Result, std::shared_ptr<Result>>(m, "Result", "A grown structure: the arrays share its memory")
      .def_property_readonly("positions", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        const auto n = static_cast<py::ssize_t>(r.cluster.particles.size());
        const double* data = n ? r.cluster.particles[0].position.data() : nullptr;
        return shared_array(data, {n, 3}, {sizeof(Particle), sizeof(double)}, self);
      }, "(N, 3) float64: particle centres, seeds first, then in attach order")
      .def_property_readonly("parent", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        const auto n = static_cast<py::ssize_t>(r.cluster.particles.size());
        return shared_array(n ? &r.cluster.particles[0].parent : nullptr, {n}, {sizeof(Particle)}, self);
      }, "(N,) int32: the particle each attached to; -1 for a seed")
      .def_property_readonly("seed", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        const auto n = static_cast<py::ssize_t>(r.cluster.particles.size());
        return shared_array(n ? &r.cluster.particles[0].seed : nullptr, {n}, {sizeof(Particle)}, self);
      }, "(N,) int32: which seed's tree each particle is in")
      .def_property_readonly("links", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        const auto n = static_cast<py::ssize_t>(r.cluster.links.size());
        return shared_array(n ? &r.cluster.links[0].earlier : nullptr, {n, 2}, {sizeof(Link), sizeof(std::int32_t)}, self);
      }, "(L, 2) int32: links beside the tree (links=, venation='closed'), earlier particle first, in order of the later")
      .def_property_readonly("cycles", [](const Result& r) { return cycle_count(r.cluster); },
                             "independent loops the links close")
      .def_property_readonly("depth", [](py::object self) {
        Result& r = self.cast<Result&>();
        const std::vector<std::int32_t>& depth = r.look().attributes.depth;
        return shared_array(depth.data(), {static_cast<py::ssize_t>(depth.size())}, {sizeof(std::int32_t)}, self);
      }, "(N,) int32: particles on the path to the seed")
      .def_property_readonly("descendants", [](py::object self) {
        Result& r = self.cast<Result&>();
        const std::vector<std::int32_t>& d = r.look().attributes.descendants;
        return shared_array(d.data(), {static_cast<py::ssize_t>(d.size())}, {sizeof(std::int32_t)}, self);
      }, "(N,) int32: particles in the subtree, itself not counted")
      .def_property_readonly("age", [](Result& r) {
        const Attributes& a = r.look().attributes;
        return per_particle<float>(r, [&](std::size_t i) { return a.age(i); });
      }, "(N,) float32: attach order, 0 (seeds and the first) to 1 (the last)")
      .def_property_readonly("order", [](Result& r) {
        const Attributes& a = r.look().attributes;
        return per_particle<std::uint8_t>(r, [&](std::size_t i) { return static_cast<std::uint8_t>(a.strahler(i)); });
      }, "(N,) uint8: Strahler order, tips 1")
      .def_property_readonly("tip", [](Result& r) {
        const Attributes& a = r.look().attributes;
        return per_particle<bool>(r, [&](std::size_t i) { return a.tip(i); });
      }, "(N,) bool: no child")
      .def_property_readonly("radius", [](Result& r) {
        const Look& look = r.look();
        return per_particle<float>(r, [&](std::size_t i) { return static_cast<float>(look.radius(r.cluster, i)); });
      }, "(N,) float32: the branch radius of the look, in scene units")
      .def_property_readonly("seed_count", [](const Result& r) { return r.cluster.seed_count; })
      .def_property_readonly("spacing", [](const Result& r) { return r.cluster.spacing; })
      .def_property_readonly("dimensions", [](const Result& r) { return r.cluster.dimensions; })
      .def_property_readonly("complete", [](const Result& r) { return r.cluster.complete; },
                             "False when growth was stopped (Ctrl-C, the callback, an error) before its count")
      .def_property_readonly("stopped_by", [](const Result& r) { return r.record.stopped_by; },
                             "'' when complete; else 'SIGINT', 'callback' or 'error: ...'")
      .def_property_readonly("command", [](const Result& r) { return r.record.command; },
                             "the dla3d command line that grows the same structure")
      .def_property_readonly("up", [](const Result& r) { return std::string(to_string(r.run->files.pov.up)); },
                             "the axis that is up: x, y or z (a mesh's longest side's by default)")
      .def("__len__", [](const Result& r) { return r.cluster.particles.size(); })
      .def("__repr__", [](const Result& r) {
        return "<dla3d.Result: " + with_commas(static_cast<double>(r.cluster.particles.size())) + " particles, " +
               std::to_string(r.cluster.seed_count) + (r.cluster.seed_count == 1 ? " seed" : " seeds") +
               (r.record.stopped_by.empty() ? "" : ", stopped by " + r.record.stopped_by) + ">";
      })
      .def("_tubes", &tubes, py::arg("sides"), py::arg("tolerance"), py::arg("min_branch"), py::arg("uv_scale"),
           "(vertices, normals, faces, particle, uv, tangent): the tube mesh of the look (dla3d.Result.tubes)")
      .def("_instances", &instances, "(positions, directions, scale, particle): the instancing points")
      .def("_solid", &solid, py::arg("options"),
           "(vertices, faces, particle, measures): the watertight solid (dla3d.Result.solid)")
      .def("strands", &strands, "(ids, starts): particle ids of every strand, strand k at ids[starts[k]:starts[k+1]]")
      .def("fractal_dimension", [](const Result& r) {
        const FractalFit gyration = fractal_dimension_by_gyration(r.cluster);
        const FractalFit mass = fractal_dimension_by_mass_radius(r.cluster);
        const auto value = [](const FractalFit& fit) { return fit.samples >= 2 ? fit.dimension : NAN; };
        return py::make_tuple(value(gyration), value(mass));
      }, "(by gyration, by mass-radius): the fractal dimension by both estimators of `dla3d analyze` "
         "(NaN where too small to fit)")
      .def("gyration", [](const Result& r, std::size_t n_min, std::size_t samples) {
        const std::vector<GyrationSample> history = gyration_history(r.cluster, n_min, samples);
        py::array_t<std::int64_t> n(static_cast<py::ssize_t>(history.size()));
        py::array_t<double> radius(static_cast<py::ssize_t>(history.size()));
        for (std::size_t k = 0; k < history.size(); ++k) {
          n.mutable_at(k) = static_cast<std::int64_t>(history[k].n);
          radius.mutable_at(k) = history[k].radius;
        }
        return py::make_tuple(n, radius);
      }, py::arg("n_min") = 100, py::arg("samples") = 40,
         "(n, Rg): the radius of gyration of the first n particles, n spaced evenly in log n from n_min to all")
      .def("write", &write, py::arg("prefix"), py::arg("formats"),
           "writes PREFIX.EXT for each of `formats` (the CLI's --formats words)");

  m.def(
      "models",
      [] {
        py::list names;
        for (const Model& model : models()) {
          keywords_of(model);  // every model has its keywords, or the import fails
          names.append(py::make_tuple(std::string(model.name), std::string(model.summary)));
        }
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
