#pragma once
// Runs dla3d as a user does, through the shell, in a test's scratch folder.

#include "test_util.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace dla::testing {

struct CliRun {
  int exit_code;    //!< -1 if it did not exit (a signal ended it)
  std::string err;  //!< what it wrote on stderr
};

//! Runs `dla3d ARGS` (ARGS as /bin/sh reads them) in `dir`, after `setup` (shell commands
//! ending in `;` or `&&`, such as a ulimit); stdout is dropped.
inline CliRun dla3d(const ScratchDir& dir, const std::string& args, const std::string& setup = "") {
  const std::string command = "cd '" + dir.path().string() + "' && " + setup + " '" DLA3D_PATH "' " + args +
                              " > out.txt 2> err.txt";
  const int status = std::system(command.c_str());
  CliRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(dir / "err.txt")};
  std::filesystem::remove(dir / "out.txt");
  std::filesystem::remove(dir / "err.txt");
  return run;
}

}  // namespace dla::testing
