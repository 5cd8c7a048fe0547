// Layout (little-endian): the magic "DLA3D-CHECKPOINT", version, input hash, the command's
// words, the cluster's header, its particles (x, y, z as doubles; parent, seed as int32), its
// walk statistics, and the FNV-1a hash of all that.

#include "dla/checkpoint.h"

#include "output_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>

namespace dla {

namespace {

constexpr std::string_view kMagic = "DLA3D-CHECKPOINT";
constexpr std::uint32_t kVersion = 1;

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

class Reader {
 public:
  Reader(std::string_view bytes, const std::string& path) : bytes_(bytes), path_(path) {}
  template <class T>
  T get() {
    T value;
    need(sizeof value);
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }
  std::string_view take(std::size_t n) {
    need(n);
    const std::string_view part = bytes_.substr(at_, n);
    at_ += n;
    return part;
  }
  //! Refuses a count whose items (of at least `size` bytes each) the file cannot hold.
  std::uint64_t count(std::size_t size) {
    const auto n = get<std::uint64_t>();
    if (n > (bytes_.size() - at_) / size) damaged();
    return n;
  }
  std::size_t at() const { return at_; }
  [[noreturn]] void damaged() const { throw InvalidInput(path_ + ": the checkpoint is cut short or damaged"); }

 private:
  void need(std::size_t n) const {
    if (n > bytes_.size() - at_) damaged();
  }
  std::string_view bytes_;
  const std::string& path_;
  std::size_t at_ = 0;
};

}  // namespace

void write_checkpoint(const Checkpoint& checkpoint, const std::string& path) {
  const Cluster& c = checkpoint.cluster;
  std::string out;
  out.reserve(128 + 32 * c.particles.size());
  out += kMagic;
  put(out, kVersion);
  put(out, checkpoint.input_hash);
  put(out, static_cast<std::uint64_t>(checkpoint.command.size()));
  for (const std::string& word : checkpoint.command) {
    put(out, static_cast<std::uint64_t>(word.size()));
    out += word;
  }
  put(out, static_cast<std::uint64_t>(c.seed_count));
  put(out, c.spacing);
  put(out, static_cast<std::int32_t>(c.dimensions));
  for (int a = 0; a < 3; ++a) put(out, c.center[a]);
  const WalkStats& s = c.stats;
  for (std::uint64_t v : {s.walkers, s.steps, s.near_steps, s.contacts, s.returns, s.relaunches, s.lost, s.rejected,
                          s.clipped})
    put(out, v);
  put(out, static_cast<std::uint64_t>(c.particles.size()));
  for (const Particle& p : c.particles) {
    for (int a = 0; a < 3; ++a) put(out, p.position[a]);
    put(out, p.parent);
    put(out, p.seed);
  }
  put(out, fnv1a(out));
  detail::OutputFile file(path);
  file << out;
  file.commit();
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError("cannot read '" + path + "': " + std::strerror(errno));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.compare(0, kMagic.size(), kMagic) != 0) throw InvalidInput(path + ": is not a dla3d checkpoint");
  if (bytes.size() < kMagic.size() + 8) throw InvalidInput(path + ": the checkpoint is cut short or damaged");
  const std::string_view body(bytes.data(), bytes.size() - 8);
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + body.size(), 8);
  if (fnv1a(body) != stored) throw InvalidInput(path + ": the checkpoint is cut short or damaged");

  Reader r(body, path);
  r.take(kMagic.size());
  if (r.get<std::uint32_t>() != kVersion) throw InvalidInput(path + ": was written by another version of dla3d");
  Checkpoint checkpoint;
  checkpoint.input_hash = r.get<std::uint64_t>();
  const std::uint64_t words = r.count(8);
  for (std::uint64_t i = 0; i < words; ++i) {
    const std::uint64_t length = r.count(1);
    checkpoint.command.emplace_back(r.take(length));
  }
  Cluster& c = checkpoint.cluster;
  c.seed_count = r.get<std::uint64_t>();
  c.spacing = r.get<double>();
  c.dimensions = r.get<std::int32_t>();
  for (int a = 0; a < 3; ++a) c.center[a] = r.get<double>();
  WalkStats& s = c.stats;
  for (std::uint64_t* v : {&s.walkers, &s.steps, &s.near_steps, &s.contacts, &s.returns, &s.relaunches, &s.lost,
                           &s.rejected, &s.clipped})
    *v = r.get<std::uint64_t>();
  const std::uint64_t particles = r.count(32);
  c.particles.resize(particles);
  for (Particle& p : c.particles) {
    for (int a = 0; a < 3; ++a) p.position[a] = r.get<double>();
    p.parent = r.get<std::int32_t>();
    p.seed = r.get<std::int32_t>();
  }
  if (r.at() != body.size() || c.seed_count > particles) r.damaged();
  c.complete = false;
  return checkpoint;
}

}  // namespace dla
