#pragma once
//! \file run_report.h
//! The JSON sidecar of a run: version, the model and its effective options and RNG seed
//! (enough to grow the same structure again), the look, counts, the model's statistics,
//! measures and timings. What is the model's own, each model's run writes (run/run.h);
//! write_run_report() writes the rest around it, the same for every model.

#include "dla/core/cluster.h"
#include "dla/io/json.h"
#include "dla/look/look.h"
#include "dla/look/solid.h"
#include "dla/io/pov_writer.h"

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dla {

//! What the sidecar records of the run itself, beyond the structure and the options.
struct RunRecord {
  double grow_seconds = 0.0;
  double write_seconds = 0.0;
  std::string command;     //!< the command line that made the run, if any
  std::string stopped_by;  //!< why growth ended before the count (a signal, an error), if it did
  //! The stage a stop (a signal, a callback) ended: "growth", "links" or "files"; empty if none.
  std::string stopped_in;
  std::optional<SolidMeasures> solid;  //!< what the solid measures, when one was written
  bool printed = false;                //!< the solid was sized for print: its units are mm
  std::vector<std::size_t> lod_triangles;  //!< each level of detail's triangles (`lod`), from level 1
  std::optional<std::size_t> leaves;       //!< the glb's leaf nodes, when a leaf (`leaf`) was given
};

//! The solid's measures in a line, for a summary: volume, area, shells, thinnest wall.
std::string describe(const SolidMeasures& solid, bool printed);

//! A JSON object written a field a line, objects within it indented, commas where they go:
//! how a model writes its part of the sidecar.
class RecordWriter {
 public:
  RecordWriter() : text_("{") {}

  RecordWriter& number(std::string_view name, double value, int digits = 0) {
    return field(name, json::number(value, digits));
  }
  RecordWriter& integer(std::string_view name, long long value) { return field(name, std::to_string(value)); }
  RecordWriter& count(std::string_view name, std::uint64_t value) { return field(name, std::to_string(value)); }
  //! count() of each (name, value), in order: a model's statistics.
  RecordWriter& counts(std::initializer_list<std::pair<std::string_view, std::uint64_t>> named) {
    for (const auto& [name, value] : named) count(name, value);
    return *this;
  }
  RecordWriter& text(std::string_view name, std::string_view value) { return field(name, json::string(value)); }
  RecordWriter& flag(std::string_view name, bool value) { return field(name, value ? "true" : "false"); }
  RecordWriter& point(std::string_view name, const Vec3& p) { return field(name, point_json(p)); }
  RecordWriter& points(std::string_view name, const std::vector<Vec3>& points) {
    std::string list = "[";
    for (std::size_t i = 0; i < points.size(); ++i) list += (i ? ", " : "") + point_json(points[i]);
    return field(name, list + "]");
  }
  //! A value already in JSON: null, an array of arrays.
  RecordWriter& raw(std::string_view name, std::string_view json) { return field(name, json); }
  //! "name": { ... }: the fields that follow go in it, up to close().
  RecordWriter& open(std::string_view name) {
    field(name, "{");
    ++depth_;
    first_ = true;
    return *this;
  }
  RecordWriter& close() {
    --depth_;
    text_ += '\n' + std::string(2 * depth_, ' ') + '}';
    first_ = false;
    return *this;
  }
  //! The whole object, closed, with a newline.
  std::string finish() const { return text_ + "\n}\n"; }

  static std::string point_json(const Vec3& p) {
    return '[' + json::number(p.x()) + ", " + json::number(p.y()) + ", " + json::number(p.z()) + ']';
  }

 private:
  RecordWriter& field(std::string_view name, std::string_view value) {
    text_ += first_ ? "\n" : ",\n";
    text_.append(2 * depth_, ' ');
    text_ += json::string(name);
    text_ += ": ";
    text_ += value;
    first_ = false;
    return *this;
  }

  std::string text_;
  int depth_ = 1;
  bool first_ = true;
};

//! A model's part of the sidecar of its run.
struct ModelRecord {
  ModelRecord(std::string_view model, std::uint64_t rng_seed) : model(model), rng_seed(rng_seed) {}

  std::string_view model;  //!< "model": the registry's name (Run::model): grow, colonize, eden, ...
  std::uint64_t rng_seed;
  //! Writes the fields of "options": what grows the same structure again (a run's, by its
  //! model's table: Run::record()).
  std::function<void(RecordWriter&)> options;
  //! Writes the fields of "resolved", if any: what the options left to the inputs and the seed
  //! and no option says, such as the seeds a mesh placed ("seed_at").
  std::function<void(RecordWriter&)> resolved;
  //! Writes the model's own objects after "counts" ("walk", "drops", "lines"), if any.
  std::function<void(RecordWriter&)> statistics;
  //! Writes the model's own fields at the end of "measures" (DLA's "filled"), if any.
  std::function<void(RecordWriter&)> measures;
  //! Writes the model's own fields at the end of "timings", if any.
  std::function<void(RecordWriter&)> timings;
};

//! Writes the sidecar of a run that grew `cluster` to `path`: "generator", "version",
//! "command", "complete", "stopped_by", then `model`'s part ("options", "resolved"), "look",
//! "counts", the model's statistics, "measures" and "timings". Throws IOError if the file
//! cannot be written. Everything but the timings is the same for the same options and seed.
void write_run_report(const Cluster& cluster, const ModelRecord& model, const LookOptions& look,
                      const PovOptions& pov, const RunRecord& record, const std::string& path);

}  // namespace dla
