#pragma once
//! \file html_writer.h
//! The web viewer: PREFIX.html, one self-contained page that opens in a browser with no server
//! and no network. It holds the structure as binary (base64) and three.js with dla3d's viewer
//! script, and shows the structure as lines or tubes coloured by an attribute, with orbit
//! controls, a growth slider and a play button that replay the attach order, and the
//! constraint mesh as a translucent surface. See docs/animation.md.

#include "dla/look/look.h"
#include "dla/mesh/mesh.h"

#include <string>

namespace dla {

struct HtmlOptions {
  Axis up = Axis::y;     //!< the axis that is up on screen
  std::string title;     //!< the page's title; default: "dla3d"
  //! Up to this many particles the page can show tubes; up to `tube_default_limit` it opens
  //! with them. Beyond, lines only: a cylinder and a sphere a particle slow a browser down.
  std::size_t tube_limit = 200'000;
  std::size_t tube_default_limit = 20'000;
};

//! Whether this build has the viewer's script (three.js is fetched by npm at build time; a
//! build without npm has none, and write_html throws).
bool has_web_viewer();

//! Writes PATH, the page: the particles (positions relative to their box's centre, in
//! spacings, as float32), their parents, branch radii (from the look), a byte a particle for
//! each colour attribute, and with a `mesh` its vertices and triangles. Throws InvalidInput
//! without the viewer's script, IOError if the file cannot be written.
void write_html(const Cluster& cluster, const Look& look, const std::string& path, const HtmlOptions& options = {},
                const TriangleMesh* mesh = nullptr);

}  // namespace dla
