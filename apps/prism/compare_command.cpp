// `prism compare A.exr B.exr [--independent]`: how far image A is from image B (the reference),
// over all pixels and RGB channels: the RMSE and the RMSE relative to B's mean, in linear values
// and as a display shows them (clipped to [0, 1], sRGB-encoded). With --independent, A and B are
// two renders of the same scene and settings with different seeds, and what is printed is the
// error of either one: the difference of two independent estimates has twice the variance of
// each, so each one's error is the difference's RMSE / √2.

#include <cmath>
#include <cstdio>

#include "apps/prism/commands.h"
#include "apps/prism/image_errors.h"
#include "core/base/error.h"
#include "core/render/image_output.h"

namespace prism {

namespace {

struct CompareArgs {
  std::string image, reference;
  bool independent = false;
};

void run(const CompareArgs& args) {
  const RgbImage a = read_exr(args.image), b = read_exr(args.reference);
  if (a.width != b.width || a.height != b.height)
    fail("{} is {}x{}, {} is {}x{}: only images of one size compare", args.image, a.width, a.height, args.reference,
         b.width, b.height);
  const double scale = args.independent ? 1 / std::sqrt(2.0) : 1.0;
  const ImageErrors linear = image_errors(a.rgb, b.rgb);
  const ImageErrors display = image_errors(display_encoded(a.rgb), display_encoded(b.rgb));
  const auto relative = [](double rmse, double mean) { return mean > 0 ? rmse / mean : INFINITY; };
  std::printf("%s: %s\n", args.independent ? "the error of either image" : "the image against the reference",
              args.independent ? "two renders with different seeds" : args.reference.c_str());
  std::printf(
      "rmse=%.6g relative_rmse=%.6g display_rmse=%.6g display_relative_rmse=%.6g mean=%.6g reference_mean=%.6g\n",
      scale * linear.rmse, scale * relative(linear.rmse, linear.reference_mean), scale * display.rmse,
      scale * relative(display.rmse, display.reference_mean), linear.reference_mean + linear.mean_error,
      linear.reference_mean);
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "How far an OpenEXR image is from a reference (RMSE, relative RMSE, linear and as displayed)");
  cmd->add_option("image", args->image, "The image (OpenEXR, RGB)")->required();
  cmd->add_option("reference", args->reference, "The reference (OpenEXR, RGB, the same size)")->required();
  cmd->add_flag("--independent", args->independent,
                "The two are renders of the same scene and settings with different seeds: print either one's "
                "error (the difference's RMSE / sqrt 2)");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
