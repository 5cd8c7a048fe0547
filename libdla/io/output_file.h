#pragma once
// Files written whole or not at all, formatted locale-free, large ones on several threads.

#include "dla/core/errors.h"
#include "dla/core/stop.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <unistd.h>

namespace dla::detail {

//! Text (and bytes) formatted into memory, with locale-free numbers so the same data gives the
//! same bytes everywhere: an OutputFile's buffer, or a part of one formatted on another thread
//! (write_in_order). Numbers are formatted straight into the buffer: the writers of 10^7
//! particles make 10^8 of them, and a std::string's append per piece cost a third of the time.
class Text {
 public:
  Text() = default;
  Text(Text&&) = default;
  Text& operator=(Text&&) = default;
  virtual ~Text() = default;

  Text& operator<<(std::string_view text) {
    if (text.empty()) return *this;  // memcpy's pointers must not be null, even for no bytes
    std::memcpy(room(text.size()), text.data(), text.size());
    used_ += text.size();
    return *this;
  }
  Text& operator<<(char c) {
    *room(1) = c;
    ++used_;
    return *this;
  }
  //! A double in the shortest form that reads back exactly, or with `digits` significant digits.
  Text& number(double value, int digits = 0) {
    char* at = room(kNumberBytes);
    const auto end = digits > 0 ? std::to_chars(at, at + kNumberBytes, value, std::chars_format::general, digits)
                                : std::to_chars(at, at + kNumberBytes, value);
    return advance_to(end.ptr);
  }
  //! A float in the shortest form that reads back as the same float: what a binary file holds,
  //! in about half the characters and time of number(value, 9).
  Text& float_number(float value) {
    char* at = room(kNumberBytes);
    return advance_to(std::to_chars(at, at + kNumberBytes, value).ptr);
  }
  //! `value` rounded to `decimals` (0-9) places, trailing zeros dropped: "-12.5", "3"; for
  //! |value| below 9e18 / 10^decimals. Integer arithmetic only: much cheaper than number().
  Text& fixed(double value, int decimals) {
    static constexpr double scales[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
    // std::llround, without its call into libm: x minus its truncation is exact in a double.
    const double scaled = value * scales[decimals];
    const auto truncated = static_cast<long long>(scaled);
    const double fraction = scaled - static_cast<double>(truncated);
    const long long units = truncated + (fraction >= 0.5) - (fraction <= -0.5);
    char* at = room(kNumberBytes);
    if (units < 0) *at++ = '-';
    const auto magnitude = static_cast<unsigned long long>(units < 0 ? -units : units);
    // A division by a constant is a multiplication; by a variable it took a fifth of the time.
    switch (decimals) {
      case 0: return advance_to(std::to_chars(at, at + 20, magnitude).ptr);
      case 1: return advance_to(write_fixed<10>(at, magnitude, 1));
      case 2: return advance_to(write_fixed<100>(at, magnitude, 2));
      case 3: return advance_to(write_fixed<1000>(at, magnitude, 3));
      case 4: return advance_to(write_fixed<10000>(at, magnitude, 4));
      case 5: return advance_to(write_fixed<100000>(at, magnitude, 5));
      case 6: return advance_to(write_fixed<1000000>(at, magnitude, 6));
      case 7: return advance_to(write_fixed<10000000>(at, magnitude, 7));
      case 8: return advance_to(write_fixed<100000000>(at, magnitude, 8));
      default: return advance_to(write_fixed<1000000000>(at, magnitude, 9));
    }
  }
  //! `value`'s bytes, little-endian (the only byte order dla3d builds for), for binary formats.
  template <class T>
  Text& raw(T value) {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary files are written little-endian");
    std::memcpy(room(sizeof value), &value, sizeof value);
    used_ += sizeof value;
    return *this;
  }
  Text& integer(long long value) {
    char* at = room(kNumberBytes);
    return advance_to(std::to_chars(at, at + kNumberBytes, value).ptr);
  }

  std::string_view view() const { return {bytes_.get(), used_}; }
  void clear() { used_ = 0; }
  void reserve(std::size_t bytes) {
    if (bytes > capacity_) grow(bytes);
  }

 protected:
  //! Makes room for `bytes` more after the text when it is full: text in memory grows, a file
  //! writes out what it holds.
  virtual void make_room(std::size_t bytes) { grow(std::max(used_ + bytes, 2 * capacity_)); }

  void grow(std::size_t capacity) {
    // Not std::make_unique: that would zero the bytes, a page fault each 4 kB for nothing.
    std::unique_ptr<char[]> bigger(new char[capacity]);
    if (used_ > 0) std::memcpy(bigger.get(), bytes_.get(), used_);
    bytes_ = std::move(bigger);
    capacity_ = capacity;
  }

  std::unique_ptr<char[]> bytes_;
  std::size_t used_ = 0;
  std::size_t capacity_ = 0;

 private:
  //! Enough for any number this class writes: a double's shortest form takes at most 24
  //! characters, one with 17 digits at most 24, an integer at most 20.
  static constexpr std::size_t kNumberBytes = 32;

  //! The free bytes after the text, at least `bytes` of them.
  char* room(std::size_t bytes) {
    if (capacity_ - used_ < bytes) make_room(bytes);
    return bytes_.get() + used_;
  }
  //! Writes `units` / Scale with `places` decimals, trailing zeros dropped; returns the end.
  template <unsigned long long Scale>
  static char* write_fixed(char* at, unsigned long long units, int places) {
    at = std::to_chars(at, at + 20, units / Scale).ptr;
    unsigned long long fraction = units % Scale;
    if (fraction == 0) return at;
    while (fraction % 10 == 0) fraction /= 10, --places;
    *at++ = '.';
    for (int i = places - 1; i >= 0; --i, fraction /= 10) at[i] = static_cast<char>('0' + fraction % 10);
    return at + places;
  }
  Text& advance_to(const char* end) {
    used_ = static_cast<std::size_t>(end - bytes_.get());
    return *this;
  }
};

//! A file written under a temporary name and renamed into place on commit(), so a failed or
//! interrupted write never leaves a half-written file under the final name. Throws Interrupted
//! once the flag of this thread's StopScope (stop.h) is set.
class OutputFile : public Text {
 public:
  explicit OutputFile(std::string path) : path_(std::move(path)), temp_(path_ + ".tmp") {
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_) fail();
    reserve(kBufferBytes);
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

