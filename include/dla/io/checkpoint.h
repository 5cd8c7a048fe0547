#pragma once
//! \file checkpoint.h
//! A growth run saved part way, to be grown on later with resume() (dla.h): the structure
//! so far, its walk statistics, and what made it. See docs/formats.md.

#include "dla/core/cluster.h"
#include "dla/core/hash.h"
#include "dla/models/walk.h"

#include <cstdint>
#include <string>
#include <vector>

namespace dla {

struct Checkpoint {
  std::vector<std::string> command;  //!< what made the run (dla3d's arguments), to run it again
  std::uint64_t input_hash = 0;      //!< of the run's input files (the mesh), 0 if none
  Cluster cluster;                   //!< the structure so far
  WalkStats walk;                    //!< the walks that grew it
};

//! Writes `checkpoint` under a temporary name and renames it into place, so an interrupted
//! write leaves the previous checkpoint whole. Throws IOError.
void write_checkpoint(const Checkpoint& checkpoint, const std::string& path);

//! Reads a checkpoint; throws IOError if it cannot be read and InvalidInput, naming the file,
//! if it is not a whole checkpoint (a checksum covers every byte).
Checkpoint read_checkpoint(const std::string& path);

}  // namespace dla
