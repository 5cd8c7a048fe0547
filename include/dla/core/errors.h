#pragma once
//! \file errors.h
//! The exceptions dla throws. Every message is one line that names what is wrong. An option
//! is named as C++ and Python spell it, between backticks (`seed_paint`); spell_options()
//! writes those names as a front end's user typed them: dla3d's --seed-paint, Python's
//! seed_paint=.

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dla {

//! A value or combination of options that cannot work (a stickiness of 1.7, two seeds closer
//! than the spacing, ...).
class InvalidInput : public std::invalid_argument {
 public:
  explicit InvalidInput(const std::string& what) : std::invalid_argument(what) {}
};

//! A file that cannot be read or written.
class IOError : public std::runtime_error {
 public:
  explicit IOError(const std::string& what) : std::runtime_error(what) {}
};

//! Growth that cannot go on with the given setup (a spawn region filled by the structure,
//! a structure larger than the spatial index can hold).
class GrowthError : public std::runtime_error {
 public:
  explicit GrowthError(const std::string& what) : std::runtime_error(what) {}
};

//! Work stopped on request (Ctrl-C, a StopFlag) before it was done: nothing of it was kept.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(const std::string& what) : std::runtime_error(what) {}
};

struct Cluster;

//! Growth that failed part way, in any model (a walker that cannot stick, a structure beyond
//! the index's reach, memory run out), with what had grown before the failure, marked
//! incomplete: it can still be written out.
class PartialGrowth : public GrowthError {
 public:
  //! `partial` is the Cluster grown so far (cluster.h).
  template <class Grown>
  PartialGrowth(const std::string& what, Grown partial)
      : GrowthError(what), partial_(std::make_shared<const Grown>(std::move(partial))) {}
  const Cluster& partial() const { return *partial_; }

 private:
  std::shared_ptr<const Cluster> partial_;  // shared: exceptions are copied
};

//! How a front end spells an option.
enum class OptionSpelling {
  cli,     //!< --seed-paint
  python,  //!< seed_paint= before its value, else seed_paint
};

//! `message` with each option named between backticks spelled as `spelling` says.
inline std::string spell_options(std::string_view message, OptionSpelling spelling) {
  std::string out;
  std::size_t at = 0;
  while (at < message.size()) {
    const std::size_t open = message.find('`', at);
    const std::size_t close = open == std::string_view::npos ? open : message.find('`', open + 1);
    if (close == std::string_view::npos) break;
    const std::string_view name = message.substr(open + 1, close - open - 1);
    const bool option = !name.empty() && name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == name.npos;
    out.append(message.substr(at, open - at));
    at = close + 1;
    if (!option) {
      out.append(message.substr(open, at - open));
      continue;
    }
    if (spelling == OptionSpelling::cli) {
      out += "--";
      for (const char c : name) out += c == '_' ? '-' : c;
      continue;
    }
    out.append(name);
    // A value after the name reads as the keyword argument it was: seed_paint='zz'.
    const bool valued = at + 1 < message.size() && message[at] == ' ' &&
                        std::string_view("0123456789'\"-+.[(").find(message[at + 1]) != std::string_view::npos;
    if (valued) out += '=', ++at;
  }
  out.append(message.substr(at));
  return out;
}

}  // namespace dla
