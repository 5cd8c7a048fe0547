// The mesh and point readers behind one call, a reader a format (mesh_readers.h), and what
// meshes share: appending one to another, their bounding box.

#include "mesh_readers.h"

#include "dla/core/hash.h"
#include "dla/core/input_file.h"

#include <limits>

namespace dla {

TriangleMesh parse_mesh(std::string_view bytes, std::string_view extension, const std::string& name) {
  const std::string format = detail::lower(extension);
  if (bytes.empty()) detail::malformed(name, "is empty");
  if (format == "stl") return detail::parse_stl(bytes, name);
  if (format == "off") return detail::parse_off(bytes, name);
  if (format == "obj") return detail::parse_obj(bytes, name);
  if (format == "ply") return detail::parse_ply(bytes, name);
  throw InvalidInput(name + ": unknown mesh format '" + std::string(extension) + "' (use .stl, .off, .obj or .ply)");
}

namespace {

std::string extension_of(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  return dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot + 1);
}

}  // namespace

TriangleMesh read_mesh(const std::string& path, std::uint64_t* file_hash) {
  const std::string extension = extension_of(path);
  if (extension.empty()) throw InvalidInput(path + ": no file extension to tell the mesh format (.stl, .off, .obj, .ply)");
  const std::string bytes = read_input_file(path, "");
  if (file_hash) *file_hash = fnv1a(bytes);
  return parse_mesh(bytes, extension, path);
}

std::vector<Vec3> parse_points(std::string_view bytes, std::string_view extension, const std::string& name) {
  const std::string format = detail::lower(extension);
  if (format != "ply" && format != "csv" && format != "txt" && format != "xyz")
    throw InvalidInput(name + ": unknown point file format '" + std::string(extension.substr(0, 40)) +
                       "' (use .csv, .txt, .xyz or .ply)");
  if (bytes.empty()) detail::malformed(name, "is empty");
  std::vector<Vec3> points = format == "ply" ? detail::parse_ply(bytes, name, true).vertices : detail::parse_point_rows(bytes, name);
  if (points.empty()) detail::malformed(name, "holds no points");
  return points;
}

std::vector<Vec3> read_points(const std::string& path) {
  return parse_points(read_input_file(path, ""), extension_of(path), path);
}

void append(TriangleMesh& mesh, const TriangleMesh& more) {
  const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
  if (!mesh.colors.empty() || !more.colors.empty()) {
    mesh.colors.resize(mesh.vertices.size(), Vec3::Ones());
    if (more.colors.empty()) mesh.colors.resize(mesh.vertices.size() + more.vertices.size(), Vec3::Ones());
    else mesh.colors.insert(mesh.colors.end(), more.colors.begin(), more.colors.end());
  }
  mesh.vertices.insert(mesh.vertices.end(), more.vertices.begin(), more.vertices.end());
  for (const auto& t : more.triangles) mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

Box bounding_box(const TriangleMesh& mesh) {
  Box box{Vec3::Constant(std::numeric_limits<double>::infinity()),
          Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (const auto& t : mesh.triangles)
    for (std::uint32_t id : t) {
      box.min = box.min.cwiseMin(mesh.vertices[id]);
      box.max = box.max.cwiseMax(mesh.vertices[id]);
    }
  return box;
}

}  // namespace dla
