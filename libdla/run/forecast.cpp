// What a run's long stages after growth will take, known before growth from its options:
// refused where it cannot fit, foretold where it will take long.

#include "model_runs.h"

#include "dla/core/memory.h"
#include "dla/io/scattering_writers.h"
#include "dla/look/tubes.h"

#include <cmath>
#include <limits>

namespace dla::detail {

namespace {

std::string gigabytes(double bytes) { return format_number(std::ceil(bytes / 1e8) / 10.0) + " GB"; }

//! A link made takes 8 bytes on the thread that made it, then 8 in the structure's list.
constexpr double kBytesPerLink = 16.0;

//! The most particles within `distance` spacings of one in 3D: balls a spacing across, packed
//! as closely as balls go (74%), in a ball of that radius.
double most_neighbours(double distance) { return 0.74 * 8.0 * distance * distance * distance; }

//! Refuses links that could take more memory than this machine has free: up to `most` a
//! particle, for every particle the run may grow.
void refuse_links(const Run& run) {
  const LinkOptions& links = run.links;
  if (!links.any() || links.lattice) return;
  const double particles = static_cast<double>(run.total);
  const double needed = kBytesPerLink * particles * static_cast<double>(links.most), memory = available_memory();
  if (memory <= 0.0 || needed <= memory) return;
  const auto fit = static_cast<std::size_t>(memory / (kBytesPerLink * particles));
  throw InvalidInput("`links` " + to_string(links) + " may make " + format_count(links.most) + " links for each of " +
                     format_count(run.total) + " particles, " + gigabytes(needed) + ", past the " + gigabytes(memory) +
                     " of memory free: " +
                     (fit > 1 ? "at most " + format_count(fit) + " links a particle fit"
                                : fit == 1 ? "at most 1 link a particle fits" : "grow fewer particles"));
}

//! Refuses tubes (glb, OBJ) larger than a glb may be or than the output's disk holds, from what
//! they take at the least: with every point kept (no `tube_tolerance`, no `tube_min_branch`),
//! each particle grown is a ring of its strand's tube, `tube_sides` + 1 vertices and 2
//! `tube_sides` triangles. Only for a run that promises its count (Run::solid_forecast).
void refuse_tubes(const Run& run) {
  const OutputOptions& f = run.files;
  const TubeOptions& tubes = f.look.tubes;
  const auto particles = static_cast<double>(run.solid_forecast.particles);
  if (particles == 0.0 || tubes.tolerance > 0.0 || tubes.min_branch > 1 || !(f.formats.glb || f.formats.obj)) return;
  const double sides = tubes.sides, vertices = (sides + 1.0) * particles, triangles = 2.0 * sides * particles;
  // A glb vertex: position, normal, tangent and texture coordinate; a triangle, three indices.
  const double glb = vertices * 48.0 + triangles * 12.0;
  constexpr double kGlbBytes = std::numeric_limits<std::uint32_t>::max();
  if (f.formats.glb && glb > kGlbBytes)
    throw InvalidInput("`formats` glb: the tubes of " + format_count(run.solid_forecast.particles) +
                       " particles take at least " + gigabytes(glb) + ", past a glb's 4.29 GB: " +
                       format_count(static_cast<std::size_t>(particles * kGlbBytes / glb)) +
                       " particles fit with these `tube_sides`, or a `tube_tolerance` or `tube_min_branch` makes them smaller");
  // An OBJ line: "v x y z" or "f a b c", 8 bytes at the least.
  const double bytes = (f.formats.glb ? glb : 0.0) + (f.formats.obj ? 8.0 * (vertices + triangles) : 0.0);
  const double disk = free_disk_bytes(f.output);
  if (bytes > disk)
    throw InvalidInput("`formats` " + std::string(f.formats.glb ? "glb" : "obj") + ": the tubes of " +
                       format_count(run.solid_forecast.particles) + " particles take at least " + gigabytes(bytes) +
                       ", past the " + gigabytes(disk) + " free on the disk of `output` " + f.output + ": " +
                       format_count(static_cast<std::size_t>(particles * disk / bytes)) + " particles fit");
}

//! Refuses a DDSCAT shape file past kMaxDipoles before growth, from the least it holds: each
//! sphere at least the least radius over the most of the mean radius, at `ddscat_resolution`
//! dipoles a mean radius. Only for a run that promises its count and its radii.
void refuse_dipoles_before_growth(const Run& run) {
  const SolidForecast& forecast = run.solid_forecast;
  if (!run.files.formats.ddscat || forecast.particles == 0 || !(forecast.least_radius > 0.0)) return;
  const double r = run.files.ddscat_resolution * forecast.least_radius / forecast.most_radius;
  refuse_dipoles({0.0, static_cast<double>(forecast.particles) * 4.0 / 3.0 * M_PI * r * r * r},
                 run.files.ddscat_resolution, run.files.output + "_ddscat.dat");
}

}  // namespace

std::string time_for_pairs(double pairs) {
  const double minutes = pairs / kPairsPerSecond / 60.0;
  if (minutes < 2.0) return "a minute or two";
  if (minutes < 120.0) return "up to " + format_count(static_cast<std::size_t>(minutes)) + " minutes";
  return "up to " + format_count(static_cast<std::size_t>(minutes / 60.0)) + " hours";
}

void refuse_or_foretell(Run& run) {
  refuse_links(run);
  refuse_tubes(run);
  refuse_dipoles_before_growth(run);
  // The links look at each particle's neighbours within their distance.
  const LinkOptions& links = run.links;
  if (links.any() && !links.lattice) {
    const double particles = static_cast<double>(run.total);
    const double pairs = particles * std::min(particles, most_neighbours(links.distance));
    if (pairs > 3e9)
      run.forecast_line = "the links may look at up to " + format_number(std::round(pairs / 1e8) / 10.0) +
                          " billion neighbour pairs within " + format_number(links.distance) + " spacings, " +
                          time_for_pairs(pairs) + "; a smaller `links` distance looks at fewer";
  }
}

}  // namespace dla::detail
