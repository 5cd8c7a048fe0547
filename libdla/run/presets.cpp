// The presets (presets.h): each from a command the docs show with its picture, so that a preset
// grows what its page shows.

#include "dla/run/presets.h"

#include "dla/core/errors.h"

#include <string>

namespace dla {

const std::vector<Preset>& presets() {
  static const std::vector<Preset> table = {
      {"grow", "main-job", "Bourke's main job: two seeds in the mesh of --stl, grown to fill it (README)",
       {{"seeds", "2"}}},
      {"grow", "roots", "roots from three seeds that fill the vessel of --stl, coloured by age (constraints.md)",
       {{"seeds", "3"}, {"fill", "0.9"}, {"color_by", "age"}}},
      {"grow", "coral", "a coral of metaballs, thick at the base (gallery.md)",
       {{"particles", "3000"}, {"look", "blob"}, {"radius", "pipe"}, {"tip_radius", "0.2"}, {"base_radius", "1.5"}}},
      {"grow", "frost", "frost over the surface of --stl, in a shell 3 spacings thick (constraints.md)",
       {{"side", "outside"}, {"shell", "3"}, {"particles", "20000"}, {"base_radius", "1.5"}}},
      {"colonize", "tree", "a tree: a trunk from the ground to a crown of attractors (look.md)",
       {{"attractors", "3000"}, {"attractor_center", "0,30,0"}, {"attractor_radius", "22"}, {"kill_distance", "3"},
        {"root_at", "0,0,0"}, {"radius", "pipe"}, {"base_radius", "1.2"}, {"tip_radius", "0.1"}, {"up", "y"}}},
      {"colonize", "veins", "veins that crawl over the surface of --collide towards attractors on it (colonization.md)",
       {{"collision", "stick"}, {"attractors_in", "surface"}, {"attractors", "5000"}, {"kill_distance", "3"},
        {"radius", "pipe"}, {"base_radius", "1.5"}, {"tip_radius", "0.4"}}},
      {"breakdown", "lightning", "a bolt from a point 40 above to the ground 40 below (breakdown.md)",
       {{"eta", "3"}, {"seed_at", "0,40,0"}, {"target_plane", "y=-40"}, {"radius", "pipe"}, {"tip_radius", "0.3"},
        {"base_radius", "2.5"}, {"color_by", "age"}}},
      {"breakdown", "lichtenberg", "a Lichtenberg figure that glows over the surface of --stl (breakdown.md)",
       {{"eta", "3"}, {"side", "surface"}, {"seeds", "1"}, {"particles", "5000"}, {"radius", "pipe"},
        {"tip_radius", "0.08"}, {"base_radius", "0.7"}, {"look", "glow"}}},
      {"breakdown", "spark", "a spark between two points 40 apart, glowing (breakdown.md)",
       {{"eta", "3"}, {"seed_at", "0,0,0"}, {"target_point", "40,0,0"}, {"particles", "3000"}, {"radius", "pipe"},
        {"tip_radius", "0.3"}, {"base_radius", "1.5"}, {"look", "glow"}}},
      {"drop", "sticky-pixels", "Roberts' Sticky Pixels, figure 7: random drops in the plane, as a PNG (drop.md)",
       {{"dimensions", "2"}, {"particles", "30000"}, {"formats", "png,json"}}},
  };
  return table;
}

std::vector<const Preset*> presets_of(std::string_view model) {
  std::vector<const Preset*> found;
  for (const Preset& preset : presets())
    if (preset.model == model) found.push_back(&preset);
  return found;
}

const Preset& find_preset(std::string_view model, std::string_view name) {
  std::string accepted;
  for (const Preset* preset : presets_of(model)) {
    if (preset->name == name) return *preset;
    accepted += (accepted.empty() ? "" : ", ") + std::string(preset->name);
  }
  if (accepted.empty()) throw InvalidInput(std::string(model) + " has no presets");
  throw InvalidInput("`preset` '" + std::string(name) + "' is not one of " + accepted);
}

}  // namespace dla
