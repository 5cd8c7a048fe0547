#pragma once
// What the mesh readers share (read_mesh(), parse_mesh() and read_points() in mesh.h): a
// reader a format, each in its own file (stl_reader.cpp, off_reader.cpp, obj_reader.cpp,
// ply_reader.cpp, point_reader.cpp), and the words, numbers and checks they read with. Every
// reader checks counts against the file's size before it allocates, indices against the vertex
// count and coordinates for finiteness, and names the file and the place in its messages.

#include "dla/mesh/mesh.h"

#include "dla/core/errors.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dla::detail {

[[noreturn]] inline void malformed(const std::string& name, const std::string& what) {
  throw InvalidInput(name + ": " + what);
}

inline std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

//! Whitespace-separated words of a text, with the line number for messages.
class Words {
 public:
  explicit Words(std::string_view text, char comment = '\0') : text_(text), comment_(comment) {}

  //! The next word, or an empty view at the end.
  std::string_view next() {
    skip();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  //! Moves past white space and comments to the next word: line() is then the word's line.
  void skip() {
    for (;;) {
      while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
        if (text_[pos_] == '\n') ++line_;
        ++pos_;
      }
      if (comment_ && pos_ < text_.size() && text_[pos_] == comment_) {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        continue;
      }
      break;
    }
  }

  //! The rest of the current line, without its end.
  std::string_view rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::string_view line = text_.substr(start, pos_ - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  std::size_t line() const { return line_; }
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

inline bool parse_double(std::string_view word, double& value) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

template <class Int>
bool parse_integer(std::string_view word, Int& value) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

//! Collects vertices and polygons, checking them as they come.
class Builder {
 public:
  explicit Builder(const std::string& name) : name_(name) {}

  void vertex(const Vec3& v, const std::string& where) {
    if (!v.allFinite()) malformed(name_, where + " has a coordinate that is not a finite number");
    mesh_.vertices.push_back(v);
  }

  //! A polygon of vertex indices, split into a fan of triangles.
  void polygon(const std::vector<std::int64_t>& ids, const std::string& where) {
    if (ids.size() < 3) malformed(name_, where + " has fewer than 3 vertices");
    for (std::int64_t id : ids)
      if (id < 0 || id >= static_cast<std::int64_t>(mesh_.vertices.size()))
        malformed(name_, where + " uses vertex " + std::to_string(id) + " but there are " +
                             std::to_string(mesh_.vertices.size()) + " vertices");
    for (std::size_t i = 1; i + 1 < ids.size(); ++i)
      mesh_.triangles.push_back({static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[i]),
                                 static_cast<std::uint32_t>(ids[i + 1])});
  }

  //! The colour of the vertex read last, from numbers that count to `full` (255 or 1).
  void color(const Vec3& rgb, double full, const std::string& where) {
    if (!rgb.allFinite() || rgb.minCoeff() < 0.0 || rgb.maxCoeff() > full)
      malformed(name_, where + " has a colour outside 0 to " + detail::format_number(full));
    mesh_.colors.resize(mesh_.vertices.size(), Vec3::Ones());
    mesh_.colors.back() = rgb / full;
  }

  void reserve(std::size_t vertices, std::size_t triangles) {
    mesh_.vertices.reserve(vertices);
    mesh_.triangles.reserve(triangles);
  }

  TriangleMesh finish(bool need_triangles = true) {
    if (need_triangles && mesh_.triangles.empty()) malformed(name_, "has no triangles");
    // A file that colours some vertices leaves the rest white, as Blender shows them.
    if (!mesh_.colors.empty()) mesh_.colors.resize(mesh_.vertices.size(), Vec3::Ones());
    return std::move(mesh_);
  }

  std::size_t vertex_count() const { return mesh_.vertices.size(); }

 private:
  const std::string& name_;
  TriangleMesh mesh_;
};

//! Binary or ASCII STL.
TriangleMesh parse_stl(std::string_view bytes, const std::string& name);
//! OFF, with vertex colours (COFF) when it has them.
TriangleMesh parse_off(std::string_view text, const std::string& name);
//! Wavefront OBJ, with vertex colours after the coordinates when it has them.
TriangleMesh parse_obj(std::string_view text, const std::string& name);
//! A PLY's mesh, ASCII or binary; with `points_only`, its vertices alone (faces, if any, are
//! read past).
TriangleMesh parse_ply(std::string_view bytes, const std::string& name, bool points_only = false);
//! Points as rows of x,y,z (CSV, TXT, XYZ); a header naming x, y and z picks those columns.
std::vector<Vec3> parse_point_rows(std::string_view text, const std::string& name);

}  // namespace dla::detail
