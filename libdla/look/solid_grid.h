#pragma once
// The solid's level set (solid.h), for the files that carry it (PREFIX.vdb). OpenVDB stays in
// libdla: this header is not installed.

#include "dla/look/solid.h"

#include <openvdb/openvdb.h>

namespace dla::detail {

struct SolidGrid {
  openvdb::FloatGrid::Ptr surface;  //!< narrow-band signed distance, in the mesh's units
};

//! OpenVDB's registries, once per process.
void initialize_openvdb();

}  // namespace dla::detail
