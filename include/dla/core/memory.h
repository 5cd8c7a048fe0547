#pragma once
//! \file memory.h
//! What this machine's memory and disks hold, for the estimates that refuse work before it
//! allocates or writes past them: one way to measure each, for every check.

#include <sys/statvfs.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace dla {

//! The memory this machine can give a process now without swapping (MemAvailable), in bytes;
//! where /proc does not say, the free pages.
inline double available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  double kib = 0.0;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  return static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

//! The memory this machine has in all, in bytes.
inline double installed_memory() {
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

//! The bytes a file written at `path` may take on its disk; infinity where that is not known.
inline double free_disk_bytes(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  struct statvfs disk;
  if (statvfs(folder.c_str(), &disk) != 0) return 1.0 / 0.0;
  return static_cast<double>(disk.f_bavail) * static_cast<double>(disk.f_frsize);
}

}  // namespace dla
