#pragma once
//! \file errors.h
//! The exceptions dla throws. Every message is one line that names what is wrong, so a
//! command-line front end can print `what()` as it is.

#include <stdexcept>
#include <string>

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

}  // namespace dla
