#pragma once
// What dla3d's subcommands share: the option groups every growth model has (Output and Look),
// the links, the refusals of DLA's mesh controls, and the hook each subcommand's file gives the
// parser. The options themselves are the library's descriptions (described.h).

#include "command_line.h"
#include "described.h"

#include "dla/run/run.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dla::cli {

//! A subcommand's options added to the parser, and what turns their words into the command
//! line once it has parsed and the subcommand was given.
struct Subcommand {
  CLI::App* app;
  std::function<void(CommandLine& line)> finish;
  //! The library's descriptions of the options added from them (described.h), which
  //! `dla3d options` gives with their kind, choices, range and unit.
  std::vector<OptionDescription> described = {};
};

//! What `dla3d options --format` prints.
enum class OptionListFormat {
  json,      //!< for front ends that build a form from it (the studio, the Blender add-on)
  markdown,  //!< docs/options.md
};
inline constexpr WordTable<OptionListFormat, 2> kOptionListFormatWords{
    "--format", {{{OptionListFormat::json, "json"}, {OptionListFormat::markdown, "markdown"}}}};
constexpr const auto& words_of(OptionListFormat) { return kOptionListFormatWords; }

//! `dla3d options`: every growth model's options (`models`, in the library's order) as `--help`
//! shows them, as JSON read from the parser itself, for front ends that build a form from them
//! (the studio). In options_list.cpp.
std::string options_json(const std::vector<Subcommand>& models);

//! `dla3d options --format markdown`: docs/options.md, every command's options (`app`'s, the
//! growth models' as `models` describe them) with their defaults, values and help, and the
//! presets. In options_list.cpp.
std::string options_markdown(const CLI::App& app, const std::vector<Subcommand>& models);

//! The Output, Look and Solid options, the same for every growth model and for `frames`: the
//! library's (files_option_table(), output_option_table()) and the CLI's own (-q, --stream),
//! added to `app`; finish() sets those given in `files`.
class OutputWords {
 public:
  //! `formats`: the --formats default; empty: those `files` holds (the model's).
  OutputWords(CLI::App& app, OutputOptions& files, bool& quiet, std::string formats = {});
  //! Sets in `files` (those given to the constructor) the options given; those the mesh gives
  //! defaults for only when given.
  void finish(OutputOptions& files) const;

 private:
  std::optional<Formats> formats_;  // the command's own default, if not the model's
  std::unique_ptr<DescribedOptions<OutputOptions>> files_, options_;
};

//! --links (with `lattice`, Eden's word lattice too), from links_option_table().
std::unique_ptr<DescribedOptions<LinkOptions>> add_links_option(CLI::App& command, bool lattice = false);
//! The links given to the options added by add_links_option(); none given: no links.
inline LinkOptions links_of(const DescribedOptions<LinkOptions>& links) {
  LinkOptions o;
  links.finish(o);
  return o;
}

//! Adds the options of `model`, as the library's registry describes them (dla/run/run.h), to
//! `command`: the top level for DLA (`dla3d [options]`), else the model's subcommand. In
//! model_command.cpp.
Subcommand add_model_command(CLI::App& command, const Model& model);

}  // namespace dla::cli
