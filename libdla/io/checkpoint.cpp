// Layout (little-endian): the magic "DLA3D-CHECKPOINT", version, input hash, the command's
// words, the cluster's header, its particles (x, y, z as doubles; parent, seed as int32), its
// walk statistics, and the FNV-1a hash of all that.

#include "dla/io/checkpoint.h"

#include "dla/core/input_file.h"

#include "output_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>
#include <vector>

namespace dla {

namespace {

constexpr std::string_view kMagic = "DLA3D-CHECKPOINT";
constexpr std::uint32_t kVersion = 1;

//! Writes to the file through a buffer, hashing every byte: the checkpoint streams, whatever
//! the structure's size.
class Writer {
 public:
  explicit Writer(detail::OutputFile& file) : file_(file) { buffer_.reserve(kChunk + 64); }
  template <class T>
  void put(const T& value) {
    buffer_.append(reinterpret_cast<const char*>(&value), sizeof value);
    if (buffer_.size() >= kChunk) flush();
  }
  void put_bytes(std::string_view bytes) {
    buffer_ += bytes;
    if (buffer_.size() >= kChunk) flush();
  }
  //! Writes what is buffered and the hash of everything.
  void finish() {
    flush();
    const std::uint64_t hash = hash_;
    file_ << std::string_view(reinterpret_cast<const char*>(&hash), sizeof hash);
  }

 private:
  static constexpr std::size_t kChunk = 1 << 16;
  void flush() {
    hash_ = fnv1a(buffer_, hash_);
    file_ << buffer_;
    buffer_.clear();
  }
  detail::OutputFile& file_;
  std::string buffer_;
  std::uint64_t hash_ = fnv1a({});
};

//! Reads a checkpoint through a buffer, hashing every byte but the last eight (the stored
//! hash): memory stays that of the structure read, not of the file besides.
class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    std::uint64_t size = 0;
    in_.reset(open_input_file(path, "", size));
    body_ = size < 8 ? 0 : size - 8;  // too short: no magic
  }
  template <class T>
  T get() {
    T value;
    read(reinterpret_cast<char*>(&value), sizeof value);
    return value;
  }
  void read(char* to, std::size_t n) {
    if (n > body_ - at_ || std::fread(to, 1, n, in_.get()) != n) damaged();
    hash_ = fnv1a(std::string_view(to, n), hash_);
    at_ += n;
  }
  //! Refuses a count whose items (of at least `size` bytes each) the file cannot hold.
  std::uint64_t count(std::size_t size) {
    const auto n = get<std::uint64_t>();
    if (n > (body_ - at_) / size) damaged();
    return n;
  }
  //! Checks that the body is all read and its hash is the one stored after it.
  void finish() {
    std::uint64_t stored = 0;
    if (at_ != body_ || std::fread(&stored, 1, sizeof stored, in_.get()) != sizeof stored || stored != hash_) damaged();
  }
  [[noreturn]] void damaged() const { throw InvalidInput(path_ + ": the checkpoint is cut short or damaged"); }

 private:
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in_{nullptr, &std::fclose};
  const std::string& path_;
  std::uint64_t body_ = 0;  // bytes before the stored hash
  std::uint64_t at_ = 0;
  std::uint64_t hash_ = fnv1a({});
};

}  // namespace

void write_checkpoint(const Checkpoint& checkpoint, const std::string& path) {
  const Cluster& c = checkpoint.cluster;
  detail::OutputFile file(path);
  Writer out(file);
  out.put_bytes(kMagic);
  out.put(kVersion);
  out.put(checkpoint.input_hash);
  out.put(static_cast<std::uint64_t>(checkpoint.command.size()));
  for (const std::string& word : checkpoint.command) {
    out.put(static_cast<std::uint64_t>(word.size()));
    out.put_bytes(word);
  }
  out.put(static_cast<std::uint64_t>(c.seed_count));
  out.put(c.spacing);
  out.put(static_cast<std::int32_t>(c.dimensions));
  for (int a = 0; a < 3; ++a) out.put(c.center[a]);
  const WalkStats& s = checkpoint.walk;
  for (std::uint64_t v : {s.walkers, s.steps, s.near_steps, s.contacts, s.returns, s.relaunches, s.lost, s.rejected,
                          s.clipped})
    out.put(v);
  out.put(static_cast<std::uint64_t>(c.particles.size()));
  for (const Particle& p : c.particles) {
    for (int a = 0; a < 3; ++a) out.put(p.position[a]);
    out.put(p.parent);
    out.put(p.seed);
  }
  out.finish();
  file.commit();
}

Checkpoint read_checkpoint(const std::string& path) {
  Reader r(path);
  std::string magic(kMagic.size(), '\0');
  try {
    r.read(magic.data(), magic.size());
  } catch (const InvalidInput&) {
    magic.clear();
  }
  if (magic != kMagic) throw InvalidInput(path + ": is not a dla3d checkpoint");
  if (r.get<std::uint32_t>() != kVersion) throw InvalidInput(path + ": was written by another version of dla3d");
  Checkpoint checkpoint;
  checkpoint.input_hash = r.get<std::uint64_t>();
  const std::uint64_t words = r.count(8);
  for (std::uint64_t i = 0; i < words; ++i) {
    std::string word(r.count(1), '\0');
    r.read(word.data(), word.size());
    checkpoint.command.push_back(std::move(word));
  }
  Cluster& c = checkpoint.cluster;
  c.seed_count = r.get<std::uint64_t>();
  c.spacing = r.get<double>();
  c.dimensions = r.get<std::int32_t>();
  for (int a = 0; a < 3; ++a) c.center[a] = r.get<double>();
  WalkStats& s = checkpoint.walk;
  for (std::uint64_t* v : {&s.walkers, &s.steps, &s.near_steps, &s.contacts, &s.returns, &s.relaunches, &s.lost,
                           &s.rejected, &s.clipped})
    *v = r.get<std::uint64_t>();
  const std::uint64_t particles = r.count(32);
  c.particles.resize(particles);
  constexpr std::size_t kBlock = 4096, kBytes = 32;  // particles read at once, bytes each
  std::vector<char> block(kBlock * kBytes);
  for (std::size_t first = 0; first < particles; first += kBlock) {
    const std::size_t count = std::min<std::size_t>(kBlock, particles - first);
    r.read(block.data(), count * kBytes);
    for (std::size_t i = 0; i < count; ++i) {
      Particle& p = c.particles[first + i];
      const char* bytes = block.data() + i * kBytes;
      std::memcpy(p.position.data(), bytes, 24);
      std::memcpy(&p.parent, bytes + 24, 4);
      std::memcpy(&p.seed, bytes + 28, 4);
    }
  }
  r.finish();
  if (c.seed_count > particles) r.damaged();
  c.complete = false;
  return checkpoint;
}

}  // namespace dla
