#pragma once
//! \file paint.h
//! A colour painted on a mesh's vertices, which marks where seeds go (`--seed-paint
//! COLOR[,TOLERANCE]`) and where leaves do not (`--tips-exclude-paint`). Colours blend across
//! each triangle, as a renderer shows them; the painted part is where the blend is within the
//! tolerance of the colour. See docs/constraints.md#painted-seeds.

#include "dla/core/options.h"
#include "dla/mesh/mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <utility>

namespace dla {

struct Paint {
  Vec3 color = Vec3(1.0, 0.0, 0.0);  //!< red, green and blue in [0, 1]
  //! The largest difference in any channel, in [0, 1): 0.3 takes in a stroke's soft edge and
  //! keeps out its neighbours' colours.
  double tolerance = 0.3;

  bool matches(const Vec3& rgb) const { return (rgb - color).cwiseAbs().maxCoeff() <= tolerance; }
  //! Whether a blend of these three colours may match.
  bool may_match(const Vec3& a, const Vec3& b, const Vec3& c) const {
    const Vec3 low = a.cwiseMin(b).cwiseMin(c), high = a.cwiseMax(b).cwiseMax(c);
    return !((low.array() > color.array() + tolerance).any() || (high.array() < color.array() - tolerance).any());
  }
};

//! The colour a renderer shows at point p of triangle t of a coloured mesh: its corners'
//! colours blended by p's barycentric coordinates (a degenerate triangle: their mean).
inline Vec3 paint_at(const TriangleMesh& mesh, std::uint32_t t, const Vec3& p) {
  const auto& tri = mesh.triangles[t];
  const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
  const Vec3 &ca = mesh.colors[tri[0]], &cb = mesh.colors[tri[1]], &cc = mesh.colors[tri[2]];
  const Vec3 e0 = b - a, e1 = c - a, e2 = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = e2.dot(e0), d21 = e2.dot(e1);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(denominator > 1e-300)) return (ca + cb + cc) / 3.0;
  const double v = std::clamp((d11 * d20 - d01 * d21) / denominator, 0.0, 1.0);
  const double w = std::clamp((d00 * d21 - d01 * d20) / denominator, 0.0, 1.0 - v);
  return (1.0 - v - w) * ca + v * cb + w * cc;
}

//! "ff8000": a colour of channels in [0, 1] as six hex digits, each channel rounded to 8 bits.
inline std::string hex_digits(const Vec3& rgb) {
  char text[8];
  std::snprintf(text, sizeof text, "%02x%02x%02x", static_cast<int>(std::lround(255 * rgb[0])),
                static_cast<int>(std::lround(255 * rgb[1])), static_cast<int>(std::lround(255 * rgb[2])));
  return text;
}

//! "ff8000,0.3": the words parse_paint() reads back.
inline std::string to_string(const Paint& paint) {
  return hex_digits(paint.color) + "," + detail::format_number(paint.tolerance);
}

//! "red", "ff0000", "#ff0000", with ",TOLERANCE" after it or not. Throws InvalidInput naming
//! `option`, the option it was given for.
inline Paint parse_paint(std::string_view text, const char* option = "seed_paint") {
  static const std::pair<const char*, Vec3> names[] = {
      {"red", {1, 0, 0}},   {"green", {0, 1, 0}},   {"blue", {0, 0, 1}},  {"yellow", {1, 1, 0}},
      {"cyan", {0, 1, 1}},  {"magenta", {1, 0, 1}}, {"white", {1, 1, 1}}, {"black", {0, 0, 0}}};
  const std::string whole(text), name = "`" + std::string(option) + "`";
  const std::size_t comma = text.find(',');
  std::string_view word = text.substr(0, comma);
  Paint paint;
  bool named = false;
  for (const auto& [name, rgb] : names)
    if (word == name) {
      paint.color = rgb;
      named = true;
    }
  if (!named) {
    if (!word.empty() && word.front() == '#') word.remove_prefix(1);
    bool hex = word.size() == 6;
    for (const char c : word) hex = hex && std::isxdigit(static_cast<unsigned char>(c));
    if (!hex)
      throw InvalidInput(name + " '" + whole + "': the colour is not a name (red, green, blue, yellow, cyan, magenta, "
                         "white, black) nor six hex digits as ff8000");
    for (int c = 0; c < 3; ++c)
      paint.color[c] = std::stoi(std::string(word.substr(2 * static_cast<std::size_t>(c), 2)), nullptr, 16) / 255.0;
  }
  if (comma != std::string_view::npos) {
    const std::string tolerance(text.substr(comma + 1));
    std::size_t end = 0;
    try {
      paint.tolerance = std::stod(tolerance, &end);
    } catch (const std::exception&) {
      end = 0;
    }
    if (end == 0 || end != tolerance.size())
      throw InvalidInput(name + " '" + whole + "': the tolerance '" + tolerance + "' is not a number");
    if (!(paint.tolerance >= 0.0 && paint.tolerance < 1.0))
      throw InvalidInput(name + "'s tolerance " + detail::format_number(paint.tolerance) +
                         " is not in [0, 1): a channel's difference, 0 to 1");
  }
  return paint;
}

//! A colour of a mesh's paint, with its tolerance (`--seed-paint ff8000,0.3`), in a member of
//! type std::optional<Paint> (unset: "").
template <class Options>
DescribedOption<Options> colour(std::string_view name, std::optional<Paint> Options::*member, std::string_view group,
                                std::string_view help) {
  return parsed<Options>(
      name, OptionKind::colour, "COLOR[,TOLERANCE]", group, help,
      [name, member](Options& o, const std::string& words) {
        o.*member = words.empty() ? std::nullopt : std::optional<Paint>(parse_paint(words, name.data()));
      },
      [member](const Options& o) { return o.*member ? to_string(*(o.*member)) : std::string(); });
}

}  // namespace dla
