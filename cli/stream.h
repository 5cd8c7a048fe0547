#pragma once
// --stream FILE: each particle as it attaches, for a live view (the studio, docs/studio.md), in
// frames written at every progress update (about twenty a second) and flushed at once.
//
// A frame, little-endian: "DLAs", u32 count, u64 first (the index of its first particle), u64
// done and u64 total (as the progress bar counts them), then count x 3 float32 positions and
// count int32 parents (-1: a seed). Frames follow in order, and a resumed run starts again at
// particle 0, so a reader writes each frame at `first`.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace dla::cli {

//! Bad input, before a mesh's set-up and a long run: a folder, or a file in a folder that is not
//! there. The file is made only once the run is known good (bad input leaves no file).
inline void check_stream_path(const std::string& path) {
  if (path.empty()) return;
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InvalidInput("--stream '" + path + "' is a folder, not a file");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder, error))
    throw InvalidInput("--stream '" + path + "': there is no folder '" + folder.string() + "'");
}

class ParticleStream {
 public:
  //! No stream for an empty path. Throws IOError if FILE cannot be opened for writing.
  explicit ParticleStream(const std::string& path) : path_(path) {
    if (path.empty()) return;
    file_ = std::fopen(path.c_str(), "wb");
    if (!file_) throw IOError("--stream " + path + ": " + std::strerror(errno));
  }
  ParticleStream(const ParticleStream&) = delete;
  ParticleStream& operator=(const ParticleStream&) = delete;
  ~ParticleStream() {
    if (file_) std::fclose(file_);
  }

  //! Bad input found only once growth began (a colonize root outside its vessel): the stream
  //! file goes, as every other file of bad input does. A pipe or device is left as it is.
  void discard() {
    std::error_code error;
    if (!path_.empty() && std::filesystem::is_regular_file(path_, error)) std::filesystem::remove(path_, error);
    if (file_) std::fclose(file_);
    file_ = nullptr;
  }

  //! The particles of `so_far` not yet sent, with the run's count. A reader that went away (a
  //! closed pipe) ends the stream, never the run.
  void send(const Cluster& so_far, std::size_t done, std::size_t total) {
    if (!file_) return;
    const std::size_t count = so_far.particles.size() - std::min(sent_, so_far.particles.size());
    if (count == 0 && done == last_done_) return;
    const std::uint32_t count32 = static_cast<std::uint32_t>(count);
    const std::uint64_t head[3] = {sent_, done, total};
    positions_.resize(count * 3);
    parents_.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Particle& p = so_far.particles[sent_ + i];
      for (int axis = 0; axis < 3; ++axis) positions_[3 * i + axis] = static_cast<float>(p.position[axis]);
      parents_[i] = p.parent;
    }
    const bool written = std::fwrite("DLAs", 1, 4, file_) == 4 && std::fwrite(&count32, 4, 1, file_) == 1 &&
                         std::fwrite(head, 8, 3, file_) == 3 &&
                         std::fwrite(positions_.data(), 4, positions_.size(), file_) == positions_.size() &&
                         std::fwrite(parents_.data(), 4, count, file_) == count && std::fflush(file_) == 0;
    if (!written) {
      std::fclose(file_);
      file_ = nullptr;
      return;
    }
    sent_ += count;
    last_done_ = done;
  }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::size_t sent_ = 0, last_done_ = static_cast<std::size_t>(-1);
  std::vector<float> positions_;
  std::vector<std::int32_t> parents_;
};

}  // namespace dla::cli
