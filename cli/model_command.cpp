// A growth model's command, made from its registration (dla/run/run.h): its options from the
// library's description, the files' and the look's, the other models' options it refuses with
// why, and, for a model whose runs go on from a checkpoint (DLA), the Long runs group.

#include "options.h"

#include <algorithm>

namespace dla::cli {

namespace {

//! What the parser holds for one model's command until it is finished into the run's options.
struct ModelWords {
  RunOptions run;
  bool quiet = false;
  std::vector<OptionDescription> described;
  std::unique_ptr<DescribedOptions<RunOptions>> own;
  std::unique_ptr<OutputWords> files;  // bound to run's files, which stay put
  // The Long runs group, for a model that resumes.
  std::string checkpoint_path, resume_path;
  double checkpoint_every = kCheckpointEvery;
  const CLI::Option* resume = nullptr;
};

//! The other models' options `model` refuses, each with why when given; not in --help.
void add_refusals(CLI::App& command, const Model& model) {
  for (const std::string_view name : model.refuses)
    command.add_option_function<std::string>(cli_flag(name), [&model, name](const std::string&) {
      refuse_for(model.name, name);
    })->group("");
}

//! --checkpoint, --checkpoint-every and --resume.
void add_long_runs(CLI::App& command, ModelWords& w) {
  const char* runs = "Long runs";
  command.add_option("--checkpoint", w.checkpoint_path, "save the run to FILE as it goes, and when stopped by Ctrl-C or SIGTERM")
      ->type_name("FILE")->group(runs);
  command.add_option("--checkpoint-every", w.checkpoint_every, "seconds between saves")->capture_default_str()->group(runs);
  w.resume = command.add_option("--resume", w.resume_path, "grow on from a checkpoint, with the options it was started with")
                 ->type_name("FILE")->group(runs);
}

//! --resume: the checkpoint gives every option but -q, --stream and those that change only how
//! fast the run goes (--threads), which replace the checkpoint's.
void finish_resume(const CLI::App& command, ModelWords& w, CommandLine& line) {
  const std::vector<const CLI::Option*> speed = w.own->options_where([](const OptionDescription& about) { return about.speed_only; });
  std::vector<const CLI::Option*> company = speed;
  company.insert(company.end(), {w.resume, command.get_option("--quiet"), command.get_option("--stream")});
  std::string names = "-q";
  for (const CLI::Option* option : company)
    if (option != w.resume && option->get_name() != "--quiet") names += ", " + option->get_name();
  for (const CLI::Option* option : command.get_options())
    if (option->count() && std::find(company.begin(), company.end(), option) == company.end())
      throw InvalidInput("--resume takes no other options but " + names + ": the rest come from the checkpoint");
  RunOptions scratch = w.run;
  w.own->finish(scratch);  // checks the values of those given, the only options set
  line.kind = CommandLine::Kind::resume;
  line.resume_path = w.resume_path;
  for (const CLI::Option* option : speed)
    if (option->count()) {
      CommandLine::ResumeOption given{{}, {option->get_name()}};
      for (const std::string& name : option->get_lnames()) given.names.push_back("--" + name);
      for (const std::string& name : option->get_snames()) given.names.push_back("-" + name);
      for (const std::string& value : option->results()) given.words.push_back(value);
      line.resume_options.push_back(std::move(given));
    }
}

}  // namespace

Subcommand add_model_command(CLI::App& command, const Model& model) {
  auto w = std::make_shared<ModelWords>();
  w->run = model.options();
  command.get_formatter()->column_width(34);
  w->own = std::make_unique<DescribedOptions<RunOptions>>(command, model.option_table, w->run, &w->described);
  add_refusals(command, model);
  w->files = std::make_unique<OutputWords>(command, model.files(w->run), w->quiet);
  if (model.resumes) add_long_runs(command, *w);
  return {&command,
          [w, &model, &command](CommandLine& line) {
            line.quiet = w->quiet;
            if (w->resume && w->resume->count()) return finish_resume(command, *w, line);
            if (!(w->checkpoint_every >= 0.0))
              throw InvalidInput("--checkpoint-every " + detail::format_number(w->checkpoint_every) +
                                 " is not a number of seconds");
            line.checkpoint_path = w->checkpoint_path;
            line.checkpoint_every = w->checkpoint_every;
            w->own->finish(w->run);
            w->files->finish(model.files(w->run));
            validate(w->run);
            line.run = w->run;
          },
          w->described};
}

}  // namespace dla::cli
