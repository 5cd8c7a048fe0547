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
  vector,   //!< a fixed count of numbers: "X,Y,Z", a box's two corners
  points,   //!< one point "X,Y,Z" a value, as many as given
  colour,   //!< a colour by name or hex digits, with a tolerance after it or not: "ff8000,0.3"
  text,     //!< words of a form of the option's own: "K|all", "D[,K]", "AXIS,DEGREES"
  file,     //!< a file's path
};
inline constexpr WordTable<OptionKind, 9> kOptionKindWords{
    "option kind", {{{OptionKind::flag, "flag"}, {OptionKind::integer, "integer"}, {OptionKind::real, "real"},
                     {OptionKind::word, "word"}, {OptionKind::vector, "vector"}, {OptionKind::points, "points"},
                     {OptionKind::colour, "colour"}, {OptionKind::text, "text"}, {OptionKind::file, "file"}}}};
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

//! The form of a file option that reads a mesh (`--stl MESH_FILE`): a front end may offer a mesh
//! of its own for it (the Blender add-on an object, Python arrays).
inline constexpr std::string_view kMeshFileForm = "MESH_FILE";

//! What a front end that paints may give an option: the studio's brushes on a mesh, and its
//! mask painter.
enum class PaintRole {
  seeds,       //!< colour: seeds on the part of the mesh painted it
  attractors,  //!< colour: attractors there
  bare,        //!< colour: no tips where the surface below is painted it
  mask,        //!< text: besides its words, a file of a mask drawn on the lattice
};
inline constexpr WordTable<PaintRole, 4> kPaintRoleWords{
    "paint role", {{{PaintRole::seeds, "seeds"}, {PaintRole::attractors, "attractors"}, {PaintRole::bare, "bare"},
                    {PaintRole::mask, "mask"}}}};
constexpr const auto& words_of(PaintRole) { return kPaintRoleWords; }

//! An option set to a value: what another option needs in order to act.
struct OptionSetting {
  std::string_view name, value;
};

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
  std::vector<std::string_view> choices;  //!< word: the mode's words; text: the words besides its form
  std::string_view negation;              //!< flag: the name that turns it off; empty: none
  std::string_view short_name;            //!< the CLI's one-letter name: "n" for -n; empty: none
  //! vector, points, colour, text, file: the value's form as --help shows it ("X,Y,Z",
  //! "COLOR[,TOLERANCE]", kMeshFileForm)
  std::string_view form = {};
  bool repeats = false;         //!< points, file: the option is given once a value, and keeps all
  std::string_view alias = {};  //!< another name for it, as C++ and Python spell it: `mesh` for `stl`
  //! Options it cannot go with (both place the seeds, both are the target): the CLI refuses
  //! the pair at once, and an option given beside a preset drops the preset's it excludes; the
  //! library's validate() refuses the pair for every front end.
  std::vector<std::string_view> excludes = {};
  //! What a front end's painting gives it; none: nothing.
  std::optional<PaintRole> paints = {};
  //! The value another option must have for this one to act (`attractor_paint`: `attractors_in`
  //! surface): a front end that sets this one for its user sets that one too.
  std::optional<OptionSetting> needs = {};
  //! It changes how fast a run goes, never its files (`threads`): a run resumed from a
  //! checkpoint may change it.
  bool speed_only = false;
};

//! A value of an option, as a front end hands it over.
//! A text-form option (vector, points, colour, text, file) takes its words as the CLI spells
//! them; one that repeats, the list of them.
using OptionValue = std::variant<bool, std::int64_t, double, std::string, std::vector<std::string>>;

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
  if (const std::string* text = std::get_if<std::string>(&value)) return *text;
  std::string list;
  for (const std::string& item : std::get<std::vector<std::string>>(value)) list += (list.empty() ? "" : "; ") + item;
  return list;
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
  OptionDescription about{name, OptionKind::real, group, help, range, special, unit, {}, {}, {}, {}, false, {}, {}, {}, {}, false};
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
  OptionDescription about{name, OptionKind::integer, group, help, range, special, unit, {}, {}, {}, {}, false, {}, {}, {}, {}, false};
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
  OptionDescription about{name, OptionKind::word, group, help, {}, {}, {}, words_list<Mode>(), {}, {}, {}, false, {}, {}, {}, {}, false};
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
  OptionDescription about{name, OptionKind::flag, group, help, {}, {}, {}, {}, negation, {}, {}, false, {}, {}, {}, {}, false};
  return {about,
          [about, member](Options& o, const OptionValue& v) {
            const bool* on = std::get_if<bool>(&v);
            if (!on) throw InvalidInput("`" + std::string(about.name) + "` " + to_string(v) + " is not True or False");
            o.*member = *on;
          },
          [member](const Options& o) { return OptionValue(o.*member); }};
}

