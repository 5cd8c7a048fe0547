#pragma once
//! \file output.h
//! What a run of any model writes and how it looks: the files under one prefix, the look they
//! share, the POV-Ray scene's settings and the instancing points. See docs/formats.md.

#include "dla/io/mesh_writers.h"
#include "dla/io/ply_writer.h"
#include "dla/io/png_writer.h"
#include "dla/io/pov_writer.h"
#include "dla/look/instances.h"
#include "dla/look/look.h"
#include "dla/look/solid.h"
#include "dla/mesh/constraint.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dla {

//! The files a run writes (`formats`), each PREFIX.EXT; tips writes PREFIX_tips.ply (and with
//! pov, PREFIX_tips.inc), spheres PREFIX_spheres.csv, mstm PREFIX_mstm.pos, ddscat
//! PREFIX_ddscat.dat.
struct Formats {
  bool pov = true, csv = true, ply = true, json = true;
  bool spheres = false;  //!< the sphere list, `x,y,z,r` (csv_writer.h): for light-scattering codes
  bool mstm = false, ddscat = false;  //!< the spheres as MSTM and DDSCAT read them (scattering_writers.h)
  bool glb = false, obj = false, tips = false, svg = false, png = false, html = false;
  //! The solid (solid.h): PREFIX.stl, PREFIX.3mf, PREFIX.vdb, PREFIX_solid.glb, PREFIX_solid.obj.
  bool stl = false, threemf = false, vdb = false, solid_glb = false, solid_obj = false;

  bool solid() const { return stl || threemf || vdb || solid_glb || solid_obj; }
  //! Without the solid's files, for a structure stopped short; with the CSV instead when no
  //! other file would hold the structure.
  void leave_out_solid() {
    stl = threemf = vdb = solid_glb = solid_obj = false;
    csv = csv || !(pov || ply || spheres || mstm || glb || obj || svg || png || html);
  }
};

//! The formats' words, in the order file_names() lists them.
inline constexpr const char* kFormatWords =
    "pov, csv, spheres, mstm, ddscat, ply, json, glb, obj, tips, svg, png, html, stl, 3mf, vdb, solid-glb, solid-obj";

//! "pov,csv,glb" as formats. Throws InvalidInput, naming `formats`, for an unknown or no word,
//! and for html when this build has no web viewer.
Formats parse_formats(std::string_view words);
//! The words of `formats`, as parse_formats() reads them: "pov,csv,ply,json".
std::string format_words(const Formats& formats);

struct OutputOptions {
  std::string output = "dla";                      //!< prefix of the files written
  Formats formats;
  PlyEncoding ply_encoding = PlyEncoding::binary;  //!< the PLYs (and PREFIX_tips.ply)
  PngOptions png;                                  //!< png: scale and bands
  LookOptions look;                                //!< radius model, colour, tubes
  InstanceOptions instances;                       //!< tips: which particles, how near the mesh
  PovOptions pov;                                  //!< the scene: style, up axis
  SolidOptions solid;                              //!< the solid's files: voxel, smoothing, print size
  int ddscat_resolution = 5;  //!< ddscat: dipoles along a mean sphere radius, in [1, 50]
  int lods = 0;  //!< glb: levels of detail beside it, PREFIX_lod1.glb on, in [0, kMaxLods] (mesh_writers.h)
  //! glb: a binary glTF whose leaf (leaf.h) goes at each instancing point `instances` picks;
  //! empty for none.
  std::string leaf;
  //! Defaults a mesh changes when they are not given: the up axis (the mesh's longest side's),
  //! and for DLA in a mesh the radius model (pipe) and range (3 to 0.05 spacings). Unset, the
  //! values in `pov` and `look` hold.
  std::optional<Axis> up;
  std::optional<RadiusModel> radius;
  std::optional<double> base_radius, tip_radius;
};

//! The files' and the look's options with a single value, described once
//! (option_description.h): the tables of PngOptions, PovOptions, LookOptions, InstanceOptions
//! and SolidOptions as options of OutputOptions, those a mesh gives a default for setting its
//! overrides (`up`, `radius`, `base_radius`, `tip_radius`); the leaf and the paint the tips leave
//! out.
const OptionTable<OutputOptions>& output_option_table();
//! The files' prefix and formats, described once: the CLI's `--output` and `--formats`. Python
//! gives them to Result.write() instead.
const OptionTable<OutputOptions>& files_option_table();

//! Throws InvalidInput for levels of detail or a leaf without the glb they belong to: checked
//! where the formats are final, before growth on the command line and at write() in Python.
//! The leaf file itself is read, once, by prepare_run (Run::leaf).
void check_glb_options(const OutputOptions& output);

//! The files `output` writes, in `formats` order, for a summary.
std::vector<std::string> file_names(const OutputOptions& output);

//! Throws InvalidInput, with one line naming the option, for output that cannot work with a
//! run of `dimensions`, with or without a mesh to measure to (the mesh's defaults resolved).
void validate(const OutputOptions& output, int dimensions, bool with_mesh);

//! What the files of a structure measure to and show, beside their options.
struct WriteContext {
  int threads = 1;                             //!< for the look's measurements
  const MeshConstraint* constraint = nullptr;  //!< the boundary radius model measures to its mesh
  const TriangleMesh* scene_mesh = nullptr;    //!< the POV-Ray scene and the web viewer show it
  std::string comment;                         //!< the POV-Ray scene's first line (the command)
  //! Set, it stops the look's measures, the solid and every writer within milliseconds: the
  //! files finished stay, no other file is written.
  const StopFlag* stop = nullptr;
  StageProgress solid_progress;                //!< how the solid's build goes (solid.h)
  //! Closest triangles of the constraint's surface measured before (Run::measured_while_growing),
  //! or null.
  const MeasuredClosest* measured = nullptr;
  //! The leaf of `leaf`, read once before growth (Run::leaf); null: read here if the glb wants it.
  const Leaf* leaf = nullptr;
};

//! What writing measured: the solid's measures, when a solid format was asked for.
struct FilesWritten {
  std::optional<SolidMeasures> solid;
  GlbWritten glb;  //!< the glb's levels of detail and leaves
};

//! Makes the look and writes every file `files.formats` asks for but the JSON record (which
//! needs a run: run.h's write_run), each by its writer behind one signature and on a thread of
//! its own: the same bytes as one by one. The solid is built once for all its files. Throws
//! InvalidInput, before any file is written, for a solid that would take more memory than it
//! may; IOError if a file cannot be written; and Interrupted, once every writer has ended, when
//! `context.stop` stopped them: the files finished by then stay whole, the others are not
//! written (none stands half-written under its name).
FilesWritten write_files(const Cluster& cluster, const OutputOptions& files, const WriteContext& context = {});

//! Fails early, before a long run, if `path` cannot be created (its temporary name is tried):
//! throws InvalidInput.
void check_writable(const std::string& path);

}  // namespace dla
