#pragma once
// nanoflann, included once for the k-d tree index and the nearest-point look-ups: nanoflann
// 1.4 leaves a bounding box uninitialised on a path it never takes, and GCC warns.

#pragma GCC diagnostic push
#if defined(__GNUC__) && !defined(__clang__)  // a GCC-only warning
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nanoflann.hpp>
#pragma GCC diagnostic pop
