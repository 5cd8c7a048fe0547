// The option descriptions (dla/core/option_description.h) and the modes' word tables
// (dla/core/words.h): each description's default lies in its range, its ends are taken and a
// step past them refused by name, each choice is its mode's word, and validate() refuses what
// the description refuses.

#include "dla/core/option_description.h"
#include "dla/core/options.h"
#include "dla/io/ply_writer.h"
#include "dla/io/pov_writer.h"
#include "dla/look/color_map.h"
#include "dla/look/instances.h"
#include "dla/look/radius_model.h"
#include "dla/look/solid.h"
#include "dla/mesh/constraint.h"
#include "dla/models/breakdown.h"
#include "dla/run/models.h"
#include "dla/run/output.h"
#include "dla/models/colonization.h"
#include "dla/models/drop.h"
#include "dla/models/eden.h"
#include "dla/run/models.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>
#include <string>

namespace dla {
namespace {

//! Every word of the mode parses to its value and back, the words are distinct, and a word
//! that is none of them is refused with all of them listed.
template <class Mode>
void expect_words_round_trip() {
  std::set<std::string_view> seen;
  for (const Word<Mode>& w : words_of(Mode{}).words) {
    EXPECT_EQ(parse_word<Mode>(w.word), w.value) << w.word;
    EXPECT_EQ(to_string(w.value), w.word);
    EXPECT_TRUE(seen.insert(w.word).second) << "twice: " << w.word;
  }
  try {
    parse_word<Mode>("none-of-these");
    ADD_FAILURE() << words_of(Mode{}).what << " took a word it does not have";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), std::string(words_of(Mode{}).what) + " 'none-of-these' is not one of " +
                                         accepted_words<Mode>());
  }
}

TEST(Words, EveryModeParsesItsOwnWordsAndRefusesOthers) {
  expect_words_round_trip<SpawnMode>();
  expect_words_round_trip<Axis>();
  expect_words_round_trip<IndexKind>();
  expect_words_round_trip<SolidShape>();
  expect_words_round_trip<RadiusModel>();
  expect_words_round_trip<InstanceSet>();
  expect_words_round_trip<ColorBy>();
  expect_words_round_trip<BreakdownField>();
  expect_words_round_trip<TargetKind>();
  expect_words_round_trip<Lattice>();
  expect_words_round_trip<EdenMode>();
  expect_words_round_trip<EdenMask>();
  expect_words_round_trip<DropZone>();
  expect_words_round_trip<AttractorRegion>();
  expect_words_round_trip<CollisionMode>();
  expect_words_round_trip<Venation>();
  expect_words_round_trip<RootRegion>();
  expect_words_round_trip<PovStyle>();
  expect_words_round_trip<PlyEncoding>();
  expect_words_round_trip<Side>();
  expect_words_round_trip<ConstraintMode>();
  EXPECT_EQ(to_string(RadiusModel::seed_distance), "seed-distance");
}

