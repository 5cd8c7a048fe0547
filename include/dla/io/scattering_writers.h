#pragma once
//! \file scattering_writers.h
//! The files light-scattering codes read a structure's spheres from: MSTM's sphere-position
//! file and DDSCAT's shape file. The spheres are the particles, each of its own radius where
//! the model sized it (Cluster::radii), else of the look's; the sphere list (csv_writer.h)
//! holds the same spheres. See docs/formats.md.

#include "dla/look/look.h"

#include <cstddef>
#include <string>

namespace dla {

//! Particle i's sphere radius in scene units: its own (Cluster::radii), else the look's.
inline double sphere_radius(const Cluster& cluster, const Look& look, std::size_t i) {
  return cluster.radii.size() == cluster.particles.size() ? cluster.radii[i] : look.radius(cluster, i);
}

//! MSTM's sphere-position file (`sphere_position_file` of MSTM 3): a line a sphere,
//! `radius x y z` in scene units. MSTM scales them by its `length_scale_factor` and gives every
//! sphere the refractive index of its `real_ref_index_scale_factor` and
//! `imag_ref_index_scale_factor`. Throws IOError.
void write_mstm_positions(const Cluster& cluster, const Look& look, const std::string& path);

//! The most dipoles a DDSCAT shape file is written with.
inline constexpr double kMaxDipoles = 1e8;

//! The dipole spacing of DDSCAT's lattice at `resolution` dipoles a mean sphere radius, in scene
//! units, and the dipoles the spheres' volume holds at that spacing: what the shape file is
//! estimated to hold before it is made.
struct DipoleLattice {
  double spacing = 0.0;
  double estimated_dipoles = 0.0;
};
DipoleLattice dipole_lattice(const Cluster& cluster, const Look& look, int resolution);

//! Throws InvalidInput, naming `ddscat_resolution` and the resolution that fits, when the shape
//! file at `resolution`, written at `path`, would hold more than kMaxDipoles dipoles, or more
//! than the free memory or the disk of `path` hold.
void refuse_dipoles(const DipoleLattice& lattice, int resolution, const std::string& path);

//! DDSCAT's shape file (TARGET = FROM_FILE, DDSCAT 7.3's layout): the points of a cubic lattice
//! of dipole_lattice()'s spacing inside any sphere, each listed once as `JA IX IY IZ 1 1 1`, in
//! order of IZ, then IY, then IX. IX d is the point's x in scene units (the lattice offset is
//! 0); the first line gives d. Throws InvalidInput as refuse_dipoles does, IOError.
void write_ddscat_shape(const Cluster& cluster, const Look& look, int resolution, const std::string& path);

}  // namespace dla
