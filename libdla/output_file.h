#pragma once
// A text file written under a temporary name and renamed into place on commit(), so a failed
// or interrupted write never leaves a half-written file under the final name. Buffered, with
// locale-free number formatting so the same data gives the same bytes everywhere.

#include "dla/errors.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

namespace dla::detail {

class OutputFile {
 public:
  explicit OutputFile(std::string path) : path_(std::move(path)), temp_(path_ + ".tmp") {
    file_ = std::fopen(temp_.c_str(), "w+b");  // read back when appended to another
    if (!file_) fail();
    buffer_.reserve(kFlushAt + 256);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() {
    if (file_) {
      std::fclose(file_);
      std::remove(temp_.c_str());
    }
  }

  OutputFile& operator<<(std::string_view text) {
    buffer_ += text;
    if (buffer_.size() >= kFlushAt) flush();
    return *this;
  }
  OutputFile& operator<<(char c) {
    buffer_ += c;
    return *this;
  }
  //! A double in the shortest form that reads back exactly, or with `digits` significant digits.
  OutputFile& number(double value, int digits = 0) {
    char text[40];
    const auto end = digits > 0 ? std::to_chars(text, text + sizeof text, value,
                                                std::chars_format::general, digits)
                                : std::to_chars(text, text + sizeof text, value);
    return *this << std::string_view(text, static_cast<std::size_t>(end.ptr - text));
  }
  //! `value` rounded to `decimals` (0-9) places, trailing zeros dropped: "-12.5", "3"; for
  //! |value| below 9e18 / 10^decimals. Integer arithmetic only: much cheaper than number().
  OutputFile& fixed(double value, int decimals) {
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
  OutputFile& raw(T value) {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary files are written little-endian");
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    return *this << std::string_view(bytes, sizeof value);
  }
  OutputFile& integer(long long value) {
    char text[24];
    const auto end = std::to_chars(text, text + sizeof text, value);
    return *this << std::string_view(text, static_cast<std::size_t>(end.ptr - text));
  }

  //! Appends what `part` holds: a file written beside this one (on another thread) and never
  //! committed, which its destructor removes.
  void append(OutputFile& part) {
    part.flush();
    if (std::fflush(part.file_) != 0 || std::fseek(part.file_, 0, SEEK_SET) != 0) part.fail();
    flush();
    std::string chunk(std::size_t{1} << 20, '\0');
    for (;;) {
      const std::size_t got = std::fread(chunk.data(), 1, chunk.size(), part.file_);
      if (got > 0 && std::fwrite(chunk.data(), 1, got, file_) != got) fail();
      if (got < chunk.size()) break;
    }
    if (std::ferror(part.file_)) part.fail();
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
  std::string buffer_;
};

}  // namespace dla::detail
