#pragma once
//! \file csv_writer.h
//! Particles as CSV: `id,x,y,z,parent,seed`, one row per particle in attach order, coordinates
//! in the shortest form that reads back to the same double.

#include "dla/cluster.h"

#include <string>

namespace dla {

//! Throws IOError if the file cannot be written.
void write_csv(const Cluster& cluster, const std::string& path);

}  // namespace dla
