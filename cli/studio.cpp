// `dla3d studio`: the growth studio (docs/studio.md). Its web server is Python's aiohttp
// (studio/server.py), which runs this same dla3d for each growth, so the studio's files are the
// command line's; this subcommand only finds the server and hands over to it.

#include "commands.h"

#include "dla/core/errors.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace dla::cli {

int studio(const StudioCommand& command) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) throw IOError("cannot find where dla3d is: " + error.message());
  // The build tree keeps the studio beside dla3d; `cmake --install` puts it in share/.
  fs::path server;
  for (const fs::path& candidate : {self.parent_path() / "studio" / "server.py",
                                    self.parent_path().parent_path() / "share" / "dla3d" / "studio" / "server.py"})
    if (fs::is_regular_file(candidate, error)) {
      server = candidate;
      break;
    }
  if (server.empty())
    throw IOError("the studio's files are not beside " + self.string() + " (studio/server.py, or ../share/dla3d/studio)");
  // Debian's Python, which has python3-aiohttp, whatever python3 comes first on the PATH.
  std::vector<std::string> words = {"/usr/bin/python3", "-I", server.string(), "--dla3d", self.string(), "--host", command.host,
                                    "--port", std::to_string(command.port)};
  if (command.open) words.push_back("--open");
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  // Python's start-up turns a Ctrl-C into a fatal error; held blocked across execv, a stop
  // signal waits for server.py, which unblocks it once it can end quietly.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigset_t unblocked;
  sigprocmask(SIG_BLOCK, &stop_signals, &unblocked);
  execv(argv.front(), argv.data());
  sigprocmask(SIG_SETMASK, &unblocked, nullptr);
  throw IOError(std::string("cannot run /usr/bin/python3 for the studio: ") + std::strerror(errno));
}

}  // namespace dla::cli
