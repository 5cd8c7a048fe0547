// `dla3d options`: the one description of every growth model's options, for the studio's
// option panel (docs/studio.md) and the Blender add-on as JSON, and as docs/options.md, so no
// front end and no page keeps a table of its own.

#include "options.h"

#include "dla/io/json.h"
#include "dla/run/presets.h"
#include "dla/run/run.h"
#include "dla/version.h"

#include <algorithm>
#include <cctype>

namespace dla::cli {

namespace {

//! The options a command shows, as --help does: an option in no group is hidden; help and
//! version are not a model's.
std::vector<const CLI::Option*> shown_options(const CLI::App& app) {
  std::vector<const CLI::Option*> shown;
  for (const CLI::Option* option : app.get_options()) {
    const std::vector<std::string>& names = option->get_lnames();
    if (option->get_group().empty() || names.empty() || names == std::vector<std::string>{"help"} ||
        names == std::vector<std::string>{"version"})
      continue;
    shown.push_back(option);
  }
  return shown;
}

//! The library's description of `option`, if it has one: among a command's `described`, or
//! the files', the look's and the links', which every growth model (and `frames` the first two) has.
const OptionDescription* description_of(const CLI::Option& option, const std::vector<OptionDescription>& described) {
  const std::string name = "--" + option.get_lnames().front();
  for (const OptionDescription& about : described)
    if (cli_flag(about.name) == name) return &about;
  for (const auto* shared : {&output_option_table(), &files_option_table()})
    for (const DescribedOption<OutputOptions>& row : *shared)
      if (cli_flag(row.about.name) == name) return &row.about;
  for (const DescribedOption<LinkOptions>& row : links_option_table())
    if (cli_flag(row.about.name) == name) return &row.about;
  return nullptr;
}

std::string names_json(const std::vector<std::string>& names, const char* dashes) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + json::string(dashes + name);
  return "[" + text + "]";
}

//! What `dla3d options` adds from the library's description of an option: its kind, choices,
//! range and unit. An option not yet described gives its kind as CLI11 knows it.
std::string description_json(const CLI::Option& option, const std::vector<OptionDescription>& described) {
  if (const OptionDescription* described_as = description_of(option, described)) {
    const OptionDescription& about = *described_as;
    std::string text = ", \"kind\": " + json::string(to_string(about.kind));
    if (!about.choices.empty()) {
      std::vector<std::string> choices(about.choices.begin(), about.choices.end());
      text += ", \"choices\": " + names_json(choices, "");
    }
    if (about.range)
      text += ", \"min\": " + json::number(about.range->min) + ", \"max\": " + json::number(about.range->max) +
              ", \"min_open\": " + (about.range->min_open ? "true" : "false") +
              ", \"max_open\": " + (about.range->max_open ? "true" : "false");
    if (about.special)
      text += ", \"special\": {\"value\": " + json::number(about.special->value) +
              ", \"means\": " + json::string(about.special->means) + "}";
    if (!about.unit.empty()) text += ", \"unit\": " + json::string(about.unit);
    // Both ways, of the command's own: the description writes a pair once, on the later option.
    std::vector<std::string> excludes;
    for (const OptionDescription& other : described)
      if (std::find(about.excludes.begin(), about.excludes.end(), other.name) != about.excludes.end() ||
          std::find(other.excludes.begin(), other.excludes.end(), about.name) != other.excludes.end())
        excludes.push_back(cli_flag(other.name).substr(2));
    if (!excludes.empty()) text += ", \"excludes\": " + names_json(excludes, "--");
    if (about.paints) text += ", \"paints\": " + json::string(to_string(*about.paints));
    if (about.needs)
      text += ", \"needs\": [" + json::string(cli_flag(about.needs->name)) + ", " + json::string(about.needs->value) + "]";
    if (about.speed_only) text += ", \"speed_only\": true";
    return text;
  }
  const std::string type = option.get_type_name();
  const char* kind = option.get_expected_max() == 0 ? "flag"
                     : type == "INT" || type == "UINT" ? "integer"
                     : type == "FLOAT" ? "real"
                     : type.find("FILE") != std::string::npos ? "file"
                                                              : "text";
  return ", \"kind\": " + json::string(kind);
}

}  // namespace

