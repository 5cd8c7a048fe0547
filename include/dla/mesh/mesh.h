#pragma once
//! \file mesh.h
//! Triangle meshes as plain data, and their files: STL (binary and ASCII), OFF, OBJ and PLY in,
//! with the vertex colours the last three can carry, binary STL out. See docs/formats.md.

#include "dla/core/options.h"

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dla {

//! A triangle soup with shared vertices. Triangles list vertex indices; their order (counter-
//! clockwise seen from outside) gives the outward side once the mesh is repaired.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  //! One per vertex, red, green and blue in [0, 1], as painted in Blender or MeshLab; empty
  //! when the file has none.
  std::vector<Vec3> colors;
};

//! Reads a mesh, choosing the format by the file's extension (.stl, .off, .obj, .ply, any
//! case). Polygons are split into triangle fans; STL normals are ignored. Vertex colours are
//! read from PLY (red, green, blue), COFF (r g b after each vertex) and OBJ (`v x y z r g b`):
//! integers count to 255, other numbers to 1. Throws IOError if the
//! file cannot be read and InvalidInput, naming the file, if it is not a well-formed mesh.
//! With `file_hash`, also gives the FNV-1a hash of the file's bytes (to tell if it changes).
TriangleMesh read_mesh(const std::string& path, std::uint64_t* file_hash = nullptr);

//! Reads a mesh from bytes, in the format named by `extension` ("stl", "off", "obj", "ply");
//! `name` prefixes the error messages. The readers behind read_mesh().
TriangleMesh parse_mesh(std::string_view bytes, std::string_view extension, const std::string& name);

//! Reads points (attractors): a PLY's vertices, ASCII or binary (faces, if any, are ignored), or
//! the rows of a text file (.csv, .txt, .xyz) of x, y and z separated by commas or spaces. A
//! first line that is not numbers is a header naming the columns, and its x, y and z columns
//! are read: dla3d's own CSV reads back. Lines starting with '#' are comments. Throws IOError
//! if the file cannot be read and InvalidInput, naming it, if it is malformed or holds no point.
std::vector<Vec3> read_points(const std::string& path);

//! The reader behind read_points(), from bytes, the format named by `extension`.
std::vector<Vec3> parse_points(std::string_view bytes, std::string_view extension, const std::string& name);


//! Adds `more`'s vertices and triangles to `mesh`, as separate parts of one mesh (colours: a
//! part without them is white).
void append(TriangleMesh& mesh, const TriangleMesh& more);

//! The smallest axis-aligned box around the vertices that triangles use.
Box bounding_box(const TriangleMesh& mesh);

}  // namespace dla
