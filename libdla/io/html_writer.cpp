#include "dla/io/html_writer.h"

#include "dla/io/json.h"
#include "dla/look/color_map.h"
#include "dla/version.h"
#include "output_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla {

namespace detail {
// viewer/viewer.js bundled with three.js, as parts of text: generated at build time
// (cmake/web_viewer.cmake); none in a build without npm.
extern const char* const kViewerScriptParts[];
extern const std::size_t kViewerScriptPartCount;
}  // namespace detail

namespace {

//! Appends `bytes` as base64.
void base64(detail::Text& out, const void* data, std::size_t size) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v = bytes[i] << 16 | bytes[i + 1] << 8 | bytes[i + 2];
    out << kDigits[v >> 18] << kDigits[(v >> 12) & 63] << kDigits[(v >> 6) & 63] << kDigits[v & 63];
  }
  if (i < size) {
    const std::uint32_t v = bytes[i] << 16 | (i + 1 < size ? bytes[i + 1] << 8 : 0);
    out << kDigits[v >> 18] << kDigits[(v >> 12) & 63] << (i + 1 < size ? kDigits[(v >> 6) & 63] : '=') << '=';
  }
}

template <class T>
void block(detail::Text& out, const char* id, const std::vector<T>& values) {
  out << "<script type=\"application/octet-stream\" id=\"" << id << "\">";
  base64(out, values.data(), values.size() * sizeof(T));
  out << "</script>\n";
}

//! Text for HTML between tags or in a quoted attribute.
std::string escaped(const std::string& text) {
  std::string safe;
  for (const char c : text) {
    switch (c) {
      case '&': safe += "&amp;"; break;
      case '<': safe += "&lt;"; break;
      case '>': safe += "&gt;"; break;
      case '"': safe += "&quot;"; break;
      default: safe += c;
    }
  }
  return safe;
}

//! Where the camera starts, from the centre: in front, a little from the side and above, as in
//! the POV-Ray scene (whose axes are left-handed; three.js', like the files', right-handed).
std::array<double, 3> view_direction(int dimensions, Axis up) {
  if (dimensions == 2) return {0, 0, 1};
  if (up == Axis::z) return {0.35, -1, 0.45};
  if (up == Axis::x) return {0.45, 0.35, 1};
  return {0.35, 0.45, 1};
}

constexpr const char* kStyle =
    "html, body { margin: 0; height: 100%; overflow: hidden; background: #0a0d12; "
    "font: 14px system-ui, sans-serif; color: #dde; }\n"
    "canvas { display: block; }\n"
    "#dla-panel { position: fixed; left: 0; right: 0; bottom: 0; display: flex; gap: 12px; align-items: center; "
    "padding: 8px 12px; background: rgba(10, 13, 18, 0.8); }\n"
    "#dla-show { flex: 1; }\n"
    "#dla-count { min-width: 16em; font-variant-numeric: tabular-nums; }\n";

}  // namespace

bool has_web_viewer() { return detail::kViewerScriptPartCount > 0; }