std::string options_json(const std::vector<Subcommand>& models) {
  std::string text = "{\"version\": " + json::string(version) + ", \"models\": [";
  for (std::size_t m = 0; m < models.size(); ++m) {
    const Model& model = dla::models()[m];
    const CLI::App& app = *models[m].app;
    // The words that run it: none for the top-level command, else the subcommand's name.
    const std::string command = app.get_parent() ? "[" + json::string(app.get_name()) + "]" : "[]";
    text += std::string(m ? "," : "") + "\n {\"name\": " + json::string(model.name) + ", \"command\": " + command +
            ", \"summary\": " + json::string(model.summary) + ", \"options\": [";
    bool first = true;
    for (const CLI::Option* option : shown_options(app)) {
      const std::string& group = option->get_group();
      const bool flag = option->get_expected_max() == 0;  // a flag takes no value
      std::vector<std::string> negations;
      for (const std::string& name : option->get_fnames())
        if (option->get_flag_value(name, "{}") == "false" || option->get_flag_value(name, "{}") == "-1")
          negations.push_back(name);
      text += std::string(first ? "" : ",") + "\n  {\"name\": " + json::string("--" + option->get_lnames().front()) +
              ", \"short\": " + names_json(option->get_snames(), "-") + ", \"negation\": " +
              names_json(negations, "--") + ", \"flag\": " + (flag ? "true" : "false") +
              ", \"repeats\": " + (option->get_expected_max() > 1 ? "true" : "false") +
              ", \"default\": " + json::string(option->get_default_str()) +
              ", \"type\": " + json::string(flag ? "" : option->get_type_name()) + ", \"group\": " +
              json::string(group) + ", \"help\": " + json::string(option->get_description()) +
              description_json(*option, models[m].described) + "}";
      first = false;
    }
    text += "], \"presets\": [";
    first = true;
    for (const Preset* preset : presets_of(model.name)) {
      std::string words;
      for (const PresetOption& option : preset->options)
        words += std::string(words.empty() ? "" : ", ") + "[" + json::string(cli_flag(option.name)) + ", " +
                 json::string(option.value) + "]";
      text += std::string(first ? "" : ",") + "\n  {\"name\": " + json::string(preset->name) +
              ", \"summary\": " + json::string(preset->summary) + ", \"options\": [" + words + "]}";
      first = false;
    }
    text += "]}";
  }
  return text + "]}\n";
}

namespace {

//! `text` for a Markdown page: "docs/look.md#files" as a link to that page, sentences begun
//! with a capital when `sentence`; in a table's cell, its bars escaped.
std::string markdown(std::string_view text, bool in_cell = true) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 5, "docs/") == 0) {
      std::size_t end = i + 5;
      while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-' ||
                                   text[end] == '_' || text[end] == '.' || text[end] == '#' || text[end] == '/'))
        ++end;
      while (end > i + 5 && text[end - 1] == '.') --end;  // a sentence's full stop
      const std::string target(text.substr(i + 5, end - i - 5));
      const std::string page = target.substr(0, target.find('#'));
      out += "[" + page + "](" + target + ")";
      i = end - 1;
    } else if (text[i] == '|' && in_cell) {
      out += "\\|";
    } else {
      out += text[i];
    }
  }
  return out;
}

//! "What it grows.": a summary as a sentence.
std::string sentence(std::string_view summary) {
  std::string text = markdown(summary, false);
  if (!text.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text + ".";
}

//! "`-n`, `--particles`": the option's names, a negation among them.
std::string names_markdown(const CLI::Option& option) {
  std::string names;
  for (const std::string& name : option.get_snames()) names += "`-" + name + "`, ";
  for (const std::string& name : option.get_lnames()) names += "`--" + name + "`, ";
  return names.substr(0, names.size() - 2);
}

//! What an option takes: its kind with its range, unit, choices and special value as the
//! library describes them; else as the parser names it.
std::string values_markdown(const CLI::Option& option, const OptionDescription* about) {
  if (option.get_expected_max() == 0) return "flag";
  if (!about) {
    const std::string type = option.get_type_name();
    std::string text = type == "INT" ? "integer" : type == "UINT" ? "integer ≥ 0" : type == "FLOAT" ? "number"
                       : type == "TEXT" ? "text" : "`" + type + "`";
    return option.get_expected_max() > 1 ? text + ", repeated" : text;
  }
  std::string text;
  switch (about->kind) {
    case OptionKind::flag: return "flag";
    case OptionKind::word:
      for (const std::string_view choice : about->choices) text += (text.empty() ? "" : ", ") + std::string(choice);
      return "one of " + text;
    case OptionKind::integer: text = "integer"; break;
    case OptionKind::real: text = "number"; break;
    case OptionKind::vector:
    case OptionKind::points:
    case OptionKind::colour:
    case OptionKind::text:
    case OptionKind::file:
      text = std::string(to_string(about->kind)) + " `" + std::string(about->form) + "`";
      return about->repeats ? text + ", repeated" : text;
  }
  if (about->range) text += " in " + to_string(*about->range);
  if (!about->unit.empty()) text += " " + std::string(about->unit);
  if (about->special) text += "; " + detail::format_number(about->special->value) + ": " + std::string(about->special->means);
  return text;
}

//! A command's options, a table a group in the order --help shows them: (group, table).
std::vector<std::pair<std::string, std::string>> group_tables(const CLI::App& command,
                                                              const std::vector<OptionDescription>& described) {
  std::vector<std::pair<std::string, std::string>> groups;
  for (const CLI::Option* option : shown_options(command)) {
    auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == option->get_group(); });
    if (group == groups.end())
      group = groups.insert(groups.end(), {option->get_group(), "| option | default | takes | what it does |\n"
                                                                "| --- | --- | --- | --- |\n"});
    const OptionDescription* about = description_of(*option, described);
    const std::string& default_word = option->get_default_str();
    group->second += "| " + names_markdown(*option) + " | " +
                     (default_word.empty() ? "" : "`" + markdown(default_word) + "`") + " | " +
                     markdown(values_markdown(*option, about)) + " | " +
                     markdown(about ? std::string(about->help) : option->get_description()) + " |\n";
  }
  return groups;
}

