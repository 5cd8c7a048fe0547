// dla3d's command line: the top level's options are the first model's (DLA's), each other
// model's a subcommand's (model_command.cpp), and the commands that grow nothing are here; this
// file puts them together, parses, and hands the words to the one given.

#include "command_line.h"

#include "described.h"
#include "options.h"

#include "dla/run/presets.h"
#include "dla/version.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>

namespace dla::cli {

Subcommand add_frames_command(CLI::App& app);

namespace {

//! Every model's --preset (presets.h), which parse_command_line() expands before parsing.
void add_preset_option(CLI::App& app, const Model& model) {
  std::string names;
  for (const Preset* preset : presets_of(model.name)) names += (names.empty() ? "" : ", ") + std::string(preset->name);
  if (names.empty()) return;
  app.add_option("--preset")
      ->description("start from a named set of options, which options given beside it override: " + names +
                    "; list: print them with what each sets")
      ->type_name("NAME|list")->group("Preset");
}

//! The presets of `model` as `--preset list` prints them.
std::string presets_text(const Model& model) {
  std::string text;
  for (const Preset* preset : presets_of(model.name)) {
    text += std::string(preset->name) + ": " + std::string(preset->summary) + "\n ";
    for (const PresetOption& option : preset->options)
      text += " " + cli_flag(option.name) + (option.value.empty() ? "" : " " + std::string(option.value));
    text += "\n";
  }
  return text;
}

//! `args` with their `--preset NAME` replaced by the preset's options, put before the user's
//! so that the record lists them; an option the user gives, or excludes by giving another,
//! is left out. Null without --preset; `listed` receives the text of `--preset list`.
std::optional<std::vector<std::string>> with_preset(const std::vector<std::string>& args, CLI::App& app,
                                                    const std::vector<Subcommand>& models, std::string& listed) {
  const Model* model = find_model("grow");
  CLI::App* command = &app;
  std::size_t start = 0;
  if (!args.empty())
    for (std::size_t m = 0; m < models.size(); ++m)
      if (models[m].app != &app && args[0] == models[m].app->get_name()) {
        model = &dla::models()[m];
        command = models[m].app;
        start = 1;
      }
  std::optional<std::size_t> at;
  std::string name;
  for (std::size_t i = start; i < args.size(); ++i) {
    if (args[i] != "--preset" && args[i].rfind("--preset=", 0) != 0) continue;
    if (at) throw InvalidInput("--preset is given twice: give one, and options beside it");
    at = i;
    if (args[i] != "--preset") {
      name = args[i].substr(9);
    } else if (i + 1 < args.size()) {
      name = args[++i];
    } else {
      throw InvalidInput("--preset needs a NAME; --preset list prints them");
    }
  }
  // Another subcommand's (convert, studio ...) has no presets, and says so when parsed.
  const std::vector<CLI::App*> subcommands = app.get_subcommands([](CLI::App*) { return true; });
  const bool other = start == 0 && !args.empty() && std::any_of(subcommands.begin(), subcommands.end(), [&](const CLI::App* sub) {
                       return sub->get_name() == args[0];
                     });
  if (!at || other || !command->get_option_no_throw("--preset")) return std::nullopt;
  if (name == "list") {
    listed = presets_text(*model);
    return std::vector<std::string>{};
  }
  const Preset& preset = find_preset(model->name, name);
  std::vector<CLI::Option*> given;
  for (std::size_t i = start; i < args.size(); ++i) {
    if (i == *at || (i == *at + 1 && args[*at] == "--preset") || args[i].size() < 2 || args[i][0] != '-') continue;
    if (CLI::Option* option = command->get_option_no_throw(args[i].substr(0, args[i].find('='))))
      given.push_back(option);
  }
  std::vector<std::string> expanded(args.begin(), args.begin() + static_cast<std::ptrdiff_t>(start));
  for (const PresetOption& option : preset.options) {
    CLI::Option* described = command->get_option_no_throw(cli_flag(option.name));
    if (!described)
      throw std::logic_error("the preset " + name + " sets " + cli_flag(option.name) + ", which " +
                             std::string(model->name) + " has not");
    const bool overridden = std::any_of(given.begin(), given.end(), [&](CLI::Option* g) {
      return g == described || g->get_excludes().count(described) || described->get_excludes().count(g);
    });
    if (overridden) continue;
    expanded.push_back(cli_flag(option.name));
    if (!option.value.empty()) expanded.emplace_back(option.value);
  }
  for (std::size_t i = start; i < args.size(); ++i)
    if (i != *at && !(i == *at + 1 && args[*at] == "--preset")) expanded.push_back(args[i]);
  return expanded;
}

}  // namespace

CommandLine parse_command_line(const std::vector<std::string>& args) {
  CommandLine line;
  line.words = args;
  CLI::App app{"Grows a branching structure by off-lattice diffusion-limited aggregation and writes\n"
               "it as a POV-Ray scene (PREFIX.pov, PREFIX.inc), PREFIX.csv, PREFIX.ply and PREFIX.json.",
               "dla3d"};
  app.set_version_flag("--version", std::string("dla3d ") + version);
  app.get_formatter()->column_width(34);

  // Every model's options: the first's (DLA's) are the top level's, the others' a subcommand each.
  std::vector<Subcommand> models;
  for (const Model& model : dla::models()) {
    models.push_back(add_model_command(
        models.empty() ? app : *app.add_subcommand(std::string(model.name), std::string(model.summary)), model));
    add_preset_option(*models.back().app, model);
  }
  CLI::App* convert = app.add_subcommand("convert", "read a mesh (STL, OFF, OBJ, PLY) and write it as binary STL, then stop");
  convert->add_option("in", line.convert_in, "the mesh to read")->required();
  convert->add_option("out", line.convert_out, "the .stl to write")->required();
  CLI::App* analyze = app.add_subcommand(
      "analyze", "print as JSON the fractal dimension of a grown structure (by gyration and by mass-radius), or "
                 "D_f and k_f of aggregates' sphere lists (by pair correlation, and by gyration over them)");
  analyze->add_option("csv", line.analyze_files, "a CSV that dla3d wrote (PREFIX.csv), or sphere lists "
                                                 "(PREFIX_spheres.csv: x,y,z,r), one an aggregate")->required();
  const Subcommand frames = add_frames_command(app);
  CLI::App* options = app.add_subcommand("options", "print every growth model's options as JSON (names, defaults, "
                                                    "kinds, ranges, choices, groups, help), as --help shows them, "
                                                    "then stop");
  std::string list_format(to_string(OptionListFormat::json));
  options->add_option("--format", list_format, "json, or markdown: the page docs/options.md")
      ->capture_default_str()->group("Listing");
  CLI::App* studio = app.add_subcommand("studio", "start the growth studio, a web page to paint seeds on a mesh, watch "
                                                  "growth live and download the files (docs/studio.md)");
  StudioCommand& s = line.studio;
  studio->add_option("--host", s.host, "the address to listen on; another than loopback lets other machines in, "
                                       "each with the printed token")->capture_default_str();
  studio->add_option("--port", s.port, "the port to listen on, 0-65535; 0: a free one")->capture_default_str();
  studio->add_flag("--open", s.open, "open the page in the web browser");
  app.require_subcommand(0, 1);

  std::string listed;
  if (const std::optional<std::vector<std::string>> expanded = with_preset(args, app, models, listed)) {
    if (expanded->empty()) {
      line.kind = CommandLine::Kind::print;
      line.text = listed;
      return line;
    }
    return parse_command_line(*expanded);
  }

  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    line.kind = CommandLine::Kind::print;
    line.text = app.help();
    return line;
  } catch (const CLI::CallForAllHelp&) {
    line.kind = CommandLine::Kind::print;
    line.text = app.help("", CLI::AppFormatMode::All);
    return line;
  } catch (const CLI::CallForVersion&) {
    line.kind = CommandLine::Kind::print;
    line.text = std::string("dla3d ") + version + "\n";
    return line;
  } catch (const CLI::ParseError& e) {
    throw InvalidInput(std::string(e.what()) + " (see dla3d --help)");
  }

