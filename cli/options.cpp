#include "options.h"

namespace dla::cli {

OutputWords::OutputWords(CLI::App& app, OutputOptions& f, bool& quiet, std::string formats) {
  if (!formats.empty()) formats_ = parse_formats(formats);
  OutputOptions defaults = f;
  if (formats_) defaults.formats = *formats_;
  files_ = std::make_unique<DescribedOptions<OutputOptions>>(app, files_option_table(), defaults, nullptr);
  // Binary became the default on 2026-11-24; the old flag still runs the scripts and resumes
  // the checkpoints that name it. Not in --help.
  app.add_flag_callback("--binary", [&f] { f.ply_encoding = PlyEncoding::binary; })->group("");
  options_ = std::make_unique<DescribedOptions<OutputOptions>>(app, output_option_table(), f, nullptr);
  app.add_flag("-q,--quiet", quiet, "no progress bar and no summary")->group("Output");
  // `dla3d frames` (whose default is glb alone) draws a finished CSV: nothing attaches to stream.
  if (!formats_)
    app.add_option("--stream", "write each particle as it attaches to FILE (a pipe for a live view), binary: "
                               "docs/studio.md#the-stream")
        ->type_name("FILE")->group("Output");
}

void OutputWords::finish(OutputOptions& f) const {
  if (formats_) f.formats = *formats_;
  files_->finish(f);
  options_->finish(f);
}

std::unique_ptr<DescribedOptions<LinkOptions>> add_links_option(CLI::App& command, bool lattice) {
  return std::make_unique<DescribedOptions<LinkOptions>>(command, links_option_table(lattice), LinkOptions{}, nullptr);
}

}  // namespace dla::cli
