// Input files read within bounds (input_file.h).

#include "dla/core/memory.h"
#include "dla/core/input_file.h"

#include "dla/core/errors.h"
#include "dla/core/options.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

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

std::FILE* open_input_file(const std::string& path, std::string_view option, std::uint64_t& size) {
  // Opened without blocking (a FIFO put in its place since would wait for a writer), then
  // judged by what was opened.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
  struct stat status;
  if (::fstat(file.fd, &status) != 0) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
  if (const char* kind = not_a_file(status.st_mode)) throw InvalidInput(named(path, option) + " is " + kind + ", not a file");
  size = static_cast<std::uint64_t>(status.st_size);
  std::FILE* stream = ::fdopen(file.fd, "rb");
  if (!stream) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
  file.fd = -1;  // the stream's now
  return stream;
}

std::string read_input_file(const std::string& path, std::string_view option) {
  std::uint64_t size = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(open_input_file(path, option, size), &std::fclose);
  const double free_bytes = available_memory();
  if (free_bytes > 0 && static_cast<double>(size) > free_bytes / 2)
    throw InvalidInput(named(path, option) + " is " + detail::format_number(static_cast<double>(size) / 1e9) +
                       " GB, more than the " + detail::format_number(free_bytes / 2e9) +
                       " GB of memory this machine has free to read it into");
  std::string bytes(size, '\0');
  std::size_t read = 0;
  while (read < size) {
    const std::size_t n = std::fread(bytes.data() + read, 1, size - read, file.get());
    if (n == 0 && std::ferror(file.get())) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
    if (n == 0) break;  // the file shrank since: what it holds now
    read += n;
  }
  bytes.resize(read);
  return bytes;
}

}  // namespace dla
