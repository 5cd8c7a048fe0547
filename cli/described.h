#pragma once
// The CLI's options for a table of described options (dla/core/option_description.h): the
// flag's name, its help, range, unit and default all come from the description, and each value
// given is set through it, so the CLI spells none of them.

#include "dla/core/option_description.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dla::cli {

//! The help `--help` and the studio show: the description's, with its range, unit and special
//! value.
inline std::string help_text(const OptionDescription& about) {
  std::string help(about.help);
  if (about.range) help += ", in " + to_string(*about.range);
  if (!about.unit.empty()) help += " " + std::string(about.unit);
  if (about.special) help += "; " + detail::format_number(about.special->value) + ": " + std::string(about.special->means);
  return help;
}

//! The number an integer option's words give: refused as typed, naming the option, when they are
//! not a number or not in its range (so before any cast to an integer).
inline OptionValue typed_number(const OptionDescription& about, const std::string& words) {
  char* end = nullptr;
  const double value = std::strtod(words.c_str(), &end);
  if (words.empty() || std::isspace(static_cast<unsigned char>(words[0])) || end != words.c_str() + words.size())
    throw InvalidInput("`" + std::string(about.name) + "` '" + words + "' is not a whole number");
  require_in(about, value, words);
  return value;
}

//! The options of one table, added to a subcommand; finish() sets those given, in the table's
//! order.
template <class Options>
class DescribedOptions {
 public:
  //! Adds every option of `table` but those named in `without` to `app`, showing the defaults
  //! of `defaults`; appends each description to `described`, if given, for `dla3d options`
  //! (which finds the files' and the look's in output_option_table() itself).
  DescribedOptions(CLI::App& app, const OptionTable<Options>& table, const Options& defaults,
                   std::vector<OptionDescription>* described, std::vector<std::string_view> without = {}) {
    for (const DescribedOption<Options>& row : table) {
      if (std::find(without.begin(), without.end(), row.about.name) != without.end()) continue;
      auto given = std::make_unique<Given>();
      given->row = &row;
      const OptionDescription& about = row.about;
      const OptionValue value = row.get(defaults);
      const std::string name = (about.short_name.empty() ? "" : "-" + std::string(about.short_name) + ",") +
                               cli_flag(about.name) + (about.alias.empty() ? "" : "," + cli_flag(about.alias)),
                        help = help_text(about);
      switch (about.kind) {
        case OptionKind::flag:
          given->on = std::get<bool>(value);
          given->option = app.add_flag(name + (about.negation.empty() ? "" : ",!" + cli_flag(about.negation)),
                                       given->on, help)
                              ->default_str(to_string(value));
          break;
        case OptionKind::integer:
          // Read as typed, so that a number past what an integer holds is refused as typed.
          given->text = to_string(value);
          given->option = app.add_option(name, given->text, help)->capture_default_str()->type_name("INT");
          break;
        case OptionKind::real:
          given->number = std::get<double>(value);
          given->option = app.add_option(name, given->number, help)->capture_default_str();
          break;
        case OptionKind::word: {
          given->text = std::get<std::string>(value);
          std::string words;
          for (std::string_view w : about.choices) words += (words.empty() ? "" : "|") + std::string(w);
          given->option = app.add_option(name, given->text, help)->capture_default_str()->type_name(words);
          break;
        }
        case OptionKind::vector:
        case OptionKind::points:
        case OptionKind::colour:
        case OptionKind::text:
        case OptionKind::file:
          if (about.repeats) {
            // Each --seed-at takes one point; its default (none) is not shown.
            given->texts = std::get<std::vector<std::string>>(value);
            given->option = app.add_option(name, given->texts, help)->allow_extra_args(false);
          } else {
            given->text = std::get<std::string>(value);
            given->option = app.add_option(name, given->text, help)->capture_default_str();
          }
          given->option->type_name(std::string(about.form));
          break;
      }
      given->option->group(std::string(about.group));
      for (const std::string_view other : about.excludes)
        if (CLI::Option* excluded = app.get_option_no_throw(cli_flag(other))) given->option->excludes(excluded);
      if (described) described->push_back(about);
      given_.push_back(std::move(given));
    }
  }

  //! The options added whose description `pick` accepts.
  std::vector<const CLI::Option*> options_where(const std::function<bool(const OptionDescription&)>& pick) const {
    std::vector<const CLI::Option*> picked;
    for (const auto& given : given_)
      if (pick(given->row->about)) picked.push_back(given->option);
    return picked;
  }

  //! Sets in `options` each option the command line gave, checked by its description.
  void finish(Options& options) const {
    for (const auto& given : given_) {
      if (!given->option->count()) continue;
      switch (given->row->about.kind) {
        case OptionKind::flag: given->row->set(options, given->on); break;
        case OptionKind::integer: given->row->set(options, typed_number(given->row->about, given->text)); break;
        case OptionKind::real: given->row->set(options, given->number); break;
        case OptionKind::word: given->row->set(options, given->text); break;
        case OptionKind::vector:
        case OptionKind::points:
        case OptionKind::colour:
        case OptionKind::text:
        case OptionKind::file:
          if (given->row->about.repeats) given->row->set(options, given->texts);
          else given->row->set(options, given->text);
          break;
      }
    }
  }

 private:
  struct Given {  // where CLI11 puts one option's value; at a fixed address
    const DescribedOption<Options>* row = nullptr;
    CLI::Option* option = nullptr;
    bool on = false;
    double number = 0.0;
    std::string text;
    std::vector<std::string> texts;
  };
  std::vector<std::unique_ptr<Given>> given_;
};

}  // namespace dla::cli
