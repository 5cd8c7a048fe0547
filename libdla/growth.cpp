// The non-template entry point: validates the options and runs the engine with the chosen
// index, so programs that call grow() compile the engine once, here.

#include "dla/growth.h"

#include "dla/grid_index.h"
#include "dla/kdtree_index.h"
#include "dla/spatial_index.h"

namespace dla {

Cluster grow(const GrowthOptions& options, const ProgressFn& progress) {
  validate(options);
  switch (options.index) {
    case IndexKind::grid: return grow_with<GridIndex>(options, progress);
    case IndexKind::kdtree: return grow_with<KdTreeIndex>(options, progress);
    case IndexKind::brute: return grow_with<BruteForceIndex>(options, progress);
  }
  throw InvalidInput("unknown index");
}

}  // namespace dla
