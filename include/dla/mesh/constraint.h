#pragma once
//! \file constraint.h
//! A triangle mesh that constrains growth (Bourke's constrained DLA): walkers move freely, and
//! when one is about to stick its new branch is tested against the surface. A branch that
//! crosses is refused (the walker walks on) or clipped to end just short of the surface.
//! Walkers on the wrong side of a closed surface, farther than the attach distance, can never
//! stick and are launched again. See docs/constraints.md.

#include "dla/mesh/inside_test.h"
#include "dla/mesh/mesh.h"
#include "dla/mesh/mesh_repair.h"
#include "dla/mesh/paint.h"
#include "dla/mesh/shell.h"
#include "dla/mesh/surface_distance.h"
#include "dla/core/random.h"
#include "dla/mesh/surface_intersector.h"
#include "dla/core/words.h"

#include <atomic>
#include <memory>
#include <string_view>
#include <vector>

namespace dla {

//! Which side of the surface the structure grows on (`--side inside|outside|both|surface`).
enum class Side {
  inside,   //!< within a closed surface (a vessel, a bust); holes are closed first
  outside,  //!< around a closed object; holes are closed first
  both,     //!< the surface is only a wall, open or closed, and is used as it is (an open can)
  surface,  //!< over the surface, on both sides, in a layer `shell` thick (frost on a leaf)
};
inline constexpr WordTable<Side, 4> kSideWords{
    "side",
    {{{Side::inside, "inside"}, {Side::outside, "outside"}, {Side::both, "both"}, {Side::surface, "surface"}}}};
constexpr const auto& words_of(Side) { return kSideWords; }

//! What a branch that crosses the surface does (`--constraint reject|clip`).
enum class ConstraintMode {
  reject,  //!< the attachment is refused and the walker walks on
  clip,    //!< the branch ends just short of the surface: the new particle touches it
};
inline constexpr WordTable<ConstraintMode, 2> kConstraintModeWords{
    "constraint",
    {{{ConstraintMode::reject, "reject"}, {ConstraintMode::clip, "clip"}}}};
constexpr const auto& words_of(ConstraintMode) { return kConstraintModeWords; }

struct ConstraintOptions {
  Side side = Side::inside;                      //!< where the structure grows
  ConstraintMode mode = ConstraintMode::reject;  //!< what a crossing branch does
  //! Growth keeps within this many spacings of the surface, on its side (`--shell T`), in
  //! [1, 1000]; 0: anywhere on the side, but kShellSpacings for Side::surface.
  double shell = 0.0;
};

//! The constraint's options, described once (option_description.h).
inline const OptionTable<ConstraintOptions>& constraint_option_table() {
  using O = ConstraintOptions;
  static const OptionTable<O> table{
      word("side", &O::side, "Mesh constraint",
           "where growth goes: both: on either side, the mesh only a wall (need not be closed); surface: over it, on "
           "both sides, in a shell"),
      real("shell", &O::shell, closed(1.0, 1000.0), "spacings", "Mesh constraint",
           "keep growth within this distance of the surface, on its side: frost, lichen",
           SpecialValue{0.0, "anywhere on its side (--side surface: 3)"}),
      word("constraint", &O::mode, "Mesh constraint", "a branch crossing the mesh: reject (walk on) or clip (end at it)"),
  };
  return table;
}

//! The layer's thickness for Side::surface when none is given: room for branches to cross
//! one another, thin enough to read as a coat.
inline constexpr double kShellSpacings = 3.0;

//! The verdict on a new branch.
struct BranchCheck {
  bool accepted = true;  //!< false: the walker walks on
  bool clipped = false;  //!< the end was moved back to just short of the surface
  Vec3 end;              //!< where the new particle goes
};

class MeshConstraint {
 public:
  //! Repairs `mesh` (closing holes unless the side is `both`), then builds the inside grid and
  //! Embree's scene. `spacing` is the growth's spacing: it sets the grid's cell and the band
  //! of the surface within which walkers may still stick. Throws InvalidInput if a solid is
  //! asked for and the mesh cannot be closed.
  MeshConstraint(const TriangleMesh& mesh, const ConstraintOptions& options, double spacing);

  const ConstraintOptions& options() const { return options_; }
  double spacing() const { return spacing_; }
  const TriangleMesh& mesh() const { return mesh_; }  //!< the repaired mesh
  const RepairReport& repair_report() const { return repair_; }
  const Box& box() const { return box_; }
  const InsideTest& inside_test() const { return inside_; }
  //! Centre and radius of a sphere around the mesh: the sphere spawn with a mesh.
  const Vec3& center() const { return center_; }
  double radius() const { return radius_; }

  //! Whether p is on the growing side, and in the shell if there is one (an exact test; always
  //! true for `both` without a shell).
  bool on_growth_side(const Vec3& p) const;

  //! Whether a walker at p can never stick: on the wrong side of a closed surface and farther
  //! than the spacing from it, or outside the shell's voxels. A grid look-up, cheap enough for
  //! every step.
  bool lost(const Vec3& p) const {
    if (shell_) return !shell_->holds(p);
    if (options_.side == Side::both || options_.side == Side::surface) return false;
    std::array<std::size_t, 3> cell;
    return inside_.grid().locate(p, cell) ? lost_cells_.test(cell) : options_.side == Side::inside;
  }

  //! The shell's thickness in mesh units; 0 without one. Walkers in a shell step at most this
  //! far, and a step that would leave its voxels is not taken.
  double shell() const { return shell_thickness_; }

  //! Tests the branch from a particle to a new one against the surface (Embree), and the new
  //! particle against the shell (its exact distance to the surface).
  BranchCheck check_branch(const Vec3& from, const Vec3& to) const;

