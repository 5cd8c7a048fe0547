// `dla3d options`: the one description of every growth model's options, for the studio's
// option panel (docs/studio.md), so no front end keeps a table of its own.

#include "options.h"

#include "dla/io/json.h"
#include "dla/run/run.h"
#include "dla/version.h"

namespace dla::cli {

namespace {

std::string names_json(const std::vector<std::string>& names, const char* dashes) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + json::string(dashes + name);
  return "[" + text + "]";
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
      const bool flag = option->get_type_size() == 0;
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
              json::string(group) + ", \"help\": " + json::string(option->get_description()) + "}";
      first = false;
    }
    text += "]}";
  }
  return text + "]}\n";
}

}  // namespace dla::cli