//! A command's words, with its positional arguments: "dla3d convert IN OUT".
std::string command_words(const CLI::App& command, bool top) {
  std::string words = top ? "dla3d" : "dla3d " + command.get_name();
  for (const CLI::Option* option : command.get_options())
    if (option->get_positional()) {
      std::string name = option->get_name();
      std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
      words += " " + name;
    }
  return words;
}

//! "`dla3d convert IN OUT`", "`dla3d eden [options]`": a command as it is typed.
std::string usage(const CLI::App& command, bool top) {
  return "`" + command_words(command, top) + (shown_options(command).empty() ? "" : " [options]") + "`";
}

}  // namespace

std::string options_markdown(const CLI::App& app, const std::vector<Subcommand>& models) {
  std::string text =
      "# Options\n\n"
      "<!-- Generated by `dla3d options --format markdown` from the library's descriptions: edit those\n"
      "(docs/dev/architecture.md#options-described-once), not this page. A test fails when the two differ. -->\n\n"
      "Every option of every command, as `dla3d --help` gives it. A range is closed at a square bracket and open at\n"
      "a round one: `(0, 1]` takes 1 but not 0. A bad value is refused in one line that names the option, and\n"
      "nothing is written; how runs are checked, stopped, resumed and written is in [running.md](running.md).\n"
      "Python's functions take the same options as keywords, spelled with underscores (`--seed-at` is\n"
      "`seed_at=`, [python.md](python.md)). Named sets of options to start from are at the end:\n"
      "[Presets](#presets).\n\n"
      "| command | what it does |\n| --- | --- |\n";
  std::vector<const CLI::App*> others;  // the commands that grow nothing
  for (const CLI::App* command : app.get_subcommands({}))
    if (std::none_of(models.begin(), models.end(), [&](const Subcommand& s) { return s.app == command; }))
      others.push_back(command);
  for (std::size_t m = 0; m < models.size(); ++m)
    text += "| " + usage(*models[m].app, models[m].app == &app) + " | " + sentence(dla::models()[m].summary) + " |\n";
  for (const CLI::App* command : others) text += "| " + usage(*command, false) + " | " + sentence(command->get_description()) + " |\n";

  // The groups most models have alike (the files, the look, the solid) once, before the models;
  // a model whose defaults there differ (an aggregate's) lists its own.
  std::vector<std::vector<std::pair<std::string, std::string>>> tables;
  for (const Subcommand& model : models) tables.push_back(group_tables(*model.app, model.described));
  const auto shared = [&](const std::pair<std::string, std::string>& group) {
    const auto alike = std::count_if(tables.begin(), tables.end(), [&](const auto& model) {
      return std::find(model.begin(), model.end(), group) != model.end();
    });
    return 2 * static_cast<std::size_t>(alike) > tables.size();
  };
  text += "\n## Every growth model\n\nThe files, the look and the solid, the same for every model below but where a "
          "model lists its own (its defaults differ).\n";
  for (const auto& group : tables.front())
    if (shared(group)) text += "\n**" + group.first + "**\n\n" + group.second;
  for (std::size_t m = 0; m < models.size(); ++m) {
    text += "\n## `" + command_words(*models[m].app, models[m].app == &app) + "`\n\n" + sentence(dla::models()[m].summary) +
            " With the options of [every growth model](#every-growth-model).\n";
    for (const auto& group : tables[m])
      if (!shared(group)) text += "\n**" + group.first + "**\n\n" + group.second;
  }
  for (const CLI::App* command : others) {
    if (shown_options(*command).empty()) continue;
    text += "\n## `" + command_words(*command, false) + "`\n\n" + sentence(command->get_description()) + "\n";
    for (const auto& group : group_tables(*command, {}))
      text += shared(group) ? "\n**" + group.first + "**: as for [every growth model](#every-growth-model).\n"
                            : "\n**" + group.first + "**\n\n" + group.second;
  }
  text += "\n## Presets\n\n`--preset NAME` starts from a named set of options; options given beside it override its "
          "own.\n`dla3d MODEL --preset list` prints them. The JSON record lists the options a preset gave.\n\n"
          "| command | preset | what it grows | options |\n| --- | --- | --- | --- |\n";
  for (const Model& model : dla::models())
    for (const Preset* preset : presets_of(model.name)) {
      std::string words;
      for (const PresetOption& option : preset->options)
        words += (words.empty() ? "" : " ") + cli_flag(option.name) + (option.value.empty() ? "" : " " + std::string(option.value));
      text += "| `dla3d" + std::string(model.name == "grow" ? "" : " " + std::string(model.name)) + "` | `" +
              std::string(preset->name) + "` | " + sentence(preset->summary) + " | `" + markdown(words) + "` |\n";
    }
  return text;
}

}  // namespace dla::cli
