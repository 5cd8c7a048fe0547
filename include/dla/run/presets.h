#pragma once
//! \file presets.h
//! Named sets of options, a few per model, to start from: `dla3d MODEL --preset NAME` (`--preset
//! list` prints them), the studio's Preset menu, and `dla3d options`. One table for every front
//! end; an option given beside the preset overrides the preset's. A preset's options are
//! recorded in the JSON like any other.

#include <string_view>
#include <vector>

namespace dla {

//! One option of a preset: its name as C++ and Python spell it (the CLI's flag is cli_flag() of
//! it; a flag that turns an option off is named by its negation), and its value as the CLI
//! writes it; empty for a flag.
struct PresetOption {
  std::string_view name;
  std::string_view value;
};

struct Preset {
  std::string_view model;    //!< the registry's name of the model (models(): grow, colonize, ...)
  std::string_view name;     //!< one word, as --preset takes it
  std::string_view summary;  //!< what it grows, and what it needs (a mesh) in a line
  std::vector<PresetOption> options;
};

//! Every preset, by model in the registry's order.
const std::vector<Preset>& presets();

//! The presets of the model named `model`, in order.
std::vector<const Preset*> presets_of(std::string_view model);

//! The preset `name` of `model`; throws InvalidInput "`preset` 'x' is not one of a, b" for a
//! name it does not have.
const Preset& find_preset(std::string_view model, std::string_view name);

}  // namespace dla
