#include "dla/io/csv_reader.h"

#include "dla/core/input_file.h"

#include "dla/io/csv_writer.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

namespace dla {

namespace {

//! The first six numbers of a row of `columns` comma-separated fields (the columns after the
//! sixth, a look's attributes, are not read), or false if the row is not that.
bool parse_row(std::string_view line, std::array<double, 6>& values, std::size_t columns) {
  std::size_t field = 0;
  for (;;) {
    const std::size_t comma = line.find(',');
    const std::string_view item = line.substr(0, comma);
    if (field == columns || item.empty()) return false;
    if (field < values.size()) {
      const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), values[field]);
      if (error != std::errc() || end != item.data() + item.size()) return false;
    }
    ++field;
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  return field == columns;
}

//! The first line of `text`, without its line end (\n or \r\n), taken off `text`.
std::string_view next_line(std::string_view& text) {
  const std::size_t end = text.find('\n');
  std::string_view line = text.substr(0, end);
  text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

}  // namespace

Cluster parse_csv(std::string_view text, const std::string& name) {
  const std::string_view header = next_line(text);
  if (header != "id,x,y,z,parent,seed" && header.rfind("id,x,y,z,parent,seed,", 0) != 0)
    throw InvalidInput(name + ": is not a dla3d CSV (no 'id,x,y,z,parent,seed' header)");
  const auto columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  Cluster cluster;
  cluster.dimensions = 2;
  std::vector<double> lengths;
  for (std::size_t row = 2; !text.empty(); ++row) {
    const std::string_view line = next_line(text);
    if (line.empty()) continue;
    std::array<double, 6> v{};
    if (!parse_row(line, v, columns))
      throw InvalidInput(name + ": line " + std::to_string(row) + " is not " + std::to_string(columns) +
                         " fields, the first 6 numbers");
    const auto index = static_cast<double>(cluster.particles.size());
    const Vec3 position(v[1], v[2], v[3]);
    // Compared as doubles before any conversion: a parent of 1e300 is refused, not cast.
    const bool seed = v[4] == -1.0;
    const bool parent_ok = seed || (v[4] >= 0.0 && v[4] < index && v[4] == std::floor(v[4]));
    const bool seed_ok = v[5] >= 0.0 && v[5] <= index && v[5] == std::floor(v[5]);
    if (v[0] != index || !parent_ok || !seed_ok || !position.allFinite())
      throw InvalidInput(name + ": line " + std::to_string(row) + " is not a particle after the ones before it");
    Particle p{position, static_cast<std::int32_t>(v[4]), static_cast<std::int32_t>(v[5])};
    if (seed) {
      ++cluster.seed_count;
    } else {
      lengths.push_back((p.position - cluster.particles[static_cast<std::size_t>(p.parent)].position).norm());
    }
    if (p.position.z() != 0.0) cluster.dimensions = 3;
    cluster.particles.push_back(p);
  }
  if (lengths.empty()) throw InvalidInput(name + ": has no branches to measure");
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  cluster.spacing = lengths[lengths.size() / 2];
  if (!(cluster.spacing > 0.0 && std::isfinite(cluster.spacing)))
    throw InvalidInput(name + ": its median branch length is " + detail::format_number(cluster.spacing) +
                       ", not a positive number");
  return cluster;
}

void parse_links_csv(std::string_view text, const std::string& name, Cluster& cluster) {
  if (next_line(text) != "a,b") throw InvalidInput(name + ": is not a dla3d links CSV (no 'a,b' header)");
  const auto count = static_cast<double>(cluster.particles.size());
  cluster.links.clear();
  for (std::size_t row = 2; !text.empty(); ++row) {
    const std::string_view line = next_line(text);
    if (line.empty()) continue;
    std::array<double, 6> v{};
    if (!parse_row(line, v, 2) || !(v[0] >= 0.0 && v[0] < v[1] && v[1] < count) || v[0] != std::floor(v[0]) ||
        v[1] != std::floor(v[1]))
      throw InvalidInput(name + ": line " + std::to_string(row) + " is not two particles a,b with a below b");
    cluster.links.push_back({static_cast<std::int32_t>(v[0]), static_cast<std::int32_t>(v[1])});
  }
  std::stable_sort(cluster.links.begin(), cluster.links.end(), [](const Link& a, const Link& b) { return a.later < b.later; });
}

bool is_sphere_list(std::string_view text) { return next_line(text) == "x,y,z,r"; }

SphereList parse_sphere_list(std::string_view text, const std::string& name) {
  if (!is_sphere_list(text)) throw InvalidInput(name + ": is not a sphere list (no 'x,y,z,r' header)");
  next_line(text);
  SphereList spheres;
  for (std::size_t row = 2; !text.empty(); ++row) {
    const std::string_view line = next_line(text);
    if (line.empty()) continue;
    std::array<double, 6> v{};
    if (!parse_row(line, v, 4) || !Vec3(v[0], v[1], v[2]).allFinite() || !(v[3] > 0.0 && std::isfinite(v[3])))
      throw InvalidInput(name + ": line " + std::to_string(row) + " is not a sphere x,y,z,r with r above 0");
    spheres.centres.emplace_back(v[0], v[1], v[2]);
    spheres.radii.push_back(v[3]);
  }
  if (spheres.centres.empty()) throw InvalidInput(name + ": has no spheres");
  return spheres;
}

Cluster read_csv(const std::string& path) {
  Cluster cluster = parse_csv(read_input_file(path, ""), path);
  const std::string links = links_csv_path(path);
  if (std::ifstream(links).good()) parse_links_csv(read_input_file(links, ""), links, cluster);
  return cluster;
}

}  // namespace dla
