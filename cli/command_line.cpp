// dla3d's command line: the top level's options are DLA's (grow.cpp), each subcommand's are in
// its own file; this file puts them together, parses, and hands the words to the one given.

#include "command_line.h"

#include "options.h"

#include "dla/version.h"

#include <algorithm>

namespace dla::cli {

Subcommand add_frames_command(CLI::App& app);

Subcommand add_model_command(CLI::App& app, const Model& model) {
  using Add = Subcommand (*)(CLI::App&, const Model&);
  static const std::pair<std::string_view, Add> commands[] = {
      {"grow", add_grow_options},    {"colonize", add_colonize_command},   {"eden", add_eden_command},
      {"drop", add_drop_command},    {"ballistic", add_ballistic_command}, {"breakdown", add_breakdown_command},
  };
  for (const auto& [name, add] : commands)
    if (name == model.name) return add(app, model);
  throw std::logic_error("the model " + std::string(model.name) + " has no command line");
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
  CommandLine line;
  CLI::App app{"Grows a branching structure by off-lattice diffusion-limited aggregation and writes\n"
               "it as a POV-Ray scene (PREFIX.pov, PREFIX.inc), PREFIX.csv, PREFIX.ply and PREFIX.json.",
               "dla3d"};
  app.set_version_flag("--version", std::string("dla3d ") + version);
  app.get_formatter()->column_width(34);

  // Every model's options: DLA's are the top level's, the others' a subcommand each.
  std::vector<Subcommand> models;
  for (const Model& model : dla::models()) models.push_back(add_model_command(app, model));
  CLI::App* convert = app.add_subcommand("convert", "read a mesh (STL, OFF, OBJ, PLY) and write it as binary STL, then stop");
  convert->add_option("in", line.convert_in, "the mesh to read")->required();
  convert->add_option("out", line.convert_out, "the .stl to write")->required();
  CLI::App* analyze = app.add_subcommand(
      "analyze", "print the fractal dimension of a grown structure (by gyration and by mass-radius) as JSON");
  analyze->add_option("csv", line.analyze_csv, "a CSV that dla3d wrote")->required();
  const Subcommand frames = add_frames_command(app);
  CLI::App* options = app.add_subcommand("options", "print every growth model's options as JSON (names, defaults, "
                                                    "types, groups, help), as --help shows them, then stop");
  CLI::App* studio = app.add_subcommand("studio", "start the growth studio, a web page to paint seeds on a mesh, watch "
                                                  "growth live and download the files (docs/studio.md)");
  StudioCommand& s = line.studio;
  studio->add_option("--host", s.host, "the address to listen on; another than loopback lets other machines in, "
                                       "each with the printed token")->capture_default_str();
  studio->add_option("--port", s.port, "the port to listen on, 0-65535; 0: a free one")->capture_default_str();
  studio->add_flag("--open", s.open, "open the page in the web browser");
  app.require_subcommand(0, 1);

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
    model.finish(line, args);
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
    line.text = options_json(models);
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
    frames.finish(line, args);
    return line;
  }
  for (const Subcommand& model : models)
    if (model.app == &app) finish_model(model);
  return line;
}

}  // namespace dla::cli
