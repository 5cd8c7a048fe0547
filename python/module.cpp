// dla3d._core: the growth runs of dla3d's command line (cli/model_run.h), grown from Python.
// dla3d/__init__.py turns keyword arguments into the command line's words, so options are
// spelled and checked as on the CLI; this file grows the run with the GIL released and hands the
// structure to numpy without copying it. See docs/python.md.

#include "../cli/command_line.h"
#include "../cli/model_run.h"
#include "../cli/run_files.h"

#include "dla/core/analysis.h"
#include "dla/core/hash.h"
#include "dla/look/look.h"
#include "dla/look/tubes.h"
#include "dla/mesh/surface_distance.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>

namespace py = pybind11;

namespace dla::python {

namespace {

using cli::CommandLine;
using cli::ModelRun;
using Clock = std::chrono::steady_clock;

//! A grown structure and the run that grew it (its look and files come from the run's options).
//! The arrays it hands out share its memory and keep it alive.
struct Result {
  Cluster cluster;
  std::shared_ptr<ModelRun> run;
  std::vector<std::string> args;  //!< the command line's words, without "dla3d"
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

//! Refuses words that ask for something but a `model` run (--help, --resume).
void check_kind(const CommandLine& line, const std::string& model) {
  const char* kinds[] = {"grow", "colonize", "eden", "drop", "ballistic"};
  const auto kind = static_cast<std::size_t>(line.kind);
  if (kind >= std::size(kinds) || model != kinds[kind]) throw InvalidInput("these options ask for no " + model + " run");
}

//! Grows the run that `args` (the command line's words) set up, with `meshes` standing in for
//! the files of those names. Releases the GIL while growing; every 0.1 s it takes it back to
//! call progress(done, total), whose False stops growth, and to see Ctrl-C, which stops growth
//! and returns what grew.
std::shared_ptr<Result> grow_run(const std::vector<std::string>& args, const std::string& model,
                                 const std::map<std::string, TriangleMesh>& meshes, const py::object& progress) {
  const CommandLine line = cli::parse_command_line(args);
  check_kind(line, model);
  auto result = std::make_shared<Result>();
  result->args = args;
  const cli::MeshReader read = [&](const std::string& path, std::uint64_t* hash) {
    const auto given = meshes.find(path);
    if (given == meshes.end()) return read_mesh(path, hash);
    const TriangleMesh& mesh = given->second;
    if (hash) *hash = fnv1a({reinterpret_cast<const char*>(mesh.vertices.data()), mesh.vertices.size() * sizeof(Vec3)});
    return mesh;
  };
  {
    py::gil_scoped_release released;  // a mesh's repair and set-up can take seconds
    result->run = cli::prepare_run(line, nullptr, read);
  }
  ModelRun& run = *result->run;

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
      raised = std::make_unique<py::error_already_set>(std::move(error));
      return false;
    }
    return true;
  };
  {
    py::gil_scoped_release released;
    const ProgressFn watch = [&](const Cluster& so_far) {
      const Clock::time_point now = Clock::now();
      if (now < next_call) return true;
      next_call = now + std::chrono::milliseconds(100);
      if (!call_python(so_far)) stop.store(true);
      return !stop.load();
    };
    std::string error;  // why growth failed part way, if it did
    const volatile std::sig_atomic_t no_signal = 0;  // what stopped growth is told below
    result->cluster = cli::grow_recorded(run, watch, stop, no_signal, args, result->record, error);
    if (!error.empty()) stopped_by = "error: " + error;
  }
  if (raised) throw std::move(*raised);
  result->record.stopped_by = result->cluster.complete ? "" : stopped_by.empty() ? "stopped" : stopped_by;
  return result;
}

//! Every tube of the structure as one mesh: float32 vertices and normals, uint32 triangles, and
//! the particle each vertex belongs to.
py::tuple tubes(Result& result, int sides, double tolerance, int min_branch) {
  TubeOptions options = result.run->files.look.tubes;
  options.sides = sides;
  options.tolerance = tolerance;
  options.min_branch = min_branch;
  validate(options);
  const Look& look = result.look();
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> triangles;
  std::vector<std::int32_t> particles;
  {
    py::gil_scoped_release released;
    for_each_tube(result.cluster, look.attributes, look.radii(result.cluster), options, [&](const TubePiece& piece) {
      const auto base = static_cast<std::uint32_t>(particles.size());
      for (std::size_t k = 0; k < piece.positions.size(); ++k) {
        positions.insert(positions.end(), piece.positions[k].data(), piece.positions[k].data() + 3);
        normals.insert(normals.end(), piece.normals[k].data(), piece.normals[k].data() + 3);
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
  return py::make_tuple(array(positions, 3), array(normals, 3), array(triangles, 3), array(particles, 1));
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

//! Writes the files `formats` names (the CLI's --formats words) as PREFIX.EXT, with the look
//! the run's options ask for; the JSON records the command line.
void write(Result& result, const std::string& prefix, const std::vector<std::string>& formats) {
  std::vector<std::string> args = result.args;
  std::string words;
  for (const std::string& format : formats) words += (words.empty() ? "" : ",") + format;
  args.insert(args.end(), {"--output", prefix, "--formats", words});
  // Parsed again, so that the formats are checked as the CLI checks them.
  const CommandLine line = cli::parse_command_line(args);
  cli::FileOptions files = *line.growth_files();
  files.pov.up = result.run->files.pov.up;  // from the mesh, when not given
  cli::check_writable(cli::file_names(files).front());
  RunRecord record = result.record;  // the growth's time, command and end; the writing's own time
  py::gil_scoped_release released;
  cli::write_run(*result.run, result.cluster, files, record);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "dla3d's growth models, grown from Python (see the dla3d package)";
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
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
      .def_property_readonly("command", [](const Result& r) { return cli::command_line(r.args); },
                             "the dla3d command line that grows the same structure")
      .def_property_readonly("up", [](const Result& r) { return std::string(to_string(r.run->files.pov.up)); },
                             "the axis that is up: x, y or z (a mesh's longest side's by default)")
      .def("__len__", [](const Result& r) { return r.cluster.particles.size(); })
      .def("__repr__", [](const Result& r) {
        return "<dla3d.Result: " + cli::with_commas(static_cast<double>(r.cluster.particles.size())) + " particles, " +
               std::to_string(r.cluster.seed_count) + (r.cluster.seed_count == 1 ? " seed" : " seeds") +
               (r.record.stopped_by.empty() ? "" : ", stopped by " + r.record.stopped_by) + ">";
      })
      .def("_tubes", &tubes, py::arg("sides"), py::arg("tolerance"), py::arg("min_branch"),
           "(vertices, normals, faces, particle): the tube mesh of the look (dla3d.Result.tubes)")
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
      "grow_run",
      [](const std::vector<std::string>& args, const std::string& model, const py::dict& arrays,
         const py::object& progress) {
        std::map<std::string, TriangleMesh> meshes;
        for (const auto& [name, value] : arrays) {
          const auto pair = value.cast<py::tuple>();
          const std::string key = name.cast<std::string>();
          meshes[key] = mesh_from_arrays(key, pair[0].cast<Vertices>(), pair[1].cast<Faces>());
        }
        return grow_run(args, model, meshes, progress);
      },
      py::arg("args"), py::arg("model"), py::arg("meshes"), py::arg("progress"));
  m.def(
      "check_args",
      [](const std::vector<std::string>& args, const std::string& model) { check_kind(cli::parse_command_line(args), model); },
      py::arg("args"), py::arg("model"), "raises ValueError for the words the command line refuses");
}

}  // namespace dla::python
