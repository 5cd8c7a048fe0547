// Mesh readers and the STL writer. Every reader checks counts against the file's size before it
// allocates, indices against the vertex count and coordinates for finiteness, and names the
// file and the place in its messages.

#include "dla/mesh/mesh.h"

#include "dla/core/hash.h"
#include "dla/io/input_file.h"
#include "io/output_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

namespace dla {

namespace {

[[noreturn]] void malformed(const std::string& name, const std::string& what) {
  throw InvalidInput(name + ": " + what);
}

std::string lower(std::string_view text) {
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

bool parse_double(std::string_view word, double& value) {
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

// --- STL ---------------------------------------------------------------------------------------

float read_float_le(const unsigned char* p) {
  std::uint32_t bits = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                       std::uint32_t(p[3]) << 24;
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint32_t read_u32_le(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

TriangleMesh parse_binary_stl(std::string_view bytes, const std::string& name, std::uint64_t count) {
  Builder mesh(name);
  mesh.reserve(3 * count, count);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::uint64_t t = 0; t < count; ++t) {
    const unsigned char* facet = data + 84 + 50 * t + 12;  // skip the stored normal
    const std::string where = "triangle " + std::to_string(t + 1);
    std::vector<std::int64_t> ids;
    for (int v = 0; v < 3; ++v) {
      const unsigned char* p = facet + 12 * v;
      ids.push_back(static_cast<std::int64_t>(mesh.vertex_count()));
      mesh.vertex({read_float_le(p), read_float_le(p + 4), read_float_le(p + 8)}, where);
    }
    mesh.polygon(ids, where);
  }
  return mesh.finish();
}

TriangleMesh parse_ascii_stl(std::string_view text, const std::string& name) {
  Builder mesh(name);
  Words words(text);
  if (lower(words.next()) != "solid") malformed(name, "is neither a binary STL nor an ASCII STL starting with 'solid'");
  words.rest_of_line();  // the solid's name
  std::vector<std::int64_t> ids;
  bool ended = false;
  for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
    const std::string key = lower(word);
    const std::string where = "line " + std::to_string(words.line());
    if (key == "vertex") {
      Vec3 v;
      for (int i = 0; i < 3; ++i)
        if (!parse_double(words.next(), v[i])) malformed(name, where + ": a vertex needs 3 numbers");
      ids.push_back(static_cast<std::int64_t>(mesh.vertex_count()));
      mesh.vertex(v, where);
    } else if (key == "endfacet") {
      if (ids.size() != 3) malformed(name, where + ": a facet has " + std::to_string(ids.size()) + " vertices, not 3");
      mesh.polygon(ids, where);
      ids.clear();
    } else if (key == "normal") {
      double ignored;
      for (int i = 0; i < 3; ++i)
        if (!parse_double(words.next(), ignored)) malformed(name, where + ": a normal needs 3 numbers");
    } else if (key == "endsolid") {
      ended = true;
      words.rest_of_line();
    } else if (key == "solid") {
      words.rest_of_line();  // files that hold several solids
    } else if (key != "facet" && key != "outer" && key != "loop" && key != "endloop") {
      malformed(name, where + ": unexpected '" + std::string(word.substr(0, 40)) + "' in an ASCII STL");
    }
  }
  if (!ids.empty() || !ended) malformed(name, "ends in the middle of the ASCII STL (no 'endsolid')");
  return mesh.finish();
}

TriangleMesh parse_stl(std::string_view bytes, const std::string& name) {
  // Binary is decided by size: 84 + 50 x count. Some binary files begin with "solid" too.
  if (bytes.size() >= 84) {
    const std::uint64_t count = read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
    if (bytes.size() == 84 + 50 * count) return parse_binary_stl(bytes, name, count);
  }
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && lower(bytes.substr(start, 5)) == "solid")
    return parse_ascii_stl(bytes, name);
  if (bytes.size() < 84) malformed(name, "is too short for an STL file (" + std::to_string(bytes.size()) + " bytes)");
  const std::uint64_t count = read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
  malformed(name, "is not a valid binary STL: its header counts " + std::to_string(count) + " triangles, " +
                      std::to_string(84 + 50 * count) + " bytes, but the file has " +
                      std::to_string(bytes.size()) + " bytes");
}

// --- OFF ---------------------------------------------------------------------------------------

TriangleMesh parse_off(std::string_view text, const std::string& name) {
  Words words(text, '#');
  const std::string header = std::string(words.next());
  if (header != "OFF" && header != "COFF" && header != "NOFF" && header != "CNOFF")
    malformed(name, "does not begin with OFF");
  const bool colored = header.front() == 'C', normals = header.find('N') != std::string::npos;
  std::uint64_t nv = 0, nf = 0, ne = 0;
  if (!parse_integer(words.next(), nv) || !parse_integer(words.next(), nf) || !parse_integer(words.next(), ne))
    malformed(name, "has no vertex, face and edge counts after OFF");
  // A vertex takes at least 6 bytes ("0 0 0\n"), a triangle 8: refuse counts the file cannot hold.
  if (nv > text.size() / 6 || nf > text.size() / 8)
    malformed(name, "counts " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                        " faces, more than its " + std::to_string(text.size()) + " bytes can hold");
  Builder mesh(name);
  mesh.reserve(nv, nf);
  for (std::uint64_t i = 0; i < nv; ++i) {
    words.skip();
    const std::string where = "vertex " + std::to_string(i) + " (line " + std::to_string(words.line()) + ")";
    Vec3 v;
    for (int a = 0; a < 3; ++a)
      if (!parse_double(words.next(), v[a])) malformed(name, where + " is not 3 numbers");
    mesh.vertex(v, where);
    Words rest(words.rest_of_line());  // NOFF's normal, then COFF's colour and alpha
    if (normals)
      for (int a = 0; a < 3; ++a) rest.next();
    if (colored) {
      // Geomview's rule: integers count to 255, any other number to 1.
      Vec3 rgb;
      bool integers = true;
      for (int a = 0; a < 3; ++a) {
        const std::string_view word = rest.next();
        if (!parse_double(word, rgb[a])) malformed(name, where + " has no red, green and blue after its place");
        integers = integers && word.find_first_of(".eE") == std::string_view::npos;
      }
      mesh.color(rgb, integers ? 255.0 : 1.0, where);
    }
  }
  std::vector<std::int64_t> ids;
  for (std::uint64_t f = 0; f < nf; ++f) {
    words.skip();
    const std::string where = "face " + std::to_string(f) + " (line " + std::to_string(words.line()) + ")";
    std::uint32_t n = 0;
    if (!parse_integer(words.next(), n)) malformed(name, where + " does not begin with its vertex count");
    if (n > nv) malformed(name, where + " has " + std::to_string(n) + " vertices, more than the mesh");
    ids.assign(n, 0);
    for (std::uint32_t i = 0; i < n; ++i)
      if (!parse_integer(words.next(), ids[i])) malformed(name, where + " has a vertex index that is not a number");
    words.rest_of_line();  // an optional colour
    mesh.polygon(ids, where);
  }
  return mesh.finish();
}

// --- OBJ ---------------------------------------------------------------------------------------

TriangleMesh parse_obj(std::string_view text, const std::string& name) {
  Builder mesh(name);
  std::vector<std::int64_t> ids;
  std::size_t line_number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const std::string where = "line " + std::to_string(line_number);
    Words words(line, '#');
    const std::string_view key = words.next();
    if (key == "v") {
      Vec3 v;
      for (int a = 0; a < 3; ++a)
        if (!parse_double(words.next(), v[a])) malformed(name, where + ": a vertex needs 3 numbers");
      mesh.vertex(v, where);
      // `v x y z r g b`, as Blender and MeshLab write vertex colours; a lone fourth number is a weight.
      const std::string_view red = words.next();
      if (!red.empty()) {
        Vec3 rgb;
        if (parse_double(red, rgb[0]) && parse_double(words.next(), rgb[1]) && parse_double(words.next(), rgb[2]))
          mesh.color(rgb, rgb.maxCoeff() > 1.0 ? 255.0 : 1.0, where);
      }
    } else if (key == "f") {
      ids.clear();
      for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
        std::int64_t id = 0;
        if (!parse_integer(word.substr(0, word.find('/')), id) || id == 0)
          malformed(name, where + ": face index '" + std::string(word.substr(0, 40)) + "' is not a vertex number");
        // 1-based; negative counts back from the latest vertex.
        ids.push_back(id > 0 ? id - 1 : static_cast<std::int64_t>(mesh.vertex_count()) + id);
      }
      mesh.polygon(ids, where);
    }
    // Normals, texture coordinates, groups and materials do not shape the surface.
  }
  return mesh.finish();
}

// --- PLY ---------------------------------------------------------------------------------------

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

bool parse_ply_type(std::string_view word, PlyType& type) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::i8},    {"int8", PlyType::i8},     {"uchar", PlyType::u8},   {"uint8", PlyType::u8},
      {"short", PlyType::i16},  {"int16", PlyType::i16},   {"ushort", PlyType::u16}, {"uint16", PlyType::u16},
      {"int", PlyType::i32},    {"int32", PlyType::i32},   {"uint", PlyType::u32},   {"uint32", PlyType::u32},
      {"float", PlyType::f32},  {"float32", PlyType::f32}, {"double", PlyType::f64}, {"float64", PlyType::f64}};
  for (const auto& [text, value] : names)
    if (word == text) {
      type = value;
      return true;
    }
  return false;
}

