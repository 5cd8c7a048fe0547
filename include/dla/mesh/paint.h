#pragma once
//! \file paint.h
//! A colour painted on a mesh's vertices, which marks where seeds go (`--seed-paint
//! COLOR[,TOLERANCE]`). Colours blend across each triangle, as a renderer shows them; the
//! painted part is where the blend is within the tolerance of the colour. See
//! docs/constraints.md#painted-seeds.

#include "dla/core/options.h"

#include <cctype>
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
};

//! "red", "ff0000", "#ff0000", with ",TOLERANCE" after it or not. Throws InvalidInput.
inline Paint parse_paint(std::string_view text) {
  static const std::pair<const char*, Vec3> names[] = {
      {"red", {1, 0, 0}},   {"green", {0, 1, 0}},   {"blue", {0, 0, 1}},  {"yellow", {1, 1, 0}},
      {"cyan", {0, 1, 1}},  {"magenta", {1, 0, 1}}, {"white", {1, 1, 1}}, {"black", {0, 0, 0}}};
  const std::string whole(text);
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
      throw InvalidInput("`seed_paint` '" + whole + "': the colour is not a name (red, green, blue, yellow, cyan, "
                         "magenta, white, black) nor six hex digits as ff8000");
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
      throw InvalidInput("`seed_paint` '" + whole + "': the tolerance '" + tolerance + "' is not a number");
    if (!(paint.tolerance >= 0.0 && paint.tolerance < 1.0))
      throw InvalidInput("`seed_paint`'s tolerance " + detail::format_number(paint.tolerance) +
                         " is not in [0, 1): a channel's difference, 0 to 1");
  }
  return paint;
}

}  // namespace dla
