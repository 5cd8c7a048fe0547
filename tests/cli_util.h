#pragma once
// Runs dla3d as a user does, through the shell, in a test's scratch folder.

#include "test_util.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
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

//! Starts `dla3d WORDS` in `dir`, stderr to err.txt, stdout dropped: its process id, or -1.
//! With `shell`, WORDS are one line of arguments as /bin/sh reads them, and the shell execs
//! dla3d with them (its process id is dla3d's).
inline pid_t start_dla3d(const ScratchDir& dir, const std::vector<std::string>& words, bool shell = false) {
  std::vector<std::string> argv_words{DLA3D_PATH};
  argv_words.insert(argv_words.end(), words.begin(), words.end());
  if (shell) argv_words = {"/bin/sh", "-c", "exec '" DLA3D_PATH "' " + (words.empty() ? "" : words.front())};
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
  return spawned == 0 ? pid : -1;
}

//! The processor time, in seconds, `dla3d WORDS` takes to run to its end in `dir`: how far
//! into a run its stages lie, on this build and machine.
inline double cpu_seconds_of_run(const ScratchDir& dir, const std::vector<std::string>& words) {
  const pid_t pid = start_dla3d(dir, words);
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

//! How an interrupted run ended.
struct InterruptedRun {
  int exit_code = -1;        //!< 128 + the signal when it stopped as asked; -1: not by exit()
  bool signalled = false;    //!< the signal was sent (the run had not ended before)
  double exit_seconds = 0;   //!< from the signal to the exit, wall-clock
};

//! Starts `dla3d WORDS` in `dir` (stderr to err.txt) and sends it `signal` once it catches that
//! signal (its handler is installed just before growth), has done `work` seconds of processor
//! time, which load on the machine does not shorten, and, if `exists` is named, once that file
//! is in `dir` (a file the run writes: the event of its stage). `shell`: as start_dla3d.
inline InterruptedRun interrupt_run(const ScratchDir& dir, const std::vector<std::string>& words, int signal,
                                 double work = 0.0, const std::string& exists = "", bool shell = false) {
  InterruptedRun ended;
  const pid_t pid = start_dla3d(dir, words, shell);
  if (pid < 0) return ended;
  int status = 0;
  while (!catches(pid, signal) || cpu_seconds(pid) < work || (!exists.empty() && !std::filesystem::exists(dir / exists))) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      ended.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      return ended;
    }
    usleep(2000);
  }
  const auto sent = std::chrono::steady_clock::now();
  kill(pid, signal);
  ended.signalled = true;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ended.exit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  ended.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return ended;
}

//! interrupt_run's exit code.
inline int interrupted(const ScratchDir& dir, const std::vector<std::string>& words, int signal, double work = 0.0,
                       const std::string& exists = "") {
  return interrupt_run(dir, words, signal, work, exists).exit_code;
}

}  // namespace dla::testing