std::size_t ply_size(PlyType type) {
  switch (type) {
    case PlyType::i8: case PlyType::u8: return 1;
    case PlyType::i16: case PlyType::u16: return 2;
    case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 1;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;
  bool list = false;
  PlyType count_type = PlyType::u8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

//! Reads PLY scalars one after another from the body, in ASCII or binary.
class PlyBody {
 public:
  PlyBody(std::string_view body, int format, const std::string& name)
      : body_(body), words_(body), format_(format), name_(name) {}

  double read(PlyType type) {
    if (format_ == 0) {
      double value;
      const std::string_view word = words_.next();
      if (word.empty()) malformed(name_, "ends before the data its header declares");
      if (!parse_double(word, value)) malformed(name_, "has '" + std::string(word.substr(0, 40)) + "' where a number belongs");
      return value;
    }
    const std::size_t n = ply_size(type);
    if (pos_ + n > body_.size()) malformed(name_, "ends before the data its header declares");
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    if (format_ == 2) std::reverse(b, b + n);  // big endian
    switch (type) {
      case PlyType::i8: return static_cast<std::int8_t>(b[0]);
      case PlyType::u8: return b[0];
      case PlyType::i16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::u16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::i32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::u32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::f64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0.0;
  }

  std::size_t remaining() const { return format_ == 0 ? body_.size() - words_.offset() : body_.size() - pos_; }

 private:
  std::string_view body_;
  Words words_;
  int format_;  // 0 ascii, 1 little endian, 2 big endian
  std::size_t pos_ = 0;
  const std::string& name_;
};

//! A PLY's mesh; with `points_only`, its vertices alone (faces, if any, are read past).
TriangleMesh parse_ply(std::string_view bytes, const std::string& name, bool points_only = false) {
  const std::size_t header_end = bytes.find("end_header");
  if (bytes.substr(0, 3) != "ply" || header_end == std::string_view::npos)
    malformed(name, "is not a PLY file (no 'ply' ... 'end_header' header)");
  std::size_t body_start = bytes.find('\n', header_end);
  body_start = body_start == std::string_view::npos ? bytes.size() : body_start + 1;

  int format = -1;
  std::vector<PlyElement> elements;
  Words header(bytes.substr(0, header_end));
  header.next();  // "ply"
  for (std::string_view word = header.next(); !word.empty(); word = header.next()) {
    const std::string where = "header line " + std::to_string(header.line());
    if (word == "format") {
      const std::string_view kind = header.next();
      format = kind == "ascii" ? 0 : kind == "binary_little_endian" ? 1 : kind == "binary_big_endian" ? 2 : -1;
      if (format < 0) malformed(name, where + ": unknown PLY format '" + std::string(kind.substr(0, 40)) + "'");
      header.rest_of_line();
    } else if (word == "element") {
      PlyElement element;
      element.name = std::string(header.next());
      if (!parse_integer(header.next(), element.count)) malformed(name, where + ": an element needs a count");
      elements.push_back(std::move(element));
    } else if (word == "property") {
      if (elements.empty()) malformed(name, where + ": a property before any element");
      PlyProperty property;
      std::string_view type = header.next();
      if (type == "list") {
        property.list = true;
        if (!parse_ply_type(header.next(), property.count_type)) malformed(name, where + ": unknown list count type");
        type = header.next();
      }
      if (!parse_ply_type(type, property.type)) malformed(name, where + ": unknown property type '" + std::string(type.substr(0, 40)) + "'");
      property.name = std::string(header.next());
      elements.back().properties.push_back(std::move(property));
    } else if (word == "comment" || word == "obj_info") {
      header.rest_of_line();
    } else {
      malformed(name, where + ": unexpected '" + std::string(word.substr(0, 40)) + "' in the PLY header");
    }
  }
  if (format < 0) malformed(name, "has no PLY format line");

  const std::string_view body = bytes.substr(body_start);
  Builder mesh(name);
  PlyBody in(body, format, name);
  std::vector<std::int64_t> ids;
  for (const PlyElement& element : elements) {
    // Every instance takes at least one byte: refuse counts the file cannot hold.
    if (element.count > body.size())
      malformed(name, "declares " + std::to_string(element.count) + " " + element.name + " elements, more than its " +
                          std::to_string(body.size()) + " data bytes can hold");
    const bool vertices = element.name == "vertex", faces = element.name == "face" && !points_only;
    int axis_of[3] = {-1, -1, -1};
    int channel_of[3] = {-1, -1, -1};
    int list_of_faces = -1;
    static const char* const channels[2][3] = {{"red", "green", "blue"}, {"diffuse_red", "diffuse_green", "diffuse_blue"}};
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const std::string& n = element.properties[p].name;
      if (vertices && n.size() == 1 && n[0] >= 'x' && n[0] <= 'z' && !element.properties[p].list)
        axis_of[n[0] - 'x'] = static_cast<int>(p);
      for (int c = 0; c < 3; ++c)
        if (vertices && !points_only && !element.properties[p].list && (n == channels[0][c] || n == channels[1][c]))
          channel_of[c] = static_cast<int>(p);
      if (faces && element.properties[p].list && (n == "vertex_indices" || n == "vertex_index")) list_of_faces = static_cast<int>(p);
    }
    if (vertices && (axis_of[0] < 0 || axis_of[1] < 0 || axis_of[2] < 0))
      malformed(name, "has vertices without x, y and z");
    if (faces && list_of_faces < 0) malformed(name, "has faces without a vertex_indices list");
    const bool colored = channel_of[0] >= 0 && channel_of[1] >= 0 && channel_of[2] >= 0;
    // Integer channels count to their type's largest value, floats to 1.
    double full = 1.0;
    if (colored) {
      const PlyType type = element.properties[static_cast<std::size_t>(channel_of[0])].type;
      full = type == PlyType::u8 || type == PlyType::i8 ? 255.0 : type == PlyType::u16 || type == PlyType::i16 ? 65535.0 : 1.0;
    }
    if (vertices) mesh.reserve(element.count, 0);
    for (std::uint64_t i = 0; i < element.count; ++i) {
      Vec3 v = Vec3::Zero(), rgb = Vec3::Zero();
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        if (!property.list) {
          const double value = in.read(property.type);
          for (int a = 0; a < 3; ++a) {
            if (axis_of[a] == static_cast<int>(p)) v[a] = value;
            if (channel_of[a] == static_cast<int>(p)) rgb[a] = value;
          }
          continue;
        }
        const double n = in.read(property.count_type);
        if (!(n >= 0.0) || n > static_cast<double>(in.remaining()))
          malformed(name, element.name + " " + std::to_string(i) + " has a list of " + std::to_string(n) + " items");
        const bool keep = faces && static_cast<int>(p) == list_of_faces;
        if (keep) ids.assign(static_cast<std::size_t>(n), 0);
        for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
          const double id = in.read(property.type);
          if (keep) ids[k] = id >= 0.0 && id < 4294967296.0 ? static_cast<std::int64_t>(id) : -1;
        }
      }
      if (vertices) mesh.vertex(v, "vertex " + std::to_string(i));
      if (vertices && colored) mesh.color(rgb, full, "vertex " + std::to_string(i));
      if (faces) mesh.polygon(ids, "face " + std::to_string(i));
    }
  }
  return mesh.finish(!points_only);
}

