// `dla3d options`: the one description of every growth model's options, for the studio's
// option panel (docs/studio.md), so no front end keeps a table of its own.

#include "options.h"

#include "dla/io/json.h"
#include "dla/run/presets.h"
#include "dla/run/run.h"
#include "dla/version.h"

namespace dla::cli {

namespace {

std::string names_json(const std::vector<std::string>& names, const char* dashes) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + json::string(dashes + name);
  return "[" + text + "]";
}

//! What `dla3d options` adds from the library's description of an option: its kind, choices,
//! range and unit. An option not yet described gives its kind as CLI11 knows it.
std::string description_json(const CLI::Option& option, const std::vector<OptionDescription>& described) {
  const std::string name = "--" + option.get_lnames().front();
  for (const OptionDescription& about : described) {
    if (cli_flag(about.name) != name) continue;
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
    text += std::string(m ? "," : "") + "\n {\"name\": " + json::string(model.name) +
            ", \"summary\": " + json::string(model.summary) + ", \"options\": [";
    bool first = true;
    for (const CLI::Option* option : app.get_options()) {
      // As --help: an option in no group is hidden; help and version are not a model's.
      const std::string& group = option->get_group();
      if (group.empty() || option->get_lnames() == std::vector<std::string>{"help"} ||
          option->get_lnames() == std::vector<std::string>{"version"} || option->get_lnames().empty())
        continue;
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

}  // namespace dla::cli
