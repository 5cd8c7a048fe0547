#pragma once
// dla3d's subcommands, one file each; main.cpp parses the command line and calls one.

#include "command_line.h"

#include "dla/io/checkpoint.h"
#include "dla/models/growth.h"

#include <csignal>
#include <string>
#include <vector>

namespace dla::cli {

//! `dla3d [options]`: grows `line.grow` by DLA and writes the files; with `resumed`, grows on
//! from that checkpoint, whose command `args` then is. `stop` and `stop_signal` are set by
//! SIGINT and SIGTERM (main.cpp). Throws InvalidInput, before growing and writing anything, for
//! options that cannot work with the mesh or this machine. Returns the exit code: 0, 1 when
//! growth failed part way (the files hold what grew, marked incomplete), or 128 + the signal
//! when stopped.
int grow(const CommandLine& line, const std::vector<std::string>& args, const Checkpoint* resumed,
         const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal);

//! `dla3d colonize`, `eden`, `drop` and `ballistic`: grows the model `line` names and writes
//! the files, as grow() does (without checkpoints). Returns 0, 1 when growth failed part way
//! (drop's structure outgrew its index, say; the files hold what grew), or 128 + the signal
//! when stopped.
int run_model(const CommandLine& line, const std::vector<std::string>& args, const StopFlag& stop,
              const volatile std::sig_atomic_t& stop_signal);

//! `dla3d convert IN OUT.stl`: the project's own mesh reading, to make bust.stl at setup.
int convert(const std::string& in, const std::string& out, bool quiet);

//! `dla3d frames PREFIX.csv --count K`: K files of each format, frame k holding the seeds and
//! k/K of the other particles. Returns 0, or 128 + the signal when stopped between frames.
int frames(const FramesCommand& command, const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal);

//! `dla3d analyze PREFIX.csv`: the fractal dimension of a grown structure, as JSON on stdout.
int analyze(const std::string& path);

}  // namespace dla::cli
