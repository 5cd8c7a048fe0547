#pragma once
// Checks of a tube piece (tubes.h) that do not trust its construction: closedness once the seam's
// repeated vertices are welded by position, and texture coordinates and tangents against the
// directions the triangles' own UVs imply.

#include "dla/look/tubes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace dla::testing {

//! The piece's triangles with each vertex index replaced by the first vertex at its position.
inline std::vector<std::array<std::uint32_t, 3>> welded_triangles(const TubePiece& piece) {
  std::map<std::tuple<float, float, float>, std::uint32_t> first;
  std::vector<std::uint32_t> to(piece.positions.size());
  for (std::uint32_t v = 0; v < piece.positions.size(); ++v) {
    const Eigen::Vector3f& p = piece.positions[v];
    to[v] = first.emplace(std::make_tuple(p.x(), p.y(), p.z()), v).first->second;
  }
  std::vector<std::array<std::uint32_t, 3>> welded = piece.triangles;
  for (auto& t : welded)
    for (std::uint32_t& v : t) v = to[v];
  return welded;
}

//! Welded, every edge is used once in each direction: a closed surface.
inline void expect_closed(const TubePiece& piece) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : welded_triangles(piece))
    for (std::size_t k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1) << "an edge used twice the same way";
    ASSERT_EQ(edges.count({edge.second, edge.first}), 1u) << "an open edge";
  }
}

//! u in [0, 1]; the only vertices sharing a position are a seam's pair at u = 0 and u = 1; each
//! tangent is a unit vector orthogonal to its normal with w = 1; and on every triangle whose
//! UVs span an area, the tangent points the way u rises and normal × tangent the way v rises.
inline void expect_texture_frame(const TubePiece& piece) {
  const std::size_t n = piece.positions.size();
  ASSERT_EQ(piece.uvs.size(), n);
  ASSERT_EQ(piece.tangents.size(), n);
  std::map<std::tuple<float, float, float>, std::vector<std::size_t>> at;
  for (std::size_t v = 0; v < n; ++v) {
    const Eigen::Vector2f& uv = piece.uvs[v];
    ASSERT_TRUE(uv.allFinite());
    ASSERT_GE(uv.x(), 0.0f);
    ASSERT_LE(uv.x(), 1.0f);
    const Eigen::Vector3f t = piece.tangents[v].head<3>();
    ASSERT_EQ(piece.tangents[v].w(), 1.0f);
    ASSERT_NEAR(t.norm(), 1.0f, 1e-5f);
    ASSERT_NEAR(t.dot(piece.normals[v]), 0.0f, 1e-5f) << "a tangent not orthogonal to its normal";
    const Eigen::Vector3f& p = piece.positions[v];
    at[std::make_tuple(p.x(), p.y(), p.z())].push_back(v);
  }
  for (const auto& [position, vertices] : at) {
    if (vertices.size() == 1) continue;
    ASSERT_EQ(vertices.size(), 2u) << "three vertices at one place";
    const Eigen::Vector2f a = piece.uvs[vertices[0]], b = piece.uvs[vertices[1]];
    EXPECT_EQ(a.x(), 0.0f) << "a repeated vertex off the seam";
    EXPECT_EQ(b.x(), 1.0f) << "a repeated vertex off the seam";
    EXPECT_EQ(a.y(), b.y());
  }
  for (const auto& t : piece.triangles) {
    const Eigen::Vector3d p0 = piece.positions[t[0]].cast<double>();
    const Eigen::Vector3d e1 = piece.positions[t[1]].cast<double>() - p0, e2 = piece.positions[t[2]].cast<double>() - p0;
    const Eigen::Vector2d d1 = (piece.uvs[t[1]] - piece.uvs[t[0]]).cast<double>(),
                          d2 = (piece.uvs[t[2]] - piece.uvs[t[0]]).cast<double>();
    const double det = d1.x() * d2.y() - d2.x() * d1.y();
    if (std::abs(det) < 1e-9) continue;  // a cap's start, all at one v
    const Eigen::Vector3d along_u = (e1 * d2.y() - e2 * d1.y()) / det, along_v = (e2 * d1.x() - e1 * d2.x()) / det;
    Eigen::Vector3d tangent = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
    for (const std::uint32_t v : t) {
      tangent += piece.tangents[v].head<3>().cast<double>();
      normal += piece.normals[v].cast<double>();
    }
    ASSERT_GT(tangent.dot(along_u), 0.0) << "the tangent runs against u";
    ASSERT_GT(normal.cross(tangent).dot(along_v), 0.0) << "normal x tangent runs against v";
  }
}

//! An OBJ file's lines hold `pieces` in order, as the writers walk them: each piece's vertex
//! lines (positions to the 7 significant digits written), then its faces, whose indices count
//! from 1 over the whole file.
inline void expect_obj_holds(const std::string& obj, const std::vector<TubePiece>& pieces) {
  std::vector<Eigen::Vector3f> positions;
  std::vector<std::array<std::size_t, 3>> faces;
  std::vector<std::size_t> vertices_before;  // for each face: the vertex lines above it
  for (const TubePiece& piece : pieces) {
    const std::size_t base = positions.size() + 1;
    positions.insert(positions.end(), piece.positions.begin(), piece.positions.end());
    for (const auto& t : piece.triangles) {
      faces.push_back({base + t[0], base + t[1], base + t[2]});
      vertices_before.push_back(positions.size());
    }
  }
  std::istringstream lines(obj);
  std::size_t v = 0, f = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line.substr(line.find(' ') + 1));
    if (line.rfind("v ", 0) == 0) {
      ASSERT_LT(v, positions.size()) << "more vertices than the pieces";
      for (int a = 0; a < 3; ++a) {
        double value = 0;
        fields >> value;
        ASSERT_NEAR(value, positions[v][a], 1e-6 * std::abs(positions[v][a]) + 1e-12) << "vertex " << v + 1;
      }
      ++v;
    } else if (line.rfind("f ", 0) == 0) {
      ASSERT_LT(f, faces.size()) << "more faces than the pieces";
      ASSERT_EQ(v, vertices_before[f]) << "face " << f + 1 << " not right after its piece's vertices";
      for (const std::size_t expected : faces[f]) {
        std::string corner;
        fields >> corner;
        ASSERT_EQ(std::stoull(corner.substr(0, corner.find('/'))), expected) << line;
      }
      ++f;
    }
  }
  EXPECT_EQ(v, positions.size());
  EXPECT_EQ(f, faces.size());
}

}  // namespace dla::testing
