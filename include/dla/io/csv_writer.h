#pragma once
//! \file csv_writer.h
//! Particles as CSV, one row per particle in attach order, coordinates in the shortest form
//! that reads back to the same double: `id,x,y,z,parent,seed`, and with a look also
//! `radius,age,depth,descendants,order,tip` (as in the PLY), and for a discharge that struck
//! `current,channel,light` (attributes.h). A structure with links also gets
//! PREFIX_links.csv beside PREFIX.csv: `a,b`, a row a link, `b` the later particle.

#include "dla/look/look.h"

#include <string>

namespace dla {

//! The path of the links' file beside a CSV: PREFIX_links.csv for PREFIX.csv.
inline std::string links_csv_path(const std::string& csv_path) {
  const bool csv = csv_path.size() >= 4 && csv_path.compare(csv_path.size() - 4, 4, ".csv") == 0;
  return (csv ? csv_path.substr(0, csv_path.size() - 4) : csv_path) + "_links.csv";
}
//! The tree alone: `id,x,y,z,parent,seed`, and the links. Throws IOError if a file cannot be
//! written. Without links, an old PREFIX_links.csv is removed: it would be read back with it.
void write_csv(const Cluster& cluster, const std::string& path);

//! The tree and the look's radius and attributes. Throws IOError.
void write_csv(const Cluster& cluster, const Look& look, const std::string& path);

//! The sphere list that light-scattering codes read (MSTM, DDSCAT's tools, T-matrix codes):
//! `x,y,z,r`, a row a particle, in scene units; r is the particle's own radius where the model
//! sized it (Cluster::radii, exactly), else the look's. Throws IOError.
void write_spheres_csv(const Cluster& cluster, const Look& look, const std::string& path);

}  // namespace dla
