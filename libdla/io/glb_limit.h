#pragma once
// A glb's lengths are 32-bit: the one check every glb writer makes before it opens its file.

#include <cstdint>

namespace dla::detail {

//! What a glb holds, for the message that refuses it.
enum class GlbContent { tubes, solid };

//! Throws InvalidInput if a glb of `bytes` would pass 4.29 GB, where its 32-bit lengths would
//! wrap: one line naming the format and the options that make it smaller.
void require_glb_fits(std::uint64_t bytes, GlbContent content);

}  // namespace dla::detail