  //! Writes `bytes` at `offset` from the file's start, past or over what was written, without
  //! moving where appends go: for a format whose parts are made together but lie apart.
  void write_at(std::uint64_t offset, std::string_view bytes) {
    flush();
    if (std::fflush(file_) != 0) fail();
    const int descriptor = fileno(file_);
    while (!bytes.empty()) {
      const ssize_t written = ::pwrite(descriptor, bytes.data(), bytes.size(), static_cast<off_t>(offset));
      if (written <= 0) {
        if (written < 0 && errno == EINTR) continue;
        if (written == 0) errno = EIO;
        fail();
      }
      bytes.remove_prefix(static_cast<std::size_t>(written));
      offset += static_cast<std::uint64_t>(written);
    }
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
  static constexpr std::size_t kBufferBytes = 1 << 16;

  void make_room(std::size_t bytes) override {
    flush();
    reserve(bytes);
  }
  //! Where the writing of every format stops once its StopScope's flag is set: before each
  //! 64 kB written, and before the rename.
  void flush() {
    throw_if_stopped("writing ", path_);
    if (used_ > 0 && std::fwrite(bytes_.get(), 1, used_, file_) != used_) fail();
    used_ = 0;
  }
  [[noreturn]] void fail() const {
    throw IOError("cannot write '" + path_ + "': " + std::strerror(errno));
  }

  std::string path_;
  std::string temp_;
  std::FILE* file_ = nullptr;
};

//! Waits for every task, then rethrows the first failure: `first` if this thread's own part
//! failed, else the earliest task's. A writer that fails loses no other writer's file.
inline void finish_all(std::vector<std::future<void>>& tasks, std::exception_ptr first = nullptr) {
  for (std::future<void>& task : tasks) {
    try {
      task.get();
    } catch (...) {
      if (!first) first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
}

//! Threads that format the parts of a large file at once (OrderedBatches): the machine's.
inline int format_threads() { return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u)); }

//! Room for the text of one batch of OrderedBatches: 4,096 particles' lines (a range of
//! write_in_order) take 100-450 kB; a longer batch grows its buffer.
constexpr std::size_t kPartBytes = std::size_t{1} << 19;

//! Appends to `out`, in order, the text of batches that the calling thread fills one after
//! another and up to `threads` threads format at once, each batch on a thread of its own: the
//! same bytes as formatting every batch into `out` in turn, with a few batches in memory at a
//! time. Fill batch(), then send() it; finish() appends what is left. For text whose parts
//! come from a walk (the OBJ writer's), or ranges of items (write_in_order). Batch needs
//! clear(); format(Text&, const Batch&) must not change what it reads elsewhere.
template <class Batch, class Format>
class OrderedBatches {
 public:
  OrderedBatches(OutputFile& out, int threads, Format format)
      : out_(out), format_(std::move(format)), slots_(static_cast<std::size_t>(std::max(threads, 1)) + 1) {
    // The slots' buffers are reserved here and reused: fresh ones would cost a page fault
    // every 4 kB.
    for (Slot& slot : slots_) {
      slot.text.reserve(kPartBytes);
      free_.push_back(&slot);
    }
    take();
  }
  OrderedBatches(const OrderedBatches&) = delete;
  OrderedBatches& operator=(const OrderedBatches&) = delete;

