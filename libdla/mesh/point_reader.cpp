// Point rows (CSV, TXT, XYZ): the reader behind read_points() (mesh_readers.h).

#include "mesh_readers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace dla::detail {

namespace {

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

}  // namespace

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

}  // namespace dla::detail
