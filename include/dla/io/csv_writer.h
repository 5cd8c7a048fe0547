#pragma once
//! \file csv_writer.h
//! Particles as CSV, one row per particle in attach order, coordinates in the shortest form
//! that reads back to the same double: `id,x,y,z,parent,seed`, and with a look also
//! `radius,age,depth,descendants,order,tip` (as in the PLY).

#include "dla/look/look.h"

#include <string>

namespace dla {

//! The tree alone: `id,x,y,z,parent,seed`. Throws IOError if the file cannot be written.
void write_csv(const Cluster& cluster, const std::string& path);

//! The tree and the look's radius and attributes. Throws IOError.
void write_csv(const Cluster& cluster, const Look& look, const std::string& path);

}  // namespace dla
