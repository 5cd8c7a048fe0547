#pragma once
// Runs dla3d as a user does, through the shell, in a test's scratch folder.

#include "test_util.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

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

//! Whether process `pid` has a handler installed for `signal` (its SigCgt mask in /proc).
inline bool catches(pid_t pid, int signal) {
  std::istringstream status(read_file("/proc/" + std::to_string(pid) + "/status"));
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1u;
  return false;
}

//! The processor time process `pid` has used, in seconds (/proc's utime and stime).
inline double cpu_seconds(pid_t pid) {
  const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
  std::istringstream fields(stat.substr(stat.rfind(')') + 2));  // after the command's name
  std::string field;
  for (int k = 3; k < 14; ++k) fields >> field;  // state ... cmajflt: fields 3 to 13
  double user = 0, system = 0;
  fields >> user >> system;
  return (user + system) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

//! Starts `dla3d WORDS` in `dir` (stderr to err.txt) and sends it `signal` once it catches that
//! signal (its handler is installed just before growth), has done `work` seconds of processor
//! time, which load on the machine does not shorten, and, if `exists` is named, once that file
//! is in `dir` (a file the run writes: the event of its stage). Returns its exit code: 128 +
//! the signal when it stopped as asked, or -1 if it did not exit by itself.
inline int interrupted(const ScratchDir& dir, const std::vector<std::string>& words, int signal, double work = 0.0,
                       const std::string& exists = "") {
  std::vector<std::string> argv_words{DLA3D_PATH};
  argv_words.insert(argv_words.end(), words.begin(), words.end());
  std::vector<char*> argv;
  for (std::string& word : argv_words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  const std::string err = dir / "err.txt";
  posix_spawn_file_actions_addopen(&files, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());  // the files land in the scratch folder
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ);
  std::filesystem::current_path(before);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return -1;
  int status = 0;
  while (!catches(pid, signal) || cpu_seconds(pid) < work || (!exists.empty() && !std::filesystem::exists(dir / exists))) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    usleep(2000);
  }
  kill(pid, signal);
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace dla::testing
