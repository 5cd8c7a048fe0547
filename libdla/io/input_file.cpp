// Input files read within bounds (input_file.h).

#include "dla/io/input_file.h"

#include "dla/core/errors.h"
#include "dla/core/options.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace dla {

namespace {

std::string named(const std::string& path, std::string_view option) {
  return (option.empty() ? std::string() : "`" + std::string(option) + "` ") + "'" + path + "'";
}

//! What a file of `mode` is, when it is not a regular file; null when it is.
const char* not_a_file(mode_t mode) {
  if (S_ISREG(mode)) return nullptr;
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a pipe (FIFO)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

//! Closes a file descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

void require_regular_file(const std::string& path, std::string_view option) {
  struct stat status;
  if (::stat(path.c_str(), &status) != 0) return;
  if (const char* kind = not_a_file(status.st_mode)) throw InvalidInput(named(path, option) + " is " + kind + ", not a file");
}

std::string read_input_file(const std::string& path, std::string_view option) {
  // Opened without blocking (a FIFO put in its place since would wait for a writer), then
  // judged by what was opened.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
  struct stat status;
  if (::fstat(file.fd, &status) != 0) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
  if (const char* kind = not_a_file(status.st_mode)) throw InvalidInput(named(path, option) + " is " + kind + ", not a file");
  const auto size = static_cast<std::uint64_t>(status.st_size);
  const double free_bytes = static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (free_bytes > 0 && static_cast<double>(size) > free_bytes / 2)
    throw InvalidInput(named(path, option) + " is " + detail::format_number(static_cast<double>(size) / 1e9) +
                       " GB, more than the " + detail::format_number(free_bytes / 2e9) +
                       " GB of memory this machine has free to read it into");
  std::string bytes(size, '\0');
  std::size_t read = 0;
  while (read < size) {
    const ssize_t n = ::read(file.fd, bytes.data() + read, size - read);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
    if (n == 0) break;  // the file shrank since: what it holds now
    read += static_cast<std::size_t>(n);
  }
  bytes.resize(read);
  return bytes;
}

}  // namespace dla
