#pragma once
//! \file growth.h
//! Deprecated: DLA is a model named like the others, `dla/models/dla.h`, and its options are
//! DlaOptions. This header and the name GrowthOptions keep old code compiling for one release
//! (0.2); include dla.h and say DlaOptions instead.

#include "dla/models/dla.h"

namespace dla {

using GrowthOptions [[deprecated("DLA's options are DlaOptions, in dla/models/dla.h")]] = DlaOptions;

}  // namespace dla
