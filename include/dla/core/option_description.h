#pragma once
//! \file option_description.h
//! One description of each option, beside its options struct: its name, kind, default, range,
//! unit, group and help, written once. The library validates by it; the CLI adds its options
//! from it, Python reads its keywords by it, and `dla3d options` hands it to the studio and the
//! Blender add-on (docs/dev/architecture.md#options-described-once).
//!
//! \code
//! inline const OptionTable<BreakdownOptions> kBreakdownOptionTable{
//!     real("eta", &BreakdownOptions::eta, closed(0, 10), "", "Discharge", "the field's exponent"),
//!     word("field", &BreakdownOptions::field, "Discharge", "how the field is measured"),
//! };
//! \endcode

#include "dla/core/errors.h"
#include "dla/core/words.h"

#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace dla {

//! What an option's value is.
enum class OptionKind {
  flag,     //!< on or off
  integer,  //!< a whole number
  real,     //!< a number
  word,     //!< one word of a mode's table
};
inline constexpr WordTable<OptionKind, 4> kOptionKindWords{
    "option kind", {{{OptionKind::flag, "flag"}, {OptionKind::integer, "integer"}, {OptionKind::real, "real"},
                     {OptionKind::word, "word"}}}};
constexpr const auto& words_of(OptionKind) { return kOptionKindWords; }

//! The numbers an option takes: from min to max, each end closed (taken) or open (not).
struct Range {
  double min = 0.0, max = 0.0;
  bool min_open = false, max_open = false;

  constexpr bool contains(double value) const {  // NaN never is
    return (min_open ? value > min : value >= min) && (max_open ? value < max : value <= max);
  }
};

constexpr Range closed(double min, double max) { return {min, max, false, false}; }
//! (min, max]
constexpr Range open_closed(double min, double max) { return {min, max, true, false}; }

namespace detail {
//! A number as messages and the help write it: "%g".
inline std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}
}  // namespace detail

//! "[0, 10]", "(0, 1]": as the refusals and the help write a range.
inline std::string to_string(const Range& range) {
  return std::string(range.min_open ? "(" : "[") + detail::format_number(range.min) + ", " +
         detail::format_number(range.max) + (range.max_open ? ")" : "]");
}

//! An option's name as the CLI spells it: `stop_at_strike` is --stop-at-strike (spell_options()).
inline std::string cli_flag(std::string_view name) {
  std::string flag = "--";
  for (const char c : name) flag += c == '_' ? '-' : c;
  return flag;
}

//! A value outside the range that means something of its own: walkers 0, "chosen by eta".
struct SpecialValue {
  double value;
  std::string_view means;
};

//! An option as every front end describes it.
struct OptionDescription {
  std::string_view name;   //!< as C++ and Python spell it (`stop_at_strike`); the CLI: --stop-at-strike
  OptionKind kind;
  std::string_view group;  //!< the heading `--help` and the studio put it under
  std::string_view help;   //!< what it does, one phrase; the range and unit are added from below
  std::optional<Range> range;           //!< integer, real: the values taken
  std::optional<SpecialValue> special;  //!< integer, real: a value outside the range
  std::string_view unit;                //!< integer, real: "spacings", "degrees"; empty: none
  std::vector<std::string_view> choices;  //!< word: the mode's words, in its table's order
  std::string_view negation;              //!< flag: the name that turns it off; empty: none
  std::string_view short_name;            //!< the CLI's one-letter name: "n" for -n; empty: none
};

//! A value of an option, as a front end hands it over.
using OptionValue = std::variant<bool, std::int64_t, double, std::string>;

//! An option's description bound to the member of `Options` it sets.
template <class Options>
struct DescribedOption {
  OptionDescription about;
  //! Sets the member, checking the value against the description first (a word: parsed).
  std::function<void(Options&, const OptionValue&)> set;
  //! The member's value: of a default-made Options, the option's default.
  std::function<OptionValue(const Options&)> get;
};

template <class Options>
using OptionTable = std::vector<DescribedOption<Options>>;

//! The value as the CLI writes it: "1", "0.25", "walkers", "true".
inline std::string to_string(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return detail::format_number(*d);
  return std::get<std::string>(value);
}

//! Throws InvalidInput "`eta` 11 is not in [0, 10]" unless `value` is in the option's range or
//! is its special value.
//! `shown` is the value as the message writes it (default "%g"; a whole number exactly).
inline void require_in(const OptionDescription& about, double value, const std::string& shown = {}) {
  if (!about.range || about.range->contains(value) || (about.special && value == about.special->value)) return;
  std::string message = "`" + std::string(about.name) + "` " + (shown.empty() ? detail::format_number(value) : shown) +
                        " is not in " + to_string(*about.range);
  if (about.special)
    message += " (" + detail::format_number(about.special->value) + ": " + std::string(about.special->means) + ")";
  throw InvalidInput(message);
}

//! Checks every number of `options` against its description: the one place a range is held.
template <class Options>
void require_in_ranges(const OptionTable<Options>& table, const Options& options) {
  for (const DescribedOption<Options>& option : table) {
    const OptionValue value = option.get(options);
    if (const double* d = std::get_if<double>(&value)) require_in(option.about, *d);
    if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) require_in(option.about, static_cast<double>(*i));
  }
}

//! The option named `name` in `table`; null if it has none.
template <class Options>
const DescribedOption<Options>* find_option(const OptionTable<Options>& table, std::string_view name) {
  for (const DescribedOption<Options>& option : table)
    if (option.about.name == name) return &option;
  return nullptr;
}

