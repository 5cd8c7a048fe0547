// `dla3d breakdown`: the dielectric breakdown model's options (the Discharge group) beside
// DLA's walk, mesh, spawn, look and output options, turned into BreakdownRunOptions.

#include "options.h"

namespace dla::cli {

namespace {

struct BreakdownWords {
  std::string target_point, target_plane;
  WalkCommand walk;
};

//! "y=-60" (or "y,-60"): the plane across the axis at that value.
Target parse_target_plane(const std::string& text) {
  const std::size_t mark = text.find_first_of("=,");
  if (mark == std::string::npos || mark == 0)
    throw InvalidInput("--target-plane '" + text + "' is not AXIS=VALUE (as y=-60)");
  Target target;
  target.kind = TargetKind::plane;
  target.axis = parse_word<Axis>(text.substr(0, mark));
  target.at = parse_numbers("--target-plane's value", text.substr(mark + 1), 1)[0];
  return target;
}

}  // namespace

Subcommand add_breakdown_command(CLI::App& app, const Model& model) {
  auto w = std::make_shared<BreakdownWords>();
  auto b = std::make_shared<BreakdownRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(std::string(model.name), std::string(model.summary));
  command->get_formatter()->column_width(34);
  const char* discharge = "Discharge";
  std::vector<OptionDescription> described;
  auto discharge_options = std::make_shared<DescribedOptions<BreakdownOptions>>(*command, breakdown_option_table(),
                                                                               BreakdownOptions{}, &described);
  CLI::Option* point = command->add_option("--target-point", w->target_point, "the other electrode: a small ball at "
                                                                              "x,y,z; walkers leave it")
                           ->type_name("X,Y,Z")->group(discharge);
  CLI::Option* plane = command->add_option("--target-plane", w->target_plane, "the other electrode: the plane AXIS = "
                                                                              "VALUE (a line in 2D), the ground; "
                                                                              "walkers leave it")
                           ->type_name("AXIS=VALUE")->group(discharge)->excludes(point);
  command->add_option("--target-mesh", b->target_mesh, "the other electrode: a mesh's surface (STL, OBJ, PLY, OFF; "
                                                       "repaired as --stl is), a lightning rod; 3D only")
      ->type_name(kMeshFile)->group(discharge)->excludes(point)->excludes(plane);
  w->walk = add_walk_options(*command, *b, *quiet, described);
  command->add_option_function<std::string>(
             "--fill", [](const std::string&) { refuse_for("breakdown", "fill"); },
             "DLA's: grow until a mesh is full (not for breakdown)")
      ->type_name("F")->group("Mesh constraint");
  return {command,
          [w, b, quiet, discharge_options](CommandLine& line, const std::vector<std::string>&) {
            w->walk.finish();
            BreakdownOptions& o = b->breakdown;
            discharge_options->finish(o);
            if (!w->target_point.empty()) {
              o.target.kind = TargetKind::point;
              o.target.point = parse_vec3("--target-point", w->target_point);
            }
            if (!w->target_plane.empty()) o.target = parse_target_plane(w->target_plane);
            validate(*b);
            line.quiet = *quiet;
            line.run = *b;
          },
          described};
}

}  // namespace dla::cli
