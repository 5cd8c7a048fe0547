#pragma once
//! \file json.h
//! The two pieces of JSON that dla3d's writers need beyond plain text: a string escaped so that
//! any bytes (a path with quotes, a command line with a newline) stay one valid string, and a
//! number that is `null` rather than the invalid `nan` or `inf`.

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace dla::json {

//! `text` as a JSON string literal, quotes included.
inline std::string string(std::string_view text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned char>(c));
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + '"';
}

//! The shortest form that reads back to `value` (or `digits` significant digits), `null` if
//! it is not finite.
inline std::string number(double value, int digits = 0) {
  if (!std::isfinite(value)) return "null";
  char text[40];
  const auto end = digits > 0 ? std::to_chars(text, text + sizeof text, value, std::chars_format::general, digits)
                              : std::to_chars(text, text + sizeof text, value);
  return std::string(text, end.ptr);
}

}  // namespace dla::json
