#pragma once
// The grown 3D DLA tree the look and solid benchmarks measure: grown once a size, on two
// threads (the same tree as on one), not timed.

#include "dla/models/dla.h"

#include <cstddef>
#include <map>

inline const dla::Cluster& dla_tree(std::size_t n) {
  static std::map<std::size_t, dla::Cluster> trees;
  dla::Cluster& tree = trees[n];
  if (tree.particles.empty()) {
    dla::DlaOptions o;
    o.particles = n;
    o.threads = 2;
    tree = dla::grow(o);
  }
  return tree;
}
