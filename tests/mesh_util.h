#pragma once
// Brute-force references for the mesh tests, written independently of the library's own
// methods: the generalized winding number by solid angles, and segment/triangle hits by
// Moller-Trumbore over every triangle.

#include "dla/mesh/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
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