// --- Points: CSV rows ---------------------------------------------------------------------------

//! The fields of one line, split at commas and whitespace.
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t at = 0;
  while (at < line.size()) {
    while (at < line.size() && (line[at] == ',' || std::isspace(static_cast<unsigned char>(line[at])))) ++at;
    const std::size_t start = at;
    while (at < line.size() && line[at] != ',' && !std::isspace(static_cast<unsigned char>(line[at]))) ++at;
    if (at > start) fields.push_back(line.substr(start, at - start));
  }
  return fields;
}

std::vector<Vec3> parse_point_rows(std::string_view text, const std::string& name) {
  std::array<std::size_t, 3> column{0, 1, 2};
  std::vector<Vec3> points;
  bool first = true;
  std::size_t line_number = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    const std::vector<std::string_view> fields = fields_of(line);
    if (fields.empty() || fields[0].front() == '#') continue;
    double value;
    if (first && !parse_double(fields[0], value)) {
      // A header: its x, y and z columns hold the point (dla3d's own CSV reads back).
      column.fill(fields.size());
      for (std::size_t f = 0; f < fields.size(); ++f) {
        const std::string word = lower(fields[f]);
        if (word.size() == 1 && word[0] >= 'x' && word[0] <= 'z') column[static_cast<std::size_t>(word[0] - 'x')] = f;
      }
      if (*std::max_element(column.begin(), column.end()) == fields.size())
        malformed(name, "line 1 is a header without x, y and z columns");
      first = false;
      continue;
    }
    first = false;
    const std::string where = "line " + std::to_string(line_number);
    Vec3 p;
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t f = column[static_cast<std::size_t>(axis)];
      if (f >= fields.size()) malformed(name, where + " has fewer than " + std::to_string(f + 1) + " fields");
      if (!parse_double(fields[f], p[axis]) || !std::isfinite(p[axis]))
        malformed(name, where + ": '" + std::string(fields[f].substr(0, 40)) + "' is not a finite number");
    }
    points.push_back(p);
  }
  return points;
}

}  // namespace

