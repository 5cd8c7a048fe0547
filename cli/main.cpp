// dla3d: grows a DLA structure (or, with `colonize`, a space colonization tree; with `eden`, an
// Eden cluster; with `drop` and `ballistic`, a random-drop or ballistic aggregate) and writes it
// as a POV-Ray scene, CSV, PLY and a JSON sidecar.
// This file parses the command line (command_line.cpp) and runs what it names: a growth run of
// any model (run.cpp) or another subcommand, a file each. Every error ends here as one line on
// stderr, with the options the library names spelled as dla3d's flags.

#include "command_line.h"
#include "commands.h"

#include "dla/io/checkpoint.h"
#include "dla/core/input_file.h"

#include <csignal>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

namespace {

//! Set by SIGINT and SIGTERM: the first ends the stage under way within milliseconds, a second
//! the writing of what grew; a third ends the process at once.
dla::cli::StopSignals stop_signals;
static_assert(dla::StopFlag::is_always_lock_free, "a signal handler may only store to a lock-free atomic");

extern "C" void on_stop_signal(int signal) {
  stop_signals.signal = signal;
  if (stop_signals.first.exchange(true)) {
    stop_signals.second.store(true);
    std::signal(signal, SIG_DFL);
  }
}

//! Every growth run, of every model, stops on Ctrl-C and SIGTERM and writes what grew.
void catch_stop_signals() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

int run(const std::vector<std::string>& args) {
  using Kind = dla::cli::CommandLine::Kind;
  const dla::cli::CommandLine line = dla::cli::parse_command_line(args);
  switch (line.kind) {
    case Kind::print: std::fputs(line.text.c_str(), stdout); return 0;
    case Kind::convert: return dla::cli::convert(line.convert_in, line.convert_out, line.quiet);
    case Kind::analyze: return dla::cli::analyze(line.analyze_files);
    case Kind::studio: return dla::cli::studio(line.studio);
    case Kind::frames:
      catch_stop_signals();
      return dla::cli::frames(line.frames, line.quiet, stop_signals);
    case Kind::run:
      catch_stop_signals();
      return dla::cli::run(line, line.words, {}, stop_signals);
    case Kind::resume: break;
  }
  // The checkpoint's own command, with -q and the options given that change how fast it goes
  // on, never what it grows (the thread count).
  dla::require_regular_file(line.resume_path, "resume");
  const dla::Checkpoint checkpoint = dla::read_checkpoint(line.resume_path);
  std::vector<std::string> command;
  for (std::size_t i = 0; i < checkpoint.command.size(); ++i) {
    const std::string& word = checkpoint.command[i];
    bool replaced = false, value_follows = false;
    for (const auto& option : line.resume_options)
      for (const std::string& name : option.names) {
        value_follows = value_follows || word == name;
        replaced = replaced || word == name || word.rfind(name + "=", 0) == 0;
      }
    if (!replaced) command.push_back(word);
    if (value_follows) ++i;
  }
  for (const auto& option : line.resume_options) command.insert(command.end(), option.words.begin(), option.words.end());
  if (line.quiet) command.push_back("-q");
  dla::cli::CommandLine resumed = dla::cli::parse_command_line(command);
  if (resumed.kind != Kind::run || !resumed.run.get_if<dla::DlaRunOptions>())
    throw dla::InvalidInput(line.resume_path + ": its command is not a growth run");
  resumed.stream_path = line.stream_path;  // a checkpoint's command never holds one: run.cpp
  catch_stop_signals();
  return dla::cli::run(resumed, command, {&checkpoint.cluster, &checkpoint.walk, checkpoint.input_hash}, stop_signals);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const dla::InvalidInput& e) {
    std::fprintf(stderr, "dla3d: error: %s\n", dla::spell_options(e.what(), dla::OptionSpelling::cli).c_str());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "dla3d: error: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dla3d: error: %s\n", dla::spell_options(e.what(), dla::OptionSpelling::cli).c_str());
  }
  return 1;
}