namespace detail {
//! The words a front end gave for the text-form option `name`.
inline const std::string& words_given(std::string_view name, const OptionValue& value) {
  if (const std::string* text = std::get_if<std::string>(&value)) return *text;
  throw InvalidInput("`" + std::string(name) + "` " + to_string(value) + " is not " +
                     (std::holds_alternative<std::vector<std::string>>(value) ? "one value" : "text"));
}
}  // namespace detail

//! An option of `kind` vector, colour, text or file, whose words (of the form `form`) `parse`
//! reads into the options, throwing InvalidInput that names the option, and `print` writes
//! back from them: "" when unset.
template <class Options>
DescribedOption<Options> parsed(std::string_view name, OptionKind kind, std::string_view form, std::string_view group,
                                std::string_view help, std::function<void(Options&, const std::string&)> parse,
                                std::function<std::string(const Options&)> print) {
  OptionDescription about{name, kind, group, help, {}, {}, {}, {}, {}, {}, form, false, {}, {}, {}, {}, false};
  return {about, [about, parse](Options& o, const OptionValue& v) { parse(o, detail::words_given(about.name, v)); },
          [print](const Options& o) { return OptionValue(print(o)); }};
}

//! An option of `kind` points or file given once a value (`--seed-at 0,0,0 --seed-at 9,0,0`):
//! `parse` reads the list, `print` writes it back.
template <class Options>
DescribedOption<Options> repeated(std::string_view name, OptionKind kind, std::string_view form,
                                  std::string_view group, std::string_view help,
                                  std::function<void(Options&, const std::vector<std::string>&)> parse,
                                  std::function<std::vector<std::string>(const Options&)> print) {
  OptionDescription about{name, kind, group, help, {}, {}, {}, {}, {}, {}, form, true, {}, {}, {}, {}, false};
  return {about,
          [about, parse](Options& o, const OptionValue& v) {
            if (const auto* list = std::get_if<std::vector<std::string>>(&v)) parse(o, *list);
            else parse(o, {detail::words_given(about.name, v)});
          },
          [print](const Options& o) { return OptionValue(print(o)); }};
}

//! A file's path, in a member of type std::string ("" : none); `form` as --help shows it:
//! "FILE.glb", kMeshFileForm.
template <class Options>
DescribedOption<Options> file(std::string_view name, std::string Options::*member, std::string_view form,
                              std::string_view group, std::string_view help) {
  return parsed<Options>(
      name, OptionKind::file, form, group, help, [member](Options& o, const std::string& path) { o.*member = path; },
      [member](const Options& o) { return o.*member; });
}

//! `row` with the CLI's one-letter name `letter` as well: -n for --monomers.
template <class Options>
DescribedOption<Options> with_short_name(DescribedOption<Options> row, std::string_view letter) {
  row.about.short_name = letter;
  return row;
}

//! `row`, which cannot go with the options `names` (those described before it).
template <class Options>
DescribedOption<Options> excluding(DescribedOption<Options> row, std::vector<std::string_view> names) {
  row.about.excludes = std::move(names);
  return row;
}

//! `row`, whose value a front end's painting gives (the studio's seed brush: `seed_paint`).
template <class Options>
DescribedOption<Options> with_paint_role(DescribedOption<Options> row, PaintRole role) {
  row.about.paints = role;
  return row;
}

//! `row`, which acts only when the option `name` has `value`.
template <class Options>
DescribedOption<Options> needing(DescribedOption<Options> row, std::string_view name, std::string_view value) {
  row.about.needs = OptionSetting{name, value};
  return row;
}

//! `row`, which changes how fast a run goes and never its files.
template <class Options>
DescribedOption<Options> speed_only(DescribedOption<Options> row) {
  row.about.speed_only = true;
  return row;
}

//! `table` under the heading `group`: links among Eden's options.
template <class Options>
OptionTable<Options> in_group(OptionTable<Options> table, std::string_view group) {
  for (DescribedOption<Options>& row : table) row.about.group = group;
  return table;
}

//! `row` with another name as well: `mesh` for `stl` (--mesh, mesh=).
template <class Options>
DescribedOption<Options> with_alias(DescribedOption<Options> row, std::string_view alias) {
  row.about.alias = alias;
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
  else if constexpr (std::is_integral_v<Value>) return static_cast<Value>(std::get<std::int64_t>(value));
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
            else if constexpr (std::is_integral_v<Value>) return OptionValue(static_cast<std::int64_t>(*(o.*member)));
            else return OptionValue(static_cast<double>(*(o.*member)));
          }};
}

}  // namespace dla
