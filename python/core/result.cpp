// dla3d._core.Result: the structure's arrays share its memory; the look's are computed on first
// use.

#include "files.h"
#include "result.h"

#include "dla/core/analysis.h"
#include "dla/mesh/surface_distance.h"

#include <pybind11/stl.h>

#include <cmath>
#include <utility>

namespace dla::python {

using detail::with_commas;

void bind_result(py::module_& m) {
  py::class_<Result, std::shared_ptr<Result>> result(m, "Result", "A grown structure: the arrays share its memory");
  result
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
        const std::vector<std::int32_t>& depth = r.look_for_python().attributes.depth;
        return shared_array(depth.data(), {static_cast<py::ssize_t>(depth.size())}, {sizeof(std::int32_t)}, self);
      }, "(N,) int32: particles on the path to the seed")
      .def_property_readonly("descendants", [](py::object self) {
        Result& r = self.cast<Result&>();
        const std::vector<std::int32_t>& d = r.look_for_python().attributes.descendants;
        return shared_array(d.data(), {static_cast<py::ssize_t>(d.size())}, {sizeof(std::int32_t)}, self);
      }, "(N,) int32: particles in the subtree, itself not counted");
  // One value a particle from its attributes, in a new array.
  const auto attribute = [&result](const char* name, auto value, const char* doc) {
    using T = decltype(value(std::declval<const Attributes&>(), std::size_t{}));
    result.def_property_readonly(name, [value](Result& r) {
      const Attributes& a = r.look_for_python().attributes;
      return per_particle<T>(r, [&](std::size_t i) { return value(a, i); });
    }, doc);
  };
  attribute("age", [](const Attributes& a, std::size_t i) { return a.age(i); },
            "(N,) float32: attach order, 0 (seeds and the first) to 1 (the last)");
  attribute("order", [](const Attributes& a, std::size_t i) { return static_cast<std::uint8_t>(a.strahler(i)); },
            "(N,) uint8: Strahler order, tips 1");
  attribute("tip", [](const Attributes& a, std::size_t i) { return a.tip(i); }, "(N,) bool: no child");
  attribute("current", [](const Attributes& a, std::size_t i) { return a.current(i); },
            "(N,) float32: the share of the largest tree's charge that flows through it, 1 at a discharge's "
            "strike; its subtree's particles when nothing struck");
  attribute("channel", [](const Attributes& a, std::size_t i) { return a.on_channel(i); },
            "(N,) bool: on a discharge's main channel, from the seed to the strike");
  attribute("light", [](const Attributes& a, std::size_t i) { return a.light(i); },
            "(N,) float32: when the leader reaches it, 0 to 1 at the strike (past 1 after it); the age "
            "when nothing struck");
  result
      .def_property_readonly("radius", [](Result& r) {
        const Look& look = r.look_for_python();
        return per_particle<float>(r, [&](std::size_t i) { return static_cast<float>(look.radius(r.cluster, i)); });
      }, "(N,) float32: the branch radius of the look, in scene units")
      .def_property_readonly("radii", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        const std::vector<double>& radii = r.cluster.radii;
        return shared_array(radii.data(), {static_cast<py::ssize_t>(radii.size())}, {sizeof(double)}, self);
      }, "(N,) float64: each particle's own radius in scene units, for a model that sizes them (an aggregate's "
         "monomers); empty for the others")
      .def_property_readonly("strike", [](const Result& r) { return r.cluster.strike; },
                             "the breakdown model's strike: the particle that reached the target; -1: none")
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
}

}  // namespace dla::python
