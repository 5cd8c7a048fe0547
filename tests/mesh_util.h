#pragma once
// Brute-force references for the mesh tests, written independently of the library's own
// methods: the generalized winding number by solid angles, segment/triangle hits by
// Moller-Trumbore over every triangle, and the closest point by sampling each triangle densely.

#include "dla/mesh/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <string>

namespace dla::testing {

//! Sum of the triangles' solid angles seen from p over 4 pi (Van Oosterom and Strackee).
inline double generalized_winding_number(const TriangleMesh& mesh, const Vec3& p) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return sum / (4.0 * 3.14159265358979323846);
}

//! Distance from p to the nearest triangle, by a scan of every one: the oracle of closest points.
inline double brute_distance(const TriangleMesh& mesh, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    // The nearest of the face's plane foot (if it falls inside) and the three edges.
    const Vec3 n = (b - a).cross(c - a);
    double d = std::numeric_limits<double>::infinity();
    if (n.squaredNorm() > 0.0) {
      const Vec3 foot = p - n * (n.dot(p - a) / n.squaredNorm());
      if (n.dot((b - a).cross(foot - a)) >= 0 && n.dot((c - b).cross(foot - b)) >= 0 && n.dot((a - c).cross(foot - c)) >= 0)
        d = (p - foot).norm();
    }
    for (const auto& [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      const double len2 = (v - u).squaredNorm();
      const double s = len2 > 0.0 ? std::clamp((p - u).dot(v - u) / len2, 0.0, 1.0) : 0.0;
      d = std::min(d, (p - (u + s * (v - u))).norm());
    }
    best = std::min(best, d);
  }
  return best;
}

//! Parameters t in [0, 1] where from + t (to - from) meets a triangle: the smallest, or -1.
inline double brute_first_hit(const TriangleMesh& mesh, const Vec3& from, const Vec3& to) {
  const Vec3 d = to - from;
  const Vec3 lo = from.cwiseMin(to), hi = from.cwiseMax(to);
  double best = -1.0;
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    if ((a.array() < lo.array() && b.array() < lo.array() && c.array() < lo.array()).any() ||
        (a.array() > hi.array() && b.array() > hi.array() && c.array() > hi.array()).any())
      continue;
    const Vec3 e1 = b - a, e2 = c - a, h = d.cross(e2);
    const double det = e1.dot(h);
    if (det == 0.0) continue;
    const Vec3 s = from - a;
    const double u = s.dot(h) / det;
    if (u < 0.0 || u > 1.0) continue;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double hit = e2.dot(q) / det;
    if (hit >= 0.0 && hit <= 1.0 && (best < 0.0 || hit < best)) best = hit;
  }
  return best;
}

//! The closest of `samples`² barycentric samples of every triangle to p, and the vertex colours
//! blended there: slow, and exact to about an edge / samples.
struct SampledClosest {
  double distance = std::numeric_limits<double>::infinity();
  Vec3 color = Vec3::Zero();
};
inline SampledClosest sampled_closest(const TriangleMesh& mesh, const Vec3& p, int samples = 24) {
  SampledClosest best;
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    if (((lo - p).cwiseMax(p - hi).cwiseMax(0.0)).norm() > best.distance) continue;
    for (int i = 0; i <= samples; ++i)
      for (int j = 0; i + j <= samples; ++j) {
        const double u = double(i) / samples, v = double(j) / samples;
        const double d = (a + u * (b - a) + v * (c - a) - p).norm();
        if (d >= best.distance) continue;
        best.distance = d;
        if (!mesh.colors.empty())
          best.color = (1 - u - v) * mesh.colors[t[0]] + u * mesh.colors[t[1]] + v * mesh.colors[t[2]];
      }
  }
  return best;
}

//! An ASCII PLY of `mesh` with its vertex colours as bytes, as Blender writes a painted mesh.
inline std::string painted_ply(const TriangleMesh& mesh) {
  std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(mesh.vertices.size()) +
                     "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                     "property uchar green\nproperty uchar blue\nelement face " +
                     std::to_string(mesh.triangles.size()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  char line[160];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    const Vec3 c = 255.0 * mesh.colors[i];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g %d %d %d\n", v.x(), v.y(), v.z(), int(std::lround(c.x())),
                  int(std::lround(c.y())), int(std::lround(c.z())));
    text += line;
  }
  for (const auto& t : mesh.triangles)
    text += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  return text;
}

//! The scanned bust from Debian's libcgal-demo, extracted into the build tree by CMake; empty
//! if the package is not installed.
inline std::string bust_path() {
  const std::string path = BUST_OFF_PATH;
  return std::filesystem::exists(path) ? path : std::string();
}

#define DLA_NEED_BUST(path)                                                                              \
  const std::string path = ::dla::testing::bust_path();                                                  \
  if (path.empty())                                                                                      \
  GTEST_SKIP() << "the bust mesh is missing: install libcgal-demo (the README's setup does) and run cmake " \
                  "again"

}  // namespace dla::testing
