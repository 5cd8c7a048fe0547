#pragma once
// Files written whole or not at all, formatted locale-free, large ones on several threads.

#include "dla/errors.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <future>
#include <limits>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

namespace dla::detail {

//! Text (and bytes) formatted into memory, with locale-free numbers so the same data gives the
//! same bytes everywhere: an OutputFile's buffer, or a part of one formatted on another thread
//! (write_in_order).
class Text {
 public:
  Text() = default;
  Text(Text&&) = default;
  Text& operator=(Text&&) = default;
  virtual ~Text() = default;

  Text& operator<<(std::string_view text) {
    buffer_ += text;
    if (buffer_.size() >= spill_at_) spill();
    return *this;
  }
  Text& operator<<(char c) {
    buffer_ += c;
    return *this;
  }
  //! A double in the shortest form that reads back exactly, or with `digits` significant digits.
  Text& number(double value, int digits = 0) {
    char text[40];
    const auto end = digits > 0 ? std::to_chars(text, text + sizeof text, value,
                                                std::chars_format::general, digits)
                                : std::to_chars(text, text + sizeof text, value);
    return *this << std::string_view(text, static_cast<std::size_t>(end.ptr - text));
  }
  //! `value` rounded to `decimals` (0-9) places, trailing zeros dropped: "-12.5", "3"; for
  //! |value| below 9e18 / 10^decimals. Integer arithmetic only: much cheaper than number().
  Text& fixed(double value, int decimals) {
    static constexpr long long powers[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000, 1000000000};
    long long units = std::llround(value * static_cast<double>(powers[decimals]));
    if (units < 0) {
      *this << '-';
      units = -units;
    }
    integer(units / powers[decimals]);
    long long fraction = units % powers[decimals];
    if (fraction == 0) return *this;
    int places = decimals;
    while (fraction % 10 == 0) fraction /= 10, --places;
    char text[16];
    for (int i = places - 1; i >= 0; --i, fraction /= 10) text[i] = static_cast<char>('0' + fraction % 10);
    return *this << '.' << std::string_view(text, static_cast<std::size_t>(places));
  }
  //! `value`'s bytes, little-endian (the only byte order dla3d builds for), for binary formats.
  template <class T>
  Text& raw(T value) {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary files are written little-endian");
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    return *this << std::string_view(bytes, sizeof value);
  }
  Text& integer(long long value) {
    char text[24];
    const auto end = std::to_chars(text, text + sizeof text, value);
    return *this << std::string_view(text, static_cast<std::size_t>(end.ptr - text));
  }

  std::string_view view() const { return buffer_; }
  void clear() { buffer_.clear(); }
  void reserve(std::size_t bytes) { buffer_.reserve(bytes); }

 protected:
  //! Called once the text reaches `spill_at_`: a file writes it out; text in memory keeps it.
  virtual void spill() {}

  std::string buffer_;
  std::size_t spill_at_ = std::numeric_limits<std::size_t>::max();
};

//! A file written under a temporary name and renamed into place on commit(), so a failed or
//! interrupted write never leaves a half-written file under the final name.
class OutputFile : public Text {
 public:
  explicit OutputFile(std::string path) : path_(std::move(path)), temp_(path_ + ".tmp") {
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_) fail();
    spill_at_ = kFlushAt;
    buffer_.reserve(kFlushAt + 256);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() override {
    if (file_) {
      std::fclose(file_);
      std::remove(temp_.c_str());
    }
  }

  //! Writes `part`, formatted elsewhere, after what this holds.
  void append(const Text& part) {
    flush();
    const std::string_view text = part.view();
    if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail();
  }

  //! Writes what is left, closes and renames the file into place.
  void commit() {
    flush();
    std::FILE* file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0) {
      std::remove(temp_.c_str());
      fail();
    }
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
      const int error = errno;
      std::remove(temp_.c_str());
      errno = error;
      fail();
    }
  }

 private:
  static constexpr std::size_t kFlushAt = 1 << 16;

  void spill() override { flush(); }
  void flush() {
    if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
      fail();
    buffer_.clear();
  }
  [[noreturn]] void fail() const {
    throw IOError("cannot write '" + path_ + "': " + std::strerror(errno));
  }

  std::string path_;
  std::string temp_;
  std::FILE* file_ = nullptr;
};

//! Threads that format the parts of a large file at once (write_in_order): the machine's.
inline int format_threads() { return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u)); }

//! Room for the text of one range of write_in_order: 4,096 particles' lines take 100-450 kB;
//! a longer range grows its buffer.
constexpr std::size_t kPartBytes = std::size_t{1} << 19;

//! Calls format(Text&, begin, end) for the items [0, count) in ranges of `chunk`, up to
//! `threads` ranges at once, each on a thread of its own, and appends their text to `out` in
//! order: the same bytes as format(out, 0, count), with a few ranges' text in memory at a time.
//! An exception from format is rethrown here, once the ranges under way have finished.
template <class Format>
void write_in_order(OutputFile& out, std::size_t count, std::size_t chunk, int threads, Format&& format) {
  // One more slot than threads: a range is ready to append while the others format. The slots'
  // buffers are reserved here and reused: fresh ones would cost a page fault every 4 kB.
  std::vector<Text> slots(static_cast<std::size_t>(std::max(threads, 1)) + 1);
  for (Text& slot : slots) slot.reserve(kPartBytes);
  std::deque<std::pair<std::future<void>, std::size_t>> pending;
  std::size_t next = 0;
  const auto start = [&](std::size_t slot) {
    const std::size_t begin = next, end = std::min(count, next + chunk);
    next = end;
    pending.emplace_back(std::async(std::launch::async, [&format, &text = slots[slot], begin, end] {
      text.clear();
      format(text, begin, end);
    }), slot);
  };
  for (std::size_t slot = 0; slot < slots.size() && next < count; ++slot) start(slot);
  while (!pending.empty()) {
    auto [formatted, slot] = std::move(pending.front());
    pending.pop_front();
    formatted.get();
    out.append(slots[slot]);
    if (next < count) start(slot);
  }
}

}  // namespace dla::detail
