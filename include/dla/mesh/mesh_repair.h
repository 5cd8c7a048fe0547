#pragma once
//! \file mesh_repair.h
//! Makes a user's mesh usable as a constraint: merges duplicate vertices, drops degenerate
//! triangles, orients the triangles consistently and, for a solid, closes holes and turns the
//! triangles to face out. CGAL does the work behind this interface (libdla/mesh/mesh_repair.cpp).

#include "dla/mesh/mesh.h"

#include <string>

namespace dla {

struct RepairOptions {
  bool close_holes = true;  //!< fill holes and orient outward so the mesh bounds a volume
};

//! What repair_mesh() changed, for a one-line report.
struct RepairReport {
  std::size_t input_triangles = 0;
  std::size_t merged_vertices = 0;       //!< vertices at the same place as an earlier one
  std::size_t dropped_triangles = 0;     //!< degenerate (zero-area) or repeated triangles
  std::size_t reoriented_triangles = 0;  //!< turned to agree with their neighbours or face out
  std::size_t holes_closed = 0;
  std::size_t hole_triangles = 0;        //!< triangles added to close them
  std::size_t holes_left = 0;            //!< holes that could not be closed
  bool closed = false;                   //!< every edge has two triangles: the mesh bounds a volume

  //! "merged 3 duplicate vertices, dropped 1 degenerate triangle, closed 1 hole with 62
  //! triangles", or "nothing to repair".
  std::string summary() const;
};

//! The repaired mesh. Throws InvalidInput if nothing usable is left.
TriangleMesh repair_mesh(const TriangleMesh& mesh, const RepairOptions& options = {},
                         RepairReport* report = nullptr);

}  // namespace dla
