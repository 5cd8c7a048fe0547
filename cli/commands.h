#pragma once
// dla3d's subcommands, one file each; main.cpp parses the command line and calls one.

#include "command_line.h"

#include "dla/io/checkpoint.h"
#include "dla/models/growth.h"

#include <csignal>
#include <string>
#include <vector>

namespace dla::cli {

//! Grows and writes the files; with `resumed`, grows on from that checkpoint, whose command
//! `args` then is. `stop` and `stop_signal` are set by SIGINT and SIGTERM (main.cpp). Throws
//! InvalidInput, before growing and writing anything, for options that cannot work with the
//! mesh or this machine. Returns the exit code:
//! 0, 1 when growth failed part way (the files hold what grew, marked incomplete), or
//! 128 + the signal when stopped.
int grow(const GrowCommand& command, const std::vector<std::string>& args, const Checkpoint* resumed,
         const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal);

//! `dla3d colonize`: grows a tree by space colonization and writes the files, as grow() does
//! (without checkpoints). Returns 0, or 128 + the signal when stopped.
int colonize(const ColonizeCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
             const volatile std::sig_atomic_t& stop_signal);

//! `dla3d eden`: grows an Eden cluster and writes the files, as colonize() does. Returns 0, or
//! 128 + the signal when stopped.
int eden(const EdenCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
         const volatile std::sig_atomic_t& stop_signal);

//! `dla3d drop`: grows by random-drop ballistic aggregation and writes the files, as colonize()
//! does. Returns 0, 1 when the structure outgrew the index (the files hold what grew), or
//! 128 + the signal when stopped.
int drop(const DropCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
         const volatile std::sig_atomic_t& stop_signal);

//! `dla3d ballistic`: grows by ballistic aggregation and writes the files, as drop() does.
int ballistic(const BallisticCommand& command, const std::vector<std::string>& args, const StopFlag& stop,
              const volatile std::sig_atomic_t& stop_signal);

//! `dla3d convert IN OUT.stl`: the project's own mesh reading, to make bust.stl at setup.
int convert(const std::string& in, const std::string& out, bool quiet);

//! `dla3d frames PREFIX.csv --count K`: K files of each format, frame k holding the seeds and
//! k/K of the other particles. Returns 0, or 128 + the signal when stopped between frames.
int frames(const FramesCommand& command, const StopFlag& stop, const volatile std::sig_atomic_t& stop_signal);

//! `dla3d analyze PREFIX.csv`: the fractal dimension of a grown structure, as JSON on stdout.
int analyze(const std::string& path);

}  // namespace dla::cli
