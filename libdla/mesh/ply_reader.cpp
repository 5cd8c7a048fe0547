// PLY, ASCII or binary: the reader behind read_mesh() for .ply and read_points() (mesh_readers.h).

#include "mesh_readers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace dla::detail {

namespace {

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

}  // namespace

TriangleMesh parse_ply(std::string_view bytes, const std::string& name, bool points_only) {
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

}  // namespace dla::detail
