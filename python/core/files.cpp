// What a grown structure gives besides its particles: tubes, instancing points, strands, the
// solid, and the files.

#include "files.h"
#include "interrupt.h"
#include "keywords.h"

#include "dla/look/instances.h"
#include "dla/look/solid.h"
#include "dla/look/strands.h"
#include "dla/look/tubes.h"
#include "dla/run/output.h"

#include <cstring>
#include <optional>

namespace dla::python {

//! Every tube of the structure as one mesh: float32 vertices, normals, texture coordinates and
//! tangents, uint32 triangles, and the particle each vertex belongs to.
py::tuple tubes(Result& result, std::optional<int> sides, std::optional<double> tolerance,
                std::optional<int> min_branch, std::optional<double> uv_scale) {
  TubeOptions options = result.run->files.look.tubes;  // the run's, where not given
  if (sides) options.sides = *sides;
  if (tolerance) options.tolerance = *tolerance;
  if (min_branch) options.min_branch = *min_branch;
  if (uv_scale) options.uv_scale = *uv_scale;
  try {
    validate(options);
  } catch (const InvalidInput& e) {
    // Result.tubes() spells its keywords without the tube_ of a run's: sides=, not tube_sides=.
    std::string message = e.what();
    for (std::size_t at = message.find("`tube_"); at != std::string::npos; at = message.find("`tube_", at))
      message.erase(at + 1, 5);
    throw InvalidInput(message);
  }
  std::vector<float> positions, normals, uvs, tangents;
  std::vector<std::uint32_t> triangles;
  std::vector<std::int32_t> particles;
  interruptible([&] {
    const Look& look = result.look();
    for_each_tube(result.cluster, look.attributes, look.radii, options, [&](const TubePiece& piece) {
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
  });
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
  interruptible([&] {
    const Look look = make_look(result.cluster, files.look,
                                {run.constraint ? &run.constraint->surface() : nullptr, nullptr, run.threads,
                                 picks_every_tip(files.instances),
                                 files.instances.exclude_paint ? &*files.instances.exclude_paint : nullptr,
                                 run.constraint ? &run.constraint->mesh() : nullptr});
    points = instancing_points(result.cluster, look.attributes, files.instances);
  });
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
  const Look& look = result.look_for_python();
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

//! The structure's solid (solid.h) with the run's solid options but those given: float32
//! vertices, uint32 triangles, each vertex's nearest particle, and the measures.
py::tuple solid(Result& result, const py::dict& given) {
  SolidOptions options = result.run->files.solid;
  Given unused;
  for (const auto& [key, value] : given) {
    const std::string name = key.cast<std::string>();
    const auto setter = solid_keywords().find(name);
    if (setter == solid_keywords().end()) throw InvalidInput(name + " is not an option of solid()");
    setter->second(options, value, unused);
  }
  Solid built;
  std::vector<std::int32_t> nearest;
  interruptible([&] {
    built = build_solid(result.cluster, result.look().radii, options, detail::scoped_stop());
    nearest = nearest_particles(result.cluster, built, built.mesh.vertices);
  });
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

//! Writes the files `formats` names (the formats' words) as PREFIX.EXT, with the look the run's
//! options ask for; the JSON records how the run was made.
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
  interruptible([&] { write_run(*result.run, result.cluster, files, record, detail::scoped_stop()); });
}


}  // namespace dla::python
