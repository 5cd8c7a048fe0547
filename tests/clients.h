#pragma once
// The real clients the tests hand dla3d's files to: Blender (headless), the Khronos
// glTF-Validator, Chromium driven by Playwright (node, from tests/clients/package.json), and
// for the solids PrusaSlicer and admesh.
// All are optional: a test that needs one skips, by name, when it is missing (the README's
// client step installs them; CI does).

#include "test_util.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>

namespace dla::testing {

//! The path of program `name` on PATH, or "" if there is none.
inline std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(folder) / name;
    if (!folder.empty() && access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

//! The validator's script, or "" if node or the npm package is missing.
inline std::string gltf_validator() {
  const std::string script = TEST_CLIENTS_DIR "/validate_gltf.mjs";
  if (find_program("node").empty() || !std::filesystem::exists(TEST_CLIENTS_DIR "/node_modules/gltf-validator")) return "";
  return script;
}

//! Runs the validator on a .glb: its exit status and its report, whose first line counts
//! `errors=N warnings=N infos=N`.
inline std::pair<int, std::string> validator_report(const std::string& glb) {
  const std::string log = glb + ".validator.txt";
  const std::string command = "node '" + gltf_validator() + "' '" + glb + "' > '" + log + "' 2>&1";
  const int status = std::system(command.c_str());
  std::string report = read_file(log);
  std::filesystem::remove(log);
  return {status, report.empty() ? "the validator did not run" : report};
}

//! Runs the validator on a .glb: "" if it finds no error, else its report.
inline std::string validate_glb(const std::string& glb) {
  auto [status, report] = validator_report(glb);
  return status == 0 ? "" : report;
}

//! The Chromium that view_page.mjs launches: $CHROMIUM, else Debian's /usr/bin/chromium; "" if
//! it is not there.
inline std::string chromium() {
  const char* chosen = std::getenv("CHROMIUM");
  const std::string path = chosen && *chosen ? chosen : "/usr/bin/chromium";
  return access(path.c_str(), X_OK) == 0 ? path : "";
}

//! The web viewer's runner (Playwright driving Debian's Chromium), or "" if node, the npm
//! package or that Chromium is missing.
inline std::string page_viewer() {
  if (find_program("node").empty() || chromium().empty() ||
      !std::filesystem::exists(TEST_CLIENTS_DIR "/node_modules/playwright-core"))
    return "";
  return TEST_CLIENTS_DIR "/view_page.mjs";
}

#define DLA_NEED_CHROMIUM()                                                                       \
  if (::dla::testing::page_viewer().empty())                                                     \
  GTEST_SKIP() << "Chromium or Playwright is missing: install Debian's chromium and run npm ci --prefix " \
                  "tests/clients (the README's client step)"

#define DLA_NEED_GLTF_VALIDATOR()                                                                 \
  if (::dla::testing::gltf_validator().empty())                                                  \
  GTEST_SKIP() << "the glTF-Validator is missing: install node and run npm ci --prefix tests/clients " \
                  "(the README's client step)"

#define DLA_NEED_BLENDER()                                                                        \
  if (::dla::testing::find_program("blender").empty())                                           \
  GTEST_SKIP() << "Blender is missing: install Debian's blender and python3-numpy (the README's client step)"

#define DLA_NEED_PRUSA_SLICER()                                                                   \
  if (::dla::testing::find_program("prusa-slicer").empty())                                      \
  GTEST_SKIP() << "PrusaSlicer is missing: install Debian's prusa-slicer (the README's client step)"

#define DLA_NEED_ADMESH()                                                                         \
  if (::dla::testing::find_program("admesh").empty())                                            \
  GTEST_SKIP() << "admesh is missing: install Debian's admesh (the README's client step)"

}  // namespace dla::testing