  // --stream is every growth model's; only the run reads it.
  const auto finish_model = [&](const Subcommand& model) {
    model.finish(line);
    if (const CLI::Option* stream = model.app->get_option_no_throw("--stream"); stream && stream->count()) {
      line.stream_path = stream->as<std::string>();
      if (line.stream_path.empty()) throw InvalidInput("--stream '' names no file");
    }
  };
  for (const Subcommand& model : models)
    if (model.app != &app && model.app->parsed()) {
      finish_model(model);
      return line;
    }
  if (options->parsed()) {
    line.kind = CommandLine::Kind::print;
    line.text = parse_word<OptionListFormat>(list_format) == OptionListFormat::json ? options_json(models)
                                                                                    : options_markdown(app, models);
    return line;
  }
  if (studio->parsed()) {
    line.kind = CommandLine::Kind::studio;
    if (s.port < 0 || s.port > 65535) throw InvalidInput("--port " + std::to_string(s.port) + " is not in 0-65535");
    const bool printable = std::all_of(s.host.begin(), s.host.end(), [](char c) { return c > ' ' && c < 127; });
    if (s.host.empty() || s.host.size() > 253 || !printable)
      throw InvalidInput("--host '" + s.host + "' is not a host name or address");
    return line;
  }
  if (convert->parsed()) {
    line.kind = CommandLine::Kind::convert;
    const std::string& out = line.convert_out;
    if (out.size() < 4 || (out.compare(out.size() - 4, 4, ".stl") != 0 && out.compare(out.size() - 4, 4, ".STL") != 0))
      throw InvalidInput("convert writes binary STL: '" + out + "' does not end in .stl");
    return line;
  }
  if (analyze->parsed()) {
    line.kind = CommandLine::Kind::analyze;
    return line;
  }
  if (frames.app->parsed()) {
    frames.finish(line);
    return line;
  }
  for (const Subcommand& model : models)
    if (model.app == &app) finish_model(model);
  return line;
}

}  // namespace dla::cli
