// libFuzzer target for the leaf reader (`--leaf FILE.glb`, leaf.h): any bytes must either be
// refused with InvalidInput or give a leaf whose objects renumber, for a glb with objects of
// its own before them, without a fault. Build with -DDLA_FUZZ=ON (clang); see docs/testing.md.

#include "io/leaf_parts.h"
#include "special_files.h"

#include "dla/io/leaf.h"

#include "dla/core/errors.h"

#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dla::fuzz::read_special_files(".glb", [](const std::string& path) { dla::read_leaf(path); });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const dla::Leaf leaf = dla::detail::parse_leaf(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
    if (leaf.binary.size() % 4 != 0) std::abort();
    const dla::detail::LeafParts parts = dla::detail::leaf_parts(leaf, {7, 2, 1, 1, 1024});
    if (parts.mesh < 1 || parts.meshes.empty() || !parts.transform.matrix().allFinite()) std::abort();
  } catch (const dla::InvalidInput&) {
  }
  return 0;
}
