#pragma once
//! \file svg_writer.h
//! 2D growth as an SVG drawing for plotters, laser cutters and print: each branch a line from
//! parent to particle, as wide as the radius model says, round-capped so branches join.
//! See docs/look.md.

#include "dla/look/look.h"

#include <string>

namespace dla {

//! Writes PATH. Black on white, or coloured by the look's colour attribute; y points up as in
//! the structure. Throws InvalidInput for a 3D structure and IOError if the file cannot be
//! written.
void write_svg(const Cluster& cluster, const Look& look, const std::string& path);

}  // namespace dla
