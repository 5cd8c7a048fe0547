// The files a run writes: their words, names and checks (output.h).

#include "dla/run/output.h"

#include "dla/io/html_writer.h"
#include "dla/io/mesh_writers.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace dla {

namespace {

//! Each format's word, its flag in Formats, and the files it writes after PREFIX.
struct FormatEntry {
  const char* word;
  bool Formats::*flag;
  std::vector<const char*> suffixes;
};

const std::vector<FormatEntry>& format_table() {
  static const std::vector<FormatEntry> table = {
      {"pov", &Formats::pov, {".pov", ".inc", "_growth.inc"}},
      {"csv", &Formats::csv, {".csv"}},
      {"spheres", &Formats::spheres, {"_spheres.csv"}},
      {"mstm", &Formats::mstm, {"_mstm.pos"}},
      {"ddscat", &Formats::ddscat, {"_ddscat.dat"}},
      {"ply", &Formats::ply, {".ply"}},
      {"glb", &Formats::glb, {".glb"}},
      {"obj", &Formats::obj, {".obj"}},
      {"tips", &Formats::tips, {"_tips.ply"}},
      {"svg", &Formats::svg, {".svg"}},
      {"png", &Formats::png, {".png"}},
      {"html", &Formats::html, {".html"}},
      {"stl", &Formats::stl, {".stl"}},
      {"3mf", &Formats::threemf, {".3mf"}},
      {"vdb", &Formats::vdb, {".vdb"}},
      {"solid-glb", &Formats::solid_glb, {"_solid.glb"}},
      {"solid-obj", &Formats::solid_obj, {"_solid.obj"}},
      {"json", &Formats::json, {".json"}},
  };
  return table;
}

}  // namespace

Formats parse_formats(std::string_view words) {
  Formats formats;
  formats.pov = formats.csv = formats.ply = formats.json = false;
  bool any = false;
  std::size_t start = 0;
  while (start <= words.size()) {
    const std::size_t comma = std::min(words.find(',', start), words.size());
    const std::string_view word = words.substr(start, comma - start);
    start = comma + 1;
    if (word.empty() && comma == words.size()) break;  // "pov," ends as "pov" does
    const FormatEntry* entry = nullptr;
    for (const FormatEntry& e : format_table())
      if (word == e.word) entry = &e;
    if (!entry)
      throw InvalidInput("`formats` '" + std::string(words) + "': '" + std::string(word) + "' is not one of " +
                         kFormatWords);
    formats.*(entry->flag) = any = true;
  }
  if (!any) throw InvalidInput(std::string("`formats` is empty: name at least one of ") + kFormatWords);
  if (formats.html && !has_web_viewer())
    throw InvalidInput("`formats` html: this dla3d was built without npm, which fetches the web viewer's three.js; "
                       "install npm and build again");
  return formats;
}

std::string format_words(const Formats& formats) {
  std::string words;
  for (const FormatEntry& e : format_table())
    if (formats.*(e.flag)) words += (words.empty() ? "" : ",") + std::string(e.word);
  return words;
}

void check_glb_options(const OutputOptions& output) {
  if (output.lods > 0 && !output.formats.glb)
    throw InvalidInput("`lod` " + std::to_string(output.lods) + " writes levels of the glb: add glb to `formats`");
  if (output.leaf.empty()) return;
  if (!output.formats.glb) throw InvalidInput("`leaf` places leaves in the glb: add glb to `formats`");
}

std::vector<std::string> file_names(const OutputOptions& output) {
  std::vector<std::string> names;
  for (const FormatEntry& e : format_table())
    if (output.formats.*(e.flag)) {
      for (const char* suffix : e.suffixes) names.push_back(output.output + suffix);
      if (e.flag == &Formats::glb)
        for (int level = 1; level <= output.lods; ++level)
          names.push_back(output.output + "_lod" + std::to_string(level) + ".glb");
    }
  return names;
}