namespace detail {
//! The number in `value`, which a front end gave for option `name` of this kind.
inline double number_of(std::string_view name, const OptionValue& value) {
  if (const double* d = std::get_if<double>(&value)) return *d;
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return static_cast<double>(*i);
  throw InvalidInput("`" + std::string(name) + "` " + to_string(value) + " is not a number");
}
}  // namespace detail

//! A number in `range` (`unit` as the help names it), in a member of type double.
template <class Options>
DescribedOption<Options> real(std::string_view name, double Options::*member, Range range, std::string_view unit,
                              std::string_view group, std::string_view help,
                              std::optional<SpecialValue> special = std::nullopt) {
  OptionDescription about{name, OptionKind::real, group, help, range, special, unit, {}, {}, {}};
  return {about,
          [about, member](Options& o, const OptionValue& v) {
            const double value = detail::number_of(about.name, v);
            require_in(about, value);
            o.*member = value;
          },
          [member](const Options& o) { return OptionValue(o.*member); }};
}

//! A whole number in `range`, in a member of an integer type (int, std::size_t); the range
//! keeps the value within what the type holds.
template <class Options, class Whole, std::enable_if_t<std::is_integral_v<Whole> && !std::is_same_v<Whole, bool>, int> = 0>
DescribedOption<Options> integer(std::string_view name, Whole Options::*member, Range range, std::string_view unit,
                                 std::string_view group, std::string_view help,
                                 std::optional<SpecialValue> special = std::nullopt) {
  OptionDescription about{name, OptionKind::integer, group, help, range, special, unit, {}, {}, {}};
  return {about,
          [about, member](Options& o, const OptionValue& v) {
            const double value = detail::number_of(about.name, v);
            require_in(about, value, to_string(v));  // first: the range keeps the casts below defined
            if (value != static_cast<double>(static_cast<std::int64_t>(value)))
              throw InvalidInput("`" + std::string(about.name) + "` " + to_string(v) + " is not a whole number");
            o.*member = static_cast<Whole>(value);
          },
          [member](const Options& o) { return OptionValue(static_cast<std::int64_t>(o.*member)); }};
}

//! One word of the mode `Mode`'s table, in a member of that type.
template <class Options, class Mode, std::enable_if_t<has_words<Mode>, int> = 0>
DescribedOption<Options> word(std::string_view name, Mode Options::*member, std::string_view group,
                              std::string_view help) {
  OptionDescription about{name, OptionKind::word, group, help, {}, {}, {}, words_list<Mode>(), {}, {}};
  return {about,
          [about, member](Options& o, const OptionValue& v) {
            const std::string* text = std::get_if<std::string>(&v);
            if (!text) throw InvalidInput("`" + std::string(about.name) + "` " + to_string(v) + " is not a word");
            try {
              o.*member = parse_word<Mode>(*text);
            } catch (const InvalidInput&) {
              throw InvalidInput("`" + std::string(about.name) + "` '" + *text + "' is not one of " +
                                 accepted_words<Mode>());
            }
          },
          [member](const Options& o) { return OptionValue(std::string(to_string(o.*member))); }};
}

//! On or off, in a member of type bool; `negation` names the option that turns it off.
template <class Options>
DescribedOption<Options> flag(std::string_view name, bool Options::*member, std::string_view group,
                              std::string_view help, std::string_view negation = {}) {
  OptionDescription about{name, OptionKind::flag, group, help, {}, {}, {}, {}, negation, {}};
  return {about,
          [about, member](Options& o, const OptionValue& v) {
            const bool* on = std::get_if<bool>(&v);
            if (!on) throw InvalidInput("`" + std::string(about.name) + "` " + to_string(v) + " is not True or False");
            o.*member = *on;
          },
          [member](const Options& o) { return OptionValue(o.*member); }};
}

//! `row` with the CLI's one-letter name `letter` as well: -n for --monomers.
template <class Options>
DescribedOption<Options> with_short_name(DescribedOption<Options> row, std::string_view letter) {
  row.about.short_name = letter;
  return row;
}

//! The options of `table`, which describes a part of `Outer` (a member, or a base), as options
//! of `Outer`: DLA's walk options as options of a DLA run.
template <class Outer, class Inner>
OptionTable<Outer> nested(const OptionTable<Inner>& table, Inner Outer::*part) {
  OptionTable<Outer> out;
  for (const DescribedOption<Inner>& row : table)
    out.push_back({row.about, [set = row.set, part](Outer& o, const OptionValue& v) { set(o.*part, v); },
                   [get = row.get, part](const Outer& o) { return get(o.*part); }});
  return out;
}

namespace detail {
//! A value an option's row gave back, as the member's type: a number, or a mode's word parsed.
template <class Value>
Value value_as(const OptionValue& value) {
  if constexpr (has_words<Value>) return parse_word<Value>(std::get<std::string>(value));
  else return static_cast<Value>(std::get<double>(value));
}
}  // namespace detail

//! `row`, which describes a member of `Inner`, as an option of `Outer` that sets `member`: a
//! value left unset unless given, because another input (a mesh) gives its default then.
//! Checked as `row` checks it; unset, it shows `Inner`'s default.
template <class Outer, class Inner, class Value>
DescribedOption<Outer> override_of(const DescribedOption<Inner>& row, std::optional<Value> Outer::*member) {
  return {row.about,
          [row, member](Outer& o, const OptionValue& v) {
            Inner scratch;
            row.set(scratch, v);
            o.*member = detail::value_as<Value>(row.get(scratch));
          },
          [row, member](const Outer& o) {
            if (!(o.*member)) return row.get(Inner{});
            if constexpr (has_words<Value>) return OptionValue(std::string(to_string(*(o.*member))));
            else return OptionValue(static_cast<double>(*(o.*member)));
          }};
}

}  // namespace dla