  Batch& batch() { return filling_->batch; }

  //! Formats the batch filled so far on a thread of its own; batch() is then an empty one.
  void send() {
    Slot* const slot = filling_;
    pending_.emplace_back(std::async(std::launch::async, [this, slot] {
      slot->text.clear();
      format_(slot->text, slot->batch);
    }), slot);
    take();
  }

  //! Appends the text of every batch sent to `out`; batch() is not sent. Rethrows the first
  //! failure of a format, once the batches under way have finished.
  void finish() {
    std::exception_ptr first;
    while (!pending_.empty()) {
      try {
        append_first();
      } catch (...) {
        if (!first) first = std::current_exception();
      }
    }
    if (first) std::rethrow_exception(first);
  }

 private:
  struct Slot {
    Batch batch;
    Text text;
  };

  //! The next batch to fill: a free slot, or the oldest one sent, once its text is appended.
  void take() {
    if (free_.empty()) append_first();
    filling_ = free_.back();
    free_.pop_back();
    filling_->batch.clear();
  }
  void append_first() {
    auto [formatted, slot] = std::move(pending_.front());
    pending_.pop_front();
    free_.push_back(slot);
    formatted.get();
    out_.append(slot->text);
  }

  OutputFile& out_;
  Format format_;
  // Declared before the tasks: a std::async future waits for its task when destroyed, so on an
  // exception the tasks end before the slots and the format they use.
  std::vector<Slot> slots_;
  std::vector<Slot*> free_;
  Slot* filling_ = nullptr;
  std::deque<std::pair<std::future<void>, Slot*>> pending_;
};

//! Calls format(Text&, begin, end) for the items [0, count) in ranges of `chunk`, up to
//! `threads` ranges at once, each on a thread of its own, and appends their text to `out` in
//! order: the same bytes as format(out, 0, count), with a few ranges' text in memory at a time.
//! An exception from format is rethrown here, once the ranges under way have finished.
template <class Format>
void write_in_order(OutputFile& out, std::size_t count, std::size_t chunk, int threads, Format&& format) {
  struct Range {
    std::size_t begin = 0, end = 0;
    void clear() { begin = end = 0; }
  };
  const auto format_range = [&format](Text& text, const Range& range) { format(text, range.begin, range.end); };
  OrderedBatches<Range, decltype(format_range)> ranges(out, threads, format_range);
  for (std::size_t begin = 0; begin < count; begin += chunk) {
    ranges.batch() = {begin, std::min(count, begin + chunk)};
    ranges.send();
  }
  ranges.finish();
}

}  // namespace dla::detail