const OptionTable<OutputOptions>& output_option_table() {
  using O = OutputOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> rows;
    const auto add = [&rows](const OptionTable<O>& more) { rows.insert(rows.end(), more.begin(), more.end()); };
    rows.push_back(word("ply_format", &O::ply_encoding, "Output",
                        "the PLYs as binary (little-endian) or ascii (text: twice the size, three times slower to write)"));
    add(nested(png_option_table(), &O::png));
    rows.push_back(override_of(*find_option(pov_option_table(), "up"), &O::up));
    for (const DescribedOption<LookOptions>& row : look_option_table()) {
      const std::string_view name = row.about.name;
      if (name == "radius") rows.push_back(override_of(row, &O::radius));
      else if (name == "base_radius") rows.push_back(override_of(row, &O::base_radius));
      else if (name == "tip_radius") rows.push_back(override_of(row, &O::tip_radius));
      else add(nested(OptionTable<LookOptions>{row}, &O::look));
      if (name == "color_by") add(nested(OptionTable<PovOptions>{*find_option(pov_option_table(), "look")}, &O::pov));
    }
    rows.push_back(integer("ddscat_resolution", &O::ddscat_resolution, closed(1, 50), "dipoles", "Output",
                           "ddscat: dipoles along a mean sphere radius; the shape file's lattice spacing is the "
                           "spheres' mean radius over this, and its dipoles go as its cube"));
    rows.push_back(integer("lod", &O::lods, closed(0, kMaxLods), "", "Look",
                           "glb: levels of detail beside it, PREFIX_lod1.glb on, each with about half the triangles "
                           "of the one before"));
    add(nested(instance_option_table(), &O::instances));
    rows.push_back(file("leaf", &O::leaf, "FILE.glb", "Look",
                        "glb: a binary glTF whose mesh goes at each instancing point (as tips picks them), along its "
                        "direction and scaled by its pscale; its +Y is the leaf's stem"));
    add(nested(OptionTable<InstanceOptions>{with_paint_role(
                   colour("tips_exclude_paint", &InstanceOptions::exclude_paint, "Look",
                          "tips: leave out the points whose closest point of the mesh's surface is painted this "
                          "colour (a name or ff8000), within TOLERANCE per channel, [0, 1), default 0.3"),
                   PaintRole::bare)},
               &O::instances));
    add(nested(solid_option_table(), &O::solid));
    return rows;
  }();
  return table;
}

const OptionTable<OutputOptions>& files_option_table() {
  using O = OutputOptions;
  static const OptionTable<O> table{
      with_short_name(file("output", &O::output, "PREFIX", "Output", "prefix of the files written"), "o"),
      parsed<O>("formats", OptionKind::text, "LIST", "Output",
                "files to write, a comma list of pov, csv, spheres (PREFIX_spheres.csv: x,y,z,r), mstm (MSTM's "
                "PREFIX_mstm.pos), ddscat (DDSCAT's PREFIX_ddscat.dat), ply, json, glb, obj, tips (PREFIX_tips.ply, "
                "and with pov PREFIX_tips.inc), svg and png (2D), html (the web viewer), and the watertight solid: "
                "stl, 3mf, vdb, solid-glb, solid-obj",
                [](O& o, const std::string& words) { o.formats = parse_formats(words); },
                [](const O& o) { return format_words(o.formats); }),
  };
  return table;
}

void validate(const OutputOptions& f, int dimensions, bool with_mesh) {
  require_in_ranges(output_option_table(), f);  // the overrides a mesh gives defaults for too
  if (f.formats.svg && dimensions != 2)
    throw InvalidInput("`formats` svg draws 2D growth: add `dimensions` 2, or leave svg out");
  if (f.formats.png && dimensions != 2)
    throw InvalidInput("`formats` png draws 2D growth: add `dimensions` 2, or leave png out");
  validate(f.png);    // its margin
  validate(f.solid);  // its print size against its walls
  if (!with_mesh) {
    if (f.radius.value_or(f.look.radius.model) == RadiusModel::boundary)
      throw InvalidInput("`radius` boundary measures to a constraint mesh: give one with `stl`");
    if (f.instances.within != std::numeric_limits<double>::infinity())
      throw InvalidInput("`tips_within` measures to a constraint mesh: give one with `stl`");
    if (f.instances.exclude_paint)
      throw InvalidInput("`tips_exclude_paint` reads the paint of a constraint mesh: give one with `stl`");
  }
  if (f.output.empty()) throw InvalidInput("`output` is empty");
  if (f.output.back() == '/') throw InvalidInput("`output` '" + f.output + "' names a folder, not a file prefix");
  if (f.formats.pov) validate_pov_prefix(f.output);
}

void check_writable(const std::string& path) {
  const std::string probe = path + ".tmp";
  {
    std::ofstream out(probe);
    if (!out) throw InvalidInput("cannot write '" + path + "': " + std::strerror(errno));
  }
  std::remove(probe.c_str());
}

}  // namespace dla
