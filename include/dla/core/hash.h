#pragma once
//! \file hash.h
//! FNV-1a, 64 bits: the checksum of checkpoints and the fingerprint of input files. Not for
//! security: it tells a changed or damaged file, not a forged one.

#include <cstdint>
#include <string_view>

namespace dla {

inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = 0xcbf29ce484222325ULL) {
  for (const char c : bytes) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return hash;
}

}  // namespace dla
