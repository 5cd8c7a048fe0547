#pragma once
// Checks of a solid's mesh that do not trust solid.cpp: edges, self-intersections (CGAL, in
// solid_check.cpp), shells, the winding number and the enclosed volume.

#include "dla/look/solid.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace dla {

//! "" when every edge has exactly two triangles, which use it in opposite directions (a closed,
//! consistently oriented 2-manifold), else what is wrong.
inline std::string edge_faults(const SolidMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  std::size_t repeated = 0, unmatched = 0;
  for (const auto& [edge, count] : directed) {
    repeated += count != 1;
    const auto back = directed.find({edge.second, edge.first});
    unmatched += back == directed.end() || back->second != 1;
  }
  if (mesh.triangles.empty()) return "no triangles";
  if (repeated || unmatched)
    return std::to_string(repeated) + " directed edges used twice, " + std::to_string(unmatched) +
           " without their opposite";
  return "";
}

//! Whether two triangles of the mesh intersect other than at a shared vertex or edge (CGAL's
//! Polygon Mesh Processing does_self_intersect).
bool self_intersects(const SolidMesh& mesh);

//! The generalised winding number of the mesh at p: 1 inside a closed, outward mesh, 0 outside.
inline double winding_number(const SolidMesh& mesh, const Vec3& p) {
  double total = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]].cast<double>() - p, b = mesh.vertices[t[1]].cast<double>() - p,
               c = mesh.vertices[t[2]].cast<double>() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    total += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return total / (4.0 * M_PI);
}

//! The mesh's shells: its faces' connected components, two faces joined where they share an
//! edge (not solid.cpp's count).
inline std::size_t face_components(const SolidMesh& mesh) {
  std::vector<std::size_t> parent(mesh.triangles.size());
  for (std::size_t f = 0; f < parent.size(); ++f) parent[f] = f;
  const auto find = [&](std::size_t f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> first_face;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
      const auto [at, added] = first_face.emplace(std::make_pair(std::min(a, b), std::max(a, b)), f);
      if (!added) parent[find(f)] = find(at->second);
    }
  std::size_t components = 0;
  for (std::size_t f = 0; f < parent.size(); ++f) components += find(f) == f;
  return components;
}

inline double mesh_volume(const SolidMesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles)
    volume += mesh.vertices[t[0]].cast<double>().dot(mesh.vertices[t[1]].cast<double>().cross(mesh.vertices[t[2]].cast<double>()));
  return volume / 6.0;
}

//! A binary STL's triangles, its vertices welded where they are equal; empty if the file is not
//! a whole binary STL.
inline SolidMesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  const std::string stl = bytes.str();
  SolidMesh mesh;
  if (stl.size() < 84) return mesh;
  std::uint32_t count = 0;
  std::memcpy(&count, stl.data() + 80, 4);
  if (stl.size() != 84 + 50 * static_cast<std::size_t>(count)) return mesh;
  std::map<std::array<float, 3>, std::uint32_t> index;
  for (std::uint32_t f = 0; f < count; ++f) {
    std::array<std::uint32_t, 3> triangle;
    for (int k = 0; k < 3; ++k) {
      std::array<float, 3> p;
      std::memcpy(p.data(), stl.data() + 84 + 50 * static_cast<std::size_t>(f) + 12 + 12 * k, 12);
      const auto [at, added] = index.emplace(p, static_cast<std::uint32_t>(mesh.vertices.size()));
      if (added) mesh.vertices.emplace_back(p[0], p[1], p[2]);
      triangle[static_cast<std::size_t>(k)] = at->second;
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

}  // namespace dla
