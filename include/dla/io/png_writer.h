#pragma once
//! \file png_writer.h
//! 2D growth as a PNG picture, each particle a dot coloured in bands by attach order: white,
//! grey and black in turn, as the colour map of "Sticky Pixels"' figure 1. Written with libpng
//! (docs/formats.md says why). See docs/formats.md.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/option_description.h"
#include "dla/core/options.h"

#include <string>
#include <utility>

namespace dla {

//! How the picture is drawn.
struct PngOptions {
  double pixels_per_spacing = 2.0;  //!< the scale: a particle is a dot this wide, (0, 64]
  int bands = 8;                    //!< times the white, grey, black cycle runs over the
                                    //!< attach order, 1 to 10^6
  int margin = 8;                   //!< pixels around the structure, 0 to 1000
};

//! The picture's options, described once (option_description.h); the margin is the library's.
inline const OptionTable<PngOptions>& png_option_table() {
  using O = PngOptions;
  static const OptionTable<O> table{
      real("png_scale", &O::pixels_per_spacing, closed(1e-6, 64), "pixels a spacing", "Output", "png: the scale"),
      integer("png_bands", &O::bands, closed(1, 1e6), "", "Output",
              "png: times the white, grey, black bands cycle over the attach order"),
  };
  return table;
}

inline void validate(const PngOptions& o) {
  require_in_ranges(png_option_table(), o);
  if (o.margin < 0 || o.margin > 1000) throw InvalidInput("png margin " + std::to_string(o.margin) + " is not in [0, 1000]");
}

//! The picture's width and height in pixels for `cluster`, as write_png() draws it.
std::pair<long long, long long> png_size(const Cluster& cluster, const PngOptions& options = {});

//! Writes PATH: an 8-bit RGB PNG, y up as in the structure, on a dark background. A structure
//! wider than 8,192 pixels at the scale is drawn smaller to fit. Throws InvalidInput for a 3D
//! structure and IOError if the file cannot be written.
void write_png(const Cluster& cluster, const std::string& path, const PngOptions& options = {});

}  // namespace dla