std::string refusal(const std::function<void()>& act) {
  try {
    act();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

//! What every described option must hold, on a default-made Options.
template <class Options>
void expect_described_soundly(const OptionTable<Options>& table) {
  std::set<std::string_view> names;
  for (const DescribedOption<Options>& option : table) {
    const OptionDescription& about = option.about;
    SCOPED_TRACE(std::string(about.name));
    EXPECT_TRUE(names.insert(about.name).second) << "described twice";
    EXPECT_FALSE(about.help.empty());
    EXPECT_FALSE(about.group.empty());
    EXPECT_EQ(about.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_"), std::string_view::npos);
    const Options defaults{};
    const OptionValue value = option.get(defaults);
    // The default is taken back as it is.
    Options again{};
    EXPECT_EQ(refusal([&] { option.set(again, value); }), "");
    EXPECT_TRUE(option.get(again) == value);
    switch (about.kind) {
      case OptionKind::flag:
        ASSERT_TRUE(std::holds_alternative<bool>(value));
        for (const bool on : {true, false}) {
          option.set(again, on);
          EXPECT_TRUE(option.get(again) == OptionValue(on));
        }
        break;
      case OptionKind::word: {
        ASSERT_FALSE(about.choices.empty());
        for (std::string_view choice : about.choices) {
          option.set(again, std::string(choice));
          EXPECT_TRUE(option.get(again) == OptionValue(std::string(choice))) << choice;
        }
        EXPECT_EQ(refusal([&] { option.set(again, std::string("none-of-these")); }).rfind("`" + std::string(about.name) + "` 'none-of-these' is not one of ", 0), 0u);
        break;
      }
      case OptionKind::integer:
      case OptionKind::real: {
        ASSERT_TRUE(about.range);
        const Range& r = *about.range;
        const double d = std::holds_alternative<double>(value) ? std::get<double>(value)
                                                                : static_cast<double>(std::get<std::int64_t>(value));
        EXPECT_TRUE(r.contains(d) || (about.special && about.special->value == d)) << "the default " << d;
        const auto as_value = [&](double v) {
          return about.kind == OptionKind::integer ? OptionValue(static_cast<std::int64_t>(v)) : OptionValue(v);
        };
        const double step = about.kind == OptionKind::integer ? 1.0 : std::max(std::abs(r.max - r.min) * 1e-3, 1e-9);
        const std::string named = "`" + std::string(about.name) + "` ";
        // Each end: taken when closed, refused when open; a step past it refused by name.
        struct End {
          double at;
          bool open;
          double outward;
        };
        for (const End& e : {End{r.min, r.min_open, -1.0}, End{r.max, r.max_open, 1.0}}) {
          const double end = e.at, outward = e.outward;
          const bool open = e.open;
          const std::string at_end = refusal([&] { option.set(again, as_value(end)); });
          if (open && !(about.special && about.special->value == end)) EXPECT_EQ(at_end.rfind(named, 0), 0u) << end;
          else EXPECT_EQ(at_end, "") << end;
          const double past = end + outward * (open ? 0.0 : step);
          if (about.special && past == about.special->value) continue;
          const std::string refused = refusal([&] { option.set(again, as_value(past)); });
          EXPECT_EQ(refused.rfind(named, 0), 0u) << refused;
          EXPECT_NE(refused.find(to_string(r)), std::string::npos) << refused;
        }
        EXPECT_EQ(refusal([&] { option.set(again, std::nan("")); }).rfind(named, 0), 0u);
        if (about.kind == OptionKind::integer && r.max >= r.min + 1) {
          EXPECT_EQ(refusal([&] { option.set(again, r.min + 0.5); }), named + detail::format_number(r.min + 0.5) + " is not a whole number");
        }
        if (about.special) {
          EXPECT_EQ(refusal([&] { option.set(again, as_value(about.special->value)); }), "");
        }
        break;
      }
      case OptionKind::vector:
      case OptionKind::points:
      case OptionKind::colour:
      case OptionKind::text:
      case OptionKind::file: {
        ASSERT_FALSE(about.form.empty());
        EXPECT_EQ(about.repeats, std::holds_alternative<std::vector<std::string>>(value));
        EXPECT_EQ(refusal([&] { option.set(again, true); }).rfind("`" + std::string(about.name) + "` ", 0), 0u);
        // A value of its form is taken and written back as given; one of another form is refused by name.
        std::string sample;
        if (about.kind == OptionKind::colour) sample = "ff8000,0.5";
        if (about.kind == OptionKind::vector || about.kind == OptionKind::points)
          for (std::size_t n = 0, numbers = std::count(about.form.begin(), about.form.end(), ',') + 1; n < numbers; ++n)
            sample += (n ? "," : "") + std::to_string(n) + ".25";
        if (!sample.empty()) {
          const OptionValue given = about.repeats ? OptionValue(std::vector<std::string>{sample, sample}) : OptionValue(sample);
          EXPECT_EQ(refusal([&] { option.set(again, given); }), "");
          EXPECT_TRUE(option.get(again) == given) << to_string(option.get(again));
          EXPECT_EQ(refusal([&] { option.set(again, std::string("x")); }).rfind("`" + std::string(about.name) + "` ", 0), 0u);
        }
        break;
      }
    }
  }
}

TEST(OptionDescription, DlasOptionsAreDescribedSoundly) { expect_described_soundly(dla_option_table()); }

TEST(OptionDescription, DlaRunsOptionsAreDescribedSoundly) {
  expect_described_soundly(dla_run_option_table());
  expect_described_soundly(mesh_seeds_option_table());
  expect_described_soundly(mesh_seeds_option_table(true));
  expect_described_soundly(constraint_option_table());
  expect_described_soundly(links_option_table());
  expect_described_soundly(links_option_table(true));
  expect_described_soundly(files_option_table());
}

TEST(OptionDescription, TextFormsReadWhatTheyPrint) {
  DlaRunOptions o;
  const OptionTable<DlaRunOptions>& table = dla_run_option_table();
  find_option(table, "rotate")->set(o, std::string("y,-30"));
  EXPECT_EQ(o.growth.rotate_axis, Axis::y);
  EXPECT_EQ(o.growth.rotate_degrees, -30.0);
  EXPECT_EQ(refusal([&] { find_option(table, "rotate")->set(o, std::string("w,30")); }),
            "`rotate` 'w,30': its axis is not one of x, y, z");
  find_option(table, "box")->set(o, std::string("-1,-2,-3,4,5,6"));
  EXPECT_EQ(o.growth.spawn_box->min, Vec3(-1, -2, -3));
  EXPECT_EQ(o.growth.spawn_box->max, Vec3(4, 5, 6));
  EXPECT_EQ(refusal([&] { find_option(table, "drift")->set(o, std::string("0.1,0.2")); }),
            "`drift` '0.1,0.2' is not 3 comma-separated numbers");
  // A number the library prints reads back as the same double.
  find_option(table, "drift")->set(o, std::string("0.1,1e-300,-0.30000000000000004"));
  EXPECT_EQ(std::get<std::string>(find_option(table, "drift")->get(o)), "0.1,1e-300,-0.30000000000000004");
  find_option(table, "seeds")->set(o, std::string("all"));
  EXPECT_TRUE(o.seeds.all && o.seeds.whole_surface());
  find_option(table, "seed_paint")->set(o, std::string("red"));
  EXPECT_FALSE(o.seeds.whole_surface());
  EXPECT_EQ(refusal([&] { find_option(table, "seeds")->set(o, std::string("0")); }), "`seeds` 0: there must be a seed");
  find_option(table, "text")->set(o, std::string("A\\nB"));
  EXPECT_EQ(o.text->text, "A\nB");
  EXPECT_EQ(o.text->font, kDefaultFont);
  find_option(table, "links")->set(o, std::string("2,3"));
  EXPECT_EQ(o.links.distance, 2.0);
  EXPECT_EQ(o.links.most, 3u);
  EXPECT_EQ(find_option(table, "stl")->about.alias, "mesh");
  EXPECT_EQ(find_option(table, "stl")->about.form, kMeshFileForm);
}

TEST(OptionDescription, BreakdownsOptionsAreDescribedSoundly) { expect_described_soundly(breakdown_option_table()); }

TEST(OptionDescription, TheOtherModelsOptionsAreDescribedSoundly) {
  expect_described_soundly(colonize_option_table());
  expect_described_soundly(drop_option_table());
  expect_described_soundly(eden_option_table());
}

TEST(OptionDescription, EveryModelsFilesAndLookAreDescribedSoundly) {
  expect_described_soundly(output_option_table());
  // An override a mesh gives its default for stays unset until it is given.
  OutputOptions files;
  const DescribedOption<OutputOptions>* tip = find_option(output_option_table(), "tip_radius");
  ASSERT_NE(tip, nullptr);
  EXPECT_TRUE(tip->get(files) == OptionValue(RadiusOptions{}.tip_radius));
  EXPECT_FALSE(files.tip_radius);
  tip->set(files, 0.125);
  EXPECT_EQ(files.tip_radius, 0.125);
  EXPECT_EQ(files.look.radius.tip_radius, RadiusOptions{}.tip_radius);
}

TEST(OptionDescription, ValidateRefusesWhatTheDescriptionRefuses) {
  // A value set past the description, not through it, is refused by validate() with the
  // description's message: the range is held in one place.
  DlaOptions dla;
  dla.stickiness = 2;
  EXPECT_EQ(refusal([&] { validate(dla); }), "`stickiness` 2 is not in [0.0001, 1]");
  dla = DlaOptions{};
  dla.disk_radius = 0;
  EXPECT_EQ(refusal([&] { validate(dla); }), "`disk_radius` 0 is not in (0, 1000]");
  BreakdownOptions breakdown;
  breakdown.eta = 10.5;
  EXPECT_EQ(refusal([&] { validate(breakdown, DlaOptions{}); }), "`eta` 10.5 is not in [0, 10]");
  breakdown = BreakdownOptions{};
  breakdown.walkers = 4097;
  EXPECT_EQ(refusal([&] { validate(breakdown, DlaOptions{}); }), "`walkers` 4097 is not in [1, 4096] (0: chosen by eta)");
  breakdown.walkers = 0;
  EXPECT_EQ(refusal([&] { validate(breakdown, DlaOptions{}); }), "");
  OutputOptions files;
  files.look.tubes.sides = 65;
  EXPECT_EQ(refusal([&] { validate(files, 3, false); }), "`tube_sides` 65 is not in [3, 64]");
  files = OutputOptions{};
  files.base_radius = 2000;
  EXPECT_EQ(refusal([&] { validate(files, 3, false); }), "`base_radius` 2000 is not in [0.001, 1000]");
  files = OutputOptions{};
  files.solid.voxel = -1;
  EXPECT_EQ(refusal([&] { validate(files, 3, false); }),
            "`solid_voxel` -1 is not in [0.001, 100] (0: a third of the thinnest branch's diameter)");
}

TEST(OptionDescription, RangesAndNamesAreWrittenAsTheFrontEndsSpellThem) {
  EXPECT_EQ(to_string(closed(0, 10)), "[0, 10]");
  EXPECT_EQ(to_string(open_closed(0, 1000)), "(0, 1000]");
  EXPECT_EQ(to_string(Range{0, 1, true, true}), "(0, 1)");
  EXPECT_TRUE(open_closed(0, 1).contains(1));
  EXPECT_FALSE(open_closed(0, 1).contains(0));
  EXPECT_FALSE(closed(0, 1).contains(std::nan("")));
  EXPECT_EQ(cli_flag("stop_at_strike"), "--stop-at-strike");
  EXPECT_EQ(spell_options("`min_step` 2 is not in [0.01, 1]", OptionSpelling::cli), "--min-step 2 is not in [0.01, 1]");
  EXPECT_EQ(spell_options("`min_step` 2 is not in [0.01, 1]", OptionSpelling::python), "min_step=2 is not in [0.01, 1]");
  // A word's choices are its mode's table, in its order.
  const DescribedOption<BreakdownOptions>* field = find_option(breakdown_option_table(), "field");
  ASSERT_NE(field, nullptr);
  EXPECT_EQ(field->about.choices, words_list<BreakdownField>());
  EXPECT_EQ(find_option(breakdown_option_table(), "no_such_option"), nullptr);
}

}  // namespace
}  // namespace dla
