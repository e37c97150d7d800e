// `prism merge PARTS... -o OUT.exr`: joins the part files of a split render (`prism render
// --samples A:B`, `--crop`) into the image the single render would have written, bit for bit,
// after checking the parts belong together and cover the render exactly once (render/merge.h).

#include <cstdio>

#include "apps/prism/commands.h"
#include "apps/prism/film_image.h"
#include "core/base/error.h"
#include "core/render/error_estimate.h"
#include "core/render/merge.h"

namespace prism {

namespace {

struct MergeArgs {
  std::vector<std::string> parts;
  std::string output, colorspace = ColorPipeline::kDefaultOutput, white_balance = "none";
  bool half = false;
};

void run(const MergeArgs& args) {
  const std::string colorspace = ColorPipeline::standard().canonical_name(args.colorspace);
  const std::optional<WhiteBalance> balance = white_balance_option(args.white_balance);
  const RenderState merged = merge_parts({args.parts.begin(), args.parts.end()});
  ExrImage image = film_image(merged.film, colorspace, balance ? &*balance : nullptr);
  const ErrorEstimate error(merged.film, output_channels(colorspace, balance ? &*balance : nullptr));
  image.metadata = {
      {"software", std::string("Prism " PRISM_VERSION)},
      {"prism.spp", merged.part.total},
      {"prism.mergedParts", int(args.parts.size())},
      {"prism.renderOptions", merged.fingerprint},
      {"prism.seconds", merged.stats.seconds},
      {"prism.invalidSamples", std::to_string(merged.stats.invalid_samples)},
      {"prism.colorSpace", colorspace},
      {"prism.estimatedRelRmse", error.rel_rmse()},
      {"prism.estimatedRelRmseRGB", error.output_rel_rmse()},
  };
  if (balance) image.metadata.push_back({"prism.whiteBalance", balance->name});
  write_exr(args.output, image, args.half);
  std::printf("wrote %s (%dx%d, %d spp from %zu parts, %s)\n", args.output.c_str(), merged.film.width(),
              merged.film.height(), merged.part.total, args.parts.size(), colorspace.c_str());
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Merge the part files of a split render into the OpenEXR image the single render makes");
  cmd->add_option("parts", args->parts, "Part files written by `prism render --samples/--crop`")->required();
  cmd->add_option("-o,--output", args->output, "Output OpenEXR file")->required();
  cmd->add_option("--colorspace", args->colorspace, "Output colour space from data/ocio/config.ocio")
      ->default_val(ColorPipeline::kDefaultOutput);
  cmd->add_flag("--half", args->half, "Write 16-bit half floats instead of 32-bit floats (beauty only)");
  cmd->add_option("--white-balance", args->white_balance,
                  "Adapt the image so that this illuminant's white is neutral (as prism render)")
      ->default_val("none");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
