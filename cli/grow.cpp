// `dla3d [options]`: DLA's options, the top level's (Growth, Mesh constraint, Spawn, Long runs),
// turned into the library's DlaRunOptions; and --resume.

#include "options.h"

namespace dla::cli {

namespace {

//! DLA's options as the parser holds them until they are finished into the run's options.
struct GrowWords {
  CLI::Option* threads_option = nullptr;
  std::vector<OptionDescription> described;
  std::unique_ptr<DescribedOptions<DlaRunOptions>> run;  // from dla_run_option_table()
  std::unique_ptr<OutputWords> files;
};

//! Only -q, --threads and --stream may go with --resume: every other option comes from the
//! checkpoint.
void check_resume_company(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--resume" || arg == "--threads" || arg == "--stream") ++i;
    else if (arg.rfind("--resume=", 0) != 0 && arg.rfind("--threads=", 0) != 0 && arg.rfind("--stream=", 0) != 0 &&
             arg != "-q" && arg != "--quiet")
      throw InvalidInput("--resume takes no other options but -q, --threads and --stream: they come from the checkpoint");
  }
}

//! DLA's options on `app`, and the long runs'.
void add_options(CLI::App& app, DlaRunOptions& g, CommandLine& line, GrowWords& w) {
  w.run = std::make_unique<DescribedOptions<DlaRunOptions>>(app, dla_run_option_table(), g, &w.described);
  w.threads_option = app.get_option("--threads");
  w.files = std::make_unique<OutputWords>(app, g.files, line.quiet);

  const char* runs = "Long runs";
  app.add_option("--checkpoint", line.checkpoint_path, "save the run to FILE as it goes, and when stopped by Ctrl-C or SIGTERM")
      ->type_name("FILE")->group(runs);
  app.add_option("--checkpoint-every", line.checkpoint_every, "seconds between saves")->capture_default_str()->group(runs);
  app.add_option("--resume", line.resume_path, "grow on from a checkpoint, with the options it was started with")
      ->type_name("FILE")->group(runs);
}

//! The words as DLA's run options, which the library checks.
void finish(CommandLine& line, DlaRunOptions& g, const GrowWords& w) {
  if (!(line.checkpoint_every >= 0.0))
    throw InvalidInput("--checkpoint-every " + detail::format_number(line.checkpoint_every) + " is not a number of seconds");
  w.run->finish(g);
  w.files->finish(g.files);
  validate(g);
}

}  // namespace

Subcommand add_grow_options(CLI::App& app, const Model&) {
  auto words = std::make_shared<GrowWords>();
  auto run = std::make_shared<DlaRunOptions>();
  auto line = std::make_shared<CommandLine>();  // the Long runs' and the quiet flag's words
  add_options(app, *run, *line, *words);
  return {&app, [words, run, line](CommandLine& out, const std::vector<std::string>& args) {
            out.quiet = line->quiet;
            out.checkpoint_path = line->checkpoint_path;
            out.checkpoint_every = line->checkpoint_every;
            if (!line->resume_path.empty()) {
              check_resume_company(args);
              out.kind = CommandLine::Kind::resume;
              out.resume_path = line->resume_path;
              words->run->finish(*run);  // the thread count, the one growth option given
              if (words->threads_option->count()) out.threads = run->growth.threads;
              validate(run->growth);
              return;
            }
            finish(out, *run, *words);
            out.run = *run;
          },
          words->described};
}

}  // namespace dla::cli
