#pragma once
// dla3d's command line, parsed and checked without touching a file: main.cpp runs what it says,
// and the CLI fuzzer (tests/fuzz/cli_fuzz.cpp) drives it with arbitrary words. The options
// fill the library's run options (dla/run/models.h), which the library checks; each
// subcommand's options are in its own file, the groups they share in options.cpp.

#include "dla/run/models.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace dla::cli {

//! `dla3d frames PREFIX.csv --count K`: the structure a CSV holds as it grew, in K files of
//! each format (PREFIX_0001.glb ...), for tools that cannot reveal growth by its age.
struct FramesCommand {
  OutputOptions files;
  std::string csv_path;
  std::size_t count = 30;  //!< frames: frame k of K holds the seeds and k/K of the rest
  //! Links made on the whole structure, each shown from its later particle's frame; none: the
  //! CSV's own (PREFIX_links.csv beside it).
  LinkOptions links;
};

//! `dla3d studio`: the growth studio's web server (docs/studio.md), run by Python.
struct StudioCommand {
  std::string host = "127.0.0.1";  //!< the address it listens on: loopback unless asked
  int port = 8765;                 //!< 0: a free port, printed
  bool open = false;               //!< open the page in the browser
};

//! `--checkpoint-every`'s default, in seconds.
inline constexpr double kCheckpointEvery = 60.0;

//! What the command line asks for.
struct CommandLine {
  enum class Kind {
    run,      //!< a growth run of any model: `run` holds its options
    resume,   //!< --resume FILE, with only -q, --stream and `resume_options` beside it
    convert,  //!< dla3d convert IN OUT.stl
    analyze,  //!< dla3d analyze PREFIX.csv, or sphere lists
    frames,   //!< dla3d frames PREFIX.csv: `frames` holds the options
    studio,   //!< dla3d studio: `studio` holds the options
    print,    //!< --help, --version or `options`: `text` goes to stdout, exit 0
  };
  Kind kind = Kind::run;
  //! The arguments as run, which the JSON and a checkpoint record: those given, with `--preset
  //! NAME` replaced by the preset's options.
  std::vector<std::string> words;
  RunOptions run;
  bool quiet = false;                //!< -q: no progress bar and no summary
  std::string checkpoint_path;       //!< DLA: --checkpoint FILE; empty: none
  std::string stream_path;           //!< --stream FILE (stream.h); empty: none
  double checkpoint_every = kCheckpointEvery;  //!< seconds
  std::string resume_path;
  //! An option given beside --resume that changes only how fast the run goes (--threads): it
  //! replaces the checkpoint's, given by any of `names`, with `words`.
  struct ResumeOption {
    std::vector<std::string> names, words;
  };
  std::vector<ResumeOption> resume_options;
  std::string convert_in, convert_out;
  std::vector<std::string> analyze_files;
  FramesCommand frames;
  StudioCommand studio;
  std::string text;
};

//! Parses dla3d's arguments (without the program name). Throws InvalidInput with a one-line
//! message for a flag or value that cannot work; options that need the mesh to be checked
//! (the spacing's default, seeds) are checked when the run is prepared.
CommandLine parse_command_line(const std::vector<std::string>& args);

}  // namespace dla::cli