TriangleMesh parse_mesh(std::string_view bytes, std::string_view extension, const std::string& name) {
  const std::string format = lower(extension);
  if (bytes.empty()) malformed(name, "is empty");
  if (format == "stl") return parse_stl(bytes, name);
  if (format == "off") return parse_off(bytes, name);
  if (format == "obj") return parse_obj(bytes, name);
  if (format == "ply") return parse_ply(bytes, name);
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
  const std::string format = lower(extension);
  if (format != "ply" && format != "csv" && format != "txt" && format != "xyz")
    throw InvalidInput(name + ": unknown point file format '" + std::string(extension.substr(0, 40)) +
                       "' (use .csv, .txt, .xyz or .ply)");
  if (bytes.empty()) malformed(name, "is empty");
  std::vector<Vec3> points = format == "ply" ? parse_ply(bytes, name, true).vertices : parse_point_rows(bytes, name);
  if (points.empty()) malformed(name, "holds no points");
  return points;
}

std::vector<Vec3> read_points(const std::string& path) {
  return parse_points(read_input_file(path, ""), extension_of(path), path);
}

void write_stl(const TriangleMesh& mesh, const std::string& path) {
  detail::OutputFile out(path);
  char header[80] = {};
  std::snprintf(header, sizeof header, "binary STL written by dla3d, %zu triangles", mesh.triangles.size());
  out << std::string_view(header, sizeof header);
  const auto u32 = [&](std::uint32_t v) {
    const char b[4] = {char(v & 0xff), char(v >> 8 & 0xff), char(v >> 16 & 0xff), char(v >> 24 & 0xff)};
    out << std::string_view(b, 4);
  };
  const auto f32 = [&](double v) {
    const float f = static_cast<float>(v);
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    u32(bits);
  };
  u32(static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    for (int i = 0; i < 3; ++i) f32(n.allFinite() ? n[i] : 0.0);
    for (const Vec3* v : {&a, &b, &c})
      for (int i = 0; i < 3; ++i) f32((*v)[i]);
    out << std::string_view("\0\0", 2);
  }
  out.commit();
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