void write_html(const Cluster& cluster, const Look& look, const std::string& path, const HtmlOptions& options,
                const TriangleMesh* mesh) {
  if (!has_web_viewer())
    throw InvalidInput("`formats` html: this dla3d was built without npm, which fetches the web viewer's three.js; "
                       "install npm and build again");
  const auto& ps = cluster.particles;
  const std::size_t n = ps.size();
  // Relative to the box's centre and in spacings, so that float32 holds any spacing and place.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Particle& p : ps) lo = lo.cwiseMin(p.position), hi = hi.cwiseMax(p.position);
  const Vec3 center = n ? Vec3(0.5 * (lo + hi)) : Vec3::Zero();
  const auto local = [&](const Vec3& p, std::vector<float>& to) {
    for (int k = 0; k < 3; ++k) to.push_back(static_cast<float>((p[k] - center[k]) / cluster.spacing));
  };
  std::vector<float> positions;
  std::vector<std::int32_t> parents;
  positions.reserve(3 * n);
  parents.reserve(n);
  for (const Particle& p : ps) {
    local(p.position, positions);
    parents.push_back(p.parent);
  }
  const std::vector<float> radii = look.radii;
  // A byte a particle for each colour attribute; distance only where it means something.
  std::vector<ColorBy> colorings = {ColorBy::age, ColorBy::depth, ColorBy::seed, ColorBy::distance};
  if (!look.attributes.channel.empty() || look.options.color_by == ColorBy::current) colorings.push_back(ColorBy::current);
  std::vector<std::uint8_t> colors;
  colors.reserve(colorings.size() * n);
  {
    std::vector<ColorScale> scales;
    for (const ColorBy by : colorings) scales.emplace_back(cluster, look.attributes, by);
    for (std::size_t i = 0; i < n; ++i)
      for (const ColorScale& scale : scales) colors.push_back(static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(scale(i), 0.0, 1.0))));
  }

  // The links as (earlier, later) pairs in order of the later: the first k particles' links
  // are a prefix.
  std::vector<std::int32_t> links;
  links.reserve(2 * cluster.links.size());
  for (const Link& link : cluster.links) links.insert(links.end(), {link.earlier, link.later});

  std::string meta = "{\"particles\": " + std::to_string(n) + ", \"seeds\": " + std::to_string(cluster.seed_count) +
                     ", \"links\": " + std::to_string(cluster.links.size()) +
                     ", \"dimensions\": " + std::to_string(cluster.dimensions) + ", \"spacing\": " +
                     json::number(cluster.spacing) + ", \"up\": \"" + std::string(to_string(options.up)) +
                     "\", \"view\": [";
  const std::array<double, 3> view = view_direction(cluster.dimensions, options.up);
  meta += json::number(view[0]) + ", " + json::number(view[1]) + ", " + json::number(view[2]) + "], \"color_by\": \"" +
          std::string(to_string(look.options.color_by)) + "\", \"colorings\": [";
  for (std::size_t k = 0; k < colorings.size(); ++k)
    meta += (k ? ", \"" : "\"") + std::string(to_string(colorings[k])) + '"';
  meta += "], \"color_stops\": [";
  for (std::size_t k = 0; k < kColorStops.size(); ++k)
    meta += (k ? ", [" : "[") + json::number(kColorStops[k][0]) + ", " + json::number(kColorStops[k][1]) + ", " +
            json::number(kColorStops[k][2]) + ']';
  const RadiusOptions& radius = look.options.radius;
  meta += "], \"radius\": {\"model\": \"" + std::string(to_string(radius.model)) + "\", \"tip\": " +
          json::number(radius.tip_radius) + ", \"base\": " + json::number(radius.base_radius) + ", \"exponent\": " +
          json::number(radius.pipe_exponent) + "}, \"tube_limit\": " +
          std::to_string(options.tube_limit) + ", \"tube_default_limit\": " + std::to_string(options.tube_default_limit) +
          ", \"mesh\": " + (mesh && !mesh->triangles.empty() ? "true" : "false") + "}";
  // "</script>" inside the JSON would end its block: "<\/" reads back as "</".
  for (std::size_t at = meta.find("</"); at != std::string::npos; at = meta.find("</", at + 3)) meta.insert(at + 1, "\\");

  detail::OutputFile out(path);
  const std::string title = escaped(options.title.empty() ? "dla3d" : options.title);
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<meta name=\"generator\" content=\"dla3d " << version << "\">\n<title>" << title << "</title>\n<style>\n"
      << kStyle << "</style>\n</head>\n<body>\n"
         "<div id=\"dla-panel\">\n"
         "  <button id=\"dla-play\" title=\"replay the growth\">Play</button>\n"
         "  <input id=\"dla-show\" type=\"range\" min=\"0\" max=\"1000\" value=\"1000\" "
         "title=\"the particles attached so far, in attach order\">\n"
         "  <span id=\"dla-count\"></span>\n"
         "  <label>colour <select id=\"dla-color\"></select></label>\n"
         "  <label><input id=\"dla-tubes\" type=\"checkbox\"> tubes</label>\n"
         "  <label><input id=\"dla-mesh\" type=\"checkbox\"> mesh</label>\n"
         "</div>\n"
         "<script type=\"application/json\" id=\"dla-meta\">" << meta << "</script>\n";
  block(out, "dla-positions", positions);
  block(out, "dla-parents", parents);
  if (!links.empty()) block(out, "dla-links", links);
  block(out, "dla-radii", radii);
  block(out, "dla-colors", colors);
  if (mesh && !mesh->triangles.empty()) {
    std::vector<float> vertices;
    vertices.reserve(3 * mesh->vertices.size());
    for (const Vec3& v : mesh->vertices) local(v, vertices);
    std::vector<std::uint32_t> triangles;
    triangles.reserve(3 * mesh->triangles.size());
    for (const auto& t : mesh->triangles) triangles.insert(triangles.end(), t.begin(), t.end());
    block(out, "dla-mesh-vertices", vertices);
    block(out, "dla-mesh-triangles", triangles);
  }
  out << "<script>\n";
  for (std::size_t k = 0; k < detail::kViewerScriptPartCount; ++k) out << detail::kViewerScriptParts[k];
  out << "\n</script>\n</body>\n</html>\n";
  out.commit();
}

}  // namespace dla
