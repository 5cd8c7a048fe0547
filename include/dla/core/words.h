#pragma once
//! \file words.h
//! Every mode (an `enum class`) has one table of the words that the CLI, Python, the files and
//! the option description spell it with. `to_string`, `parse_word` and a front end's list of
//! choices all read that table, so a mode's words are written once.
//!
//! A mode declares its table beside itself and a `words_of` that ADL finds:
//! \code
//! enum class Axis { x, y, z };
//! inline constexpr WordTable<Axis, 3> kAxisWords{"axis", {{{Axis::x, "x"}, {Axis::y, "y"}, {Axis::z, "z"}}}};
//! constexpr const auto& words_of(Axis) { return kAxisWords; }
//! \endcode

#include "dla/core/errors.h"

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace dla {

template <class Enum>
struct Word {
  Enum value;
  std::string_view word;
};

//! A mode's words, in the order `--help` and the front ends list them.
template <class Enum, std::size_t N>
struct WordTable {
  std::string_view what;  //!< how a refusal names the mode: "spawn mode 'x' is not one of ..."
  std::array<Word<Enum>, N> words;
};

namespace detail {
template <class Enum, class = void>
struct HasWords : std::false_type {};
template <class Enum>
struct HasWords<Enum, std::void_t<decltype(words_of(Enum{}))>> : std::true_type {};
}  // namespace detail

//! Whether `Enum` is a mode with a table of words.
template <class Enum>
inline constexpr bool has_words = std::is_enum_v<Enum> && detail::HasWords<Enum>::value;

//! The word for a mode's value, as the CLI spells it.
template <class Enum, std::enable_if_t<has_words<Enum>, int> = 0>
constexpr std::string_view to_string(Enum value) {
  for (const Word<Enum>& w : words_of(value).words)
    if (w.value == value) return w.word;
  return "?";
}

//! A mode's words, in the table's order.
template <class Enum, std::enable_if_t<has_words<Enum>, int> = 0>
std::vector<std::string_view> words_list() {
  std::vector<std::string_view> list;
  for (const Word<Enum>& w : words_of(Enum{}).words) list.push_back(w.word);
  return list;
}

//! "a, b, c": the words a refusal lists.
template <class Enum, std::enable_if_t<has_words<Enum>, int> = 0>
std::string accepted_words() {
  std::string accepted;
  for (const Word<Enum>& w : words_of(Enum{}).words) accepted += (accepted.empty() ? "" : ", ") + std::string(w.word);
  return accepted;
}

//! The value a word names; throws InvalidInput "WHAT 'word' is not one of a, b, c".
template <class Enum, std::enable_if_t<has_words<Enum>, int> = 0>
Enum parse_word(std::string_view word) {
  for (const Word<Enum>& w : words_of(Enum{}).words)
    if (w.word == word) return w.value;
  throw InvalidInput(std::string(words_of(Enum{}).what) + " '" + std::string(word) + "' is not one of " +
                     accepted_words<Enum>());
}

}  // namespace dla
