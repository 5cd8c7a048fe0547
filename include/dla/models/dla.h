#pragma once
//! \file dla.h
//! Off-lattice diffusion-limited aggregation: walkers launched one after another walk in
//! continuous space until they touch the structure and stick. See docs/dla.md.

#include "dla/core/cluster.h"
#include "dla/core/options.h"
#include "dla/mesh/constraint.h"
#include "dla/models/walk.h"

namespace dla {

// DLA calls its ProgressFn (cluster.h) as model_shell.h says; an incomplete cluster can be
// saved and grown on with resume(). Walkers look at the StopFlag every few
// thousand steps, so growth stops within milliseconds, even in a walk that would never end.

//! Grows a structure with the index chosen in options.index. Validates the options first.
//! Defined in libdla (it instantiates grow_with for every index). Throws PartialGrowth if
//! growth fails part way. With `stats`, counts there what the walks did, as they go: a
//! progress callback reads how full a mesh is there.
Cluster grow(const DlaOptions& options, const ProgressFn& progress = {}, const StopFlag* stop = nullptr,
             DlaStats* stats = nullptr);

//! Grows a structure constrained by a mesh (see constraint.h). Validates the options and
//! checks them against the constraint: the same spacing, 3 dimensions, seeds on the growing
//! side, a spawn mode that can start walkers there.
Cluster grow(const DlaOptions& options, const MeshConstraint& constraint, const ProgressFn& progress = {},
             const StopFlag* stop = nullptr, DlaStats* stats = nullptr);

//! Grows on a structure that growth with the same options (and constraint) stopped early, up
//! to options.particles. The result is the one growth without the stop gives, byte for byte:
//! walker k draws from its own random stream, whenever it runs. Throws InvalidInput if
//! `partial` cannot have come from these options. `stats`, if given, holds the walks that grew
//! `partial` (a checkpoint keeps them): the walks' count goes on from them.
Cluster resume(const DlaOptions& options, const Cluster& partial, const ProgressFn& progress = {},
               const StopFlag* stop = nullptr, DlaStats* stats = nullptr);
Cluster resume(const DlaOptions& options, const MeshConstraint& constraint, const Cluster& partial,
               const ProgressFn& progress = {}, const StopFlag* stop = nullptr, DlaStats* stats = nullptr);

//! Throws InvalidInput where the options and the constraint cannot work together.
void validate(const DlaOptions& options, const MeshConstraint& constraint);

//! Grows a structure with a given index type (see spatial_index.h), constrained by a mesh if
//! `constraint` is set, going on from `partial` if it is set. Does not validate. Compiled in
//! libdla for GridIndex, KdTreeIndex and BruteForceIndex (libdla/models/aggregation.h holds the
//! engine).
template <class Index>
Cluster grow_with(const DlaOptions& options, const ProgressFn& progress = {},
                  const MeshConstraint* constraint = nullptr, const Cluster* partial = nullptr,
                  const StopFlag* stop = nullptr, DlaStats* stats = nullptr);

}  // namespace dla
