#pragma once
// dla3d's subcommands, one file each; main.cpp parses the command line and calls one.

#include "command_line.h"

#include "dla/core/cluster.h"
#include "dla/run/run.h"

#include <csignal>
#include <cstdint>
#include <string>
#include <vector>

namespace dla::cli {

//! What SIGINT and SIGTERM set (main.cpp): the first signal `first`, a second one `second`
//! too, and `signal` the number of the last. The first ends the stage it comes in; if that
//! stage was growth or links, what grew is written, and a second signal ends that too.
struct StopSignals {
  StopFlag first{false};
  StopFlag second{false};
  volatile std::sig_atomic_t signal = 0;
};

//! Grows the run `line` asks for, of any model, and writes its files; with `resumed`, a DLA
//! run grows on from its checkpoint's structure, and `args` are the checkpoint's command.
//! Throws InvalidInput, before growing and writing anything, for options that cannot work with
//! the meshes or this machine. Returns the exit code: 0, 1 when growth failed part way (the
//! files hold what grew, marked incomplete), or 128 + the signal when stopped.
int run(const CommandLine& line, const std::vector<std::string>& args, const Resumed& resumed, const StopSignals& stop);

//! `dla3d convert IN OUT.stl`: the project's own mesh reading, to make bust.stl at setup.
int convert(const std::string& in, const std::string& out, bool quiet);

//! `dla3d frames PREFIX.csv --count K`: K files of each format, frame k holding the seeds and
//! k/K of the other particles. Returns 0, or 128 + the signal when stopped: the frames written
//! before it are whole, and none of the frame under way is left.
int frames(const FramesCommand& command, bool quiet, const StopSignals& stop);

//! `dla3d analyze PREFIX.csv`: the fractal dimension of a grown structure, as JSON on stdout;
//! `dla3d analyze A_spheres.csv B_spheres.csv ...`: D_f and k_f of aggregates' sphere lists.
int analyze(const std::vector<std::string>& paths);

//! `dla3d studio`: runs the studio's server (studio/server.py, installed beside dla3d) in
//! Python in place of this process, so that Ctrl-C and SIGTERM reach it. Returns only on
//! failure, by throwing IOError.
int studio(const StudioCommand& command);

}  // namespace dla::cli
