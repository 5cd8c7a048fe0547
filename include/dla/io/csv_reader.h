#pragma once
//! \file csv_reader.h
//! A structure read back from the CSV that write_csv() makes (`id,x,y,z,parent,seed`), for
//! `dla3d analyze` and for tools that measure what was grown.

#include "dla/core/cluster.h"

#include <string>
#include <string_view>
#include <vector>

namespace dla {

//! Parses a dla3d CSV held in `text`; `name` names it in errors. The spacing is the median
//! branch length; the structure is planar if every z is 0. Throws InvalidInput, one line naming
//! `name` and the row, for anything else: rows out of order, a parent that is not an earlier
//! particle, a number that is not finite, no branch to measure.
Cluster parse_csv(std::string_view text, const std::string& name);

//! Parses the rows `a,b` of a PREFIX_links.csv into `cluster`'s links; throws InvalidInput for a
//! row that is not two particles of it, earlier first.
void parse_links_csv(std::string_view text, const std::string& name, Cluster& cluster);
//! Reads and parses the CSV at `path`, with the links of PREFIX_links.csv beside it if there is
//! one; throws IOError if one cannot be read.
Cluster read_csv(const std::string& path);

//! Spheres read back from a sphere list (PREFIX_spheres.csv, csv_writer.h), in its order.
struct SphereList {
  std::vector<Vec3> centres;
  std::vector<double> radii;
};
//! Whether `text` begins with a sphere list's header, `x,y,z,r`.
bool is_sphere_list(std::string_view text);
//! Parses a sphere list held in `text`; `name` names it in errors. Throws InvalidInput, one
//! line naming `name` and the row, for a row that is not four finite numbers with a positive
//! radius, or for no sphere.
SphereList parse_sphere_list(std::string_view text, const std::string& name);

}  // namespace dla
