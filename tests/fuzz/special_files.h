#pragma once
// The special files every path-reading fuzz target hands its reader once, before fuzzing
// (LLVMFuzzerInitialize): a folder, a device that never ends, a FIFO no one writes (a reader
// that opened it would wait for ever), and an empty file. Each must be refused with
// InvalidInput or IOError, the empty file may read as nothing; anything else aborts.

#include "dla/core/errors.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace dla::fuzz {

//! Each special file named as the reader's format is (`extension`: ".stl"), handed to `read`.
template <class Read>
void read_special_files(const std::string& extension, Read&& read) {
  char folder[] = "/tmp/dla_fuzz_special_XXXXXX";
  if (!mkdtemp(folder)) std::abort();
  const std::string dir = folder, inner = dir + "/folder" + extension, zero = dir + "/zero" + extension,
                    fifo = dir + "/pipe" + extension, empty = dir + "/empty" + extension;
  if (mkdir(inner.c_str(), 0700) != 0 || symlink("/dev/zero", zero.c_str()) != 0 || mkfifo(fifo.c_str(), 0600) != 0)
    std::abort();
  if (FILE* file = std::fopen(empty.c_str(), "w")) std::fclose(file);
  const auto refused = [&](const std::string& path, bool may_read) {
    try {
      read(path);
      if (!may_read) std::abort();  // a folder, a device or a FIFO was read as a file
    } catch (const InvalidInput&) {
    } catch (const IOError&) {
    }
  };
  refused(inner, false);
  refused(zero, false);
  refused(fifo, false);
  refused(empty, true);
  for (const std::string& path : {zero, fifo, empty}) std::remove(path.c_str());
  rmdir(inner.c_str());
  rmdir(folder);
}

}  // namespace dla::fuzz