  //! A point uniform in the enclosed volume (`--spawn inside`); with a shell, in the shell.
  Vec3 draw_inside(Rng& rng) const;
  //! A point on the segment from the volume's centroid to a point of the surface, both
  //! uniform (`--spawn radial`, Bourke's figure 5): thin features get walkers in proportion to
  //! their surface, not their tiny volume.
  Vec3 draw_radial(Rng& rng) const;
  //! A point half a spacing off the surface on the growing side, uniform by area
  //! (`--spawn surface`): growth reaches every part of the mesh, thin horns included, as the
  //! thesis' roots fill a model from its skin.
  Vec3 draw_near_surface(Rng& rng) const;

  //! `count` seeds on the growing side: inside, deep and far apart; outside, a little off the
  //! surface and far apart. The same for the same `rng_seed`. Throws InvalidInput if they do
  //! not fit.
  std::vector<Vec3> place_seeds(std::size_t count, std::uint64_t rng_seed) const;

  //! The surface sampled at the spacing, as seeds (`--seed-surface`): points half a spacing off
  //! it on the growing side, uniform by area, no two closer than the spacing (dart throwing, 4
  //! tries per spacing² of area). With `paint`, only its painted part (`--seed-paint`). The
  //! same for the same `rng_seed`. Throws InvalidInput for a surface of more than 500,000
  //! spacings², with `--side both`, and for paint on a mesh without colours or not on it.
  std::vector<Vec3> sample_surface(std::uint64_t rng_seed, const Paint* paint = nullptr) const;
  //! `count` points half a spacing off the part of the surface painted `paint`, on the growing
  //! side, uniform by its area (`attractor_paint`). Throws InvalidInput as require_paint() does,
  //! naming `option`.
  std::vector<Vec3> draw_near_paint(std::size_t count, Rng& rng, const Paint& paint, const char* option) const;
  //! Throws InvalidInput, naming `option`, where the mesh has no vertex colours or no part of
  //! it is painted within the paint's tolerance, saying what colours it has.
  void require_paint(const Paint& paint, const char* option) const;

  //! Seeds where other meshes enter this one (`--seed-mesh`): along the curves where their
  //! surfaces cross this surface, and over the patches where they overlap it in a plane, half a
  //! spacing off it on the growing side, a spacing apart. Open and self-intersecting meshes
  //! work: only their triangles count. Throws InvalidInput when none meets the surface, with
  //! `--side both`, or for more than 500,000 spacings of curve.
  std::vector<Vec3> sample_intersection(const std::vector<TriangleMesh>& others, std::uint64_t rng_seed) const;

  //! Distance from p to the nearest triangle.
  double distance_to_surface(const Vec3& p) const;
  //! Closest points of the surface: what the look measures, and vessels push out to.
  const SurfaceDistance& surface() const { return surface_; }

 private:
  //! A point of the surface, uniform by area; its triangle's unit normal in `normal` and its
  //! index in `triangle`, where asked for.
  Vec3 surface_point(Rng& rng, Vec3* normal, std::uint32_t* triangle = nullptr) const;
  static constexpr std::uint32_t kNoTriangle = ~std::uint32_t{0};
  //! s moved half a spacing along ±normal to the growing side (to either, at random, when both
  //! grow); not finite if neither side is. s on `triangle`, where known, saves most inside tests.
  Vec3 beside(const Vec3& s, const Vec3& normal, Rng& rng, std::uint32_t triangle = kNoTriangle) const;
  //! Where half a spacing off triangle t on `side` (+1 along its normal, -1 against it) lies.
  enum class Offset : std::uint8_t {
    unknown,  //!< not asked yet
    growing,  //!< all of it on the growing side
    other,    //!< all of it on the other side
    mixed,    //!< not known to be all on one side: ask the inside test point by point
  };
  Offset offset_side(std::uint32_t t, double side) const;
  bool encloses(const Vec3& p) const;  // inside, by the grid where it can tell
  bool in_shell(const Vec3& p) const;  // exact: within the shell's thickness, on its side

  ConstraintOptions options_;
  double spacing_;
  RepairReport repair_;
  TriangleMesh mesh_;
  Box box_;
  Vec3 center_;
  double radius_ = 0.0;
  Vec3 centroid_;              // of the enclosed volume, for the radial spawn
  double gap_ = 0.0;           // how far short of the surface a clipped branch ends
  std::vector<double> area_prefix_;  // cumulative triangle areas, to sample the surface
  std::vector<std::uint32_t> area_guide_;  // the first prefix past each slice's start
  //! Where the j-th of area_prefix_.size() equal slices of the total area starts.
  double slice_start(std::size_t j) const {
    return area_prefix_.back() * (static_cast<double>(j) / static_cast<double>(area_prefix_.size()));
  }
  InsideTest inside_;
  // The cells of the inside grid where walkers are lost, looked up on every step: mostly in
  // bricks with none, whose bits stay in the caches.
  BrickBits lost_cells_;
  SurfaceIntersector hits_;
  SurfaceDistance surface_;
  double shell_thickness_ = 0.0;
  std::unique_ptr<ShellBand> shell_;              // with a shell: where walkers may go
  // offset_side() of each triangle for beside()'s first side, found on the triangle's first
  // start by any thread (all find the same): on a closed mesh, empty on an open one.
  mutable std::vector<std::atomic<Offset>> offset_sides_;
};

//! `count` of `points`, far apart: the one nearest their mean first, then each the farthest
//! from those taken (`--seeds K` with paint or other meshes). Throws InvalidInput if there are
//! fewer points than `count`.
std::vector<Vec3> farthest_apart(const std::vector<Vec3>& points, std::size_t count);

//! Closest distance from p to triangle (a, b, c).
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace dla
