// `prism farm slurm SCENE [--frames A:B] --parts N [render options] --out DIR`: splits a render
// into N sample ranges (per frame, for an animation), writes a Slurm array job with one task per
// part (frame, sample range), each writing one part file, and a merge job that runs after all of
// them succeed (--dependency=afterok) and merges each frame's parts into its image, and submits
// both with sbatch, printing their job ids. DIR must be on a filesystem every node sees (as Slurm
// sites have); the scene path and this executable are used by absolute path. Submitting again
// renders only the parts whose files are missing (and cancels the previous merge job, whose
// dependency a failed part left unmet). --dry-run prints the scripts instead.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "apps/prism/commands.h"
#include "apps/prism/frame_sequence.h"
#include "core/base/error.h"

namespace prism {

namespace {

struct FarmArgs {
  std::string scene, out, frames;
  int parts = 4, spp = 16;
  double fps = 24;
  bool dry_run = false;
  std::vector<std::string> render_options;
};

// Slurm's largest MaxArraySize: task ids must stay below it (sites often keep the default, 1001).
constexpr int64_t kMaxArraySize = 4000001;

// The parts of the render: array task T renders frame first + T / parts, sample range T % parts.
// A still is one frame without --frames.
struct Plan {
  std::filesystem::path dir;
  std::optional<FrameRange> frames;
  int parts, spp;

  int frame_count() const { return frames ? frames->last - frames->first + 1 : 1; }
  int tasks() const { return frame_count() * parts; }
  int frame(int task) const { return frames->first + task / parts; }
  // Part I of frame F: DIR/part-I.prism-part, or DIR/frame-FFFF.part-I.prism-part (a frame_path
  // pattern): the prefix before I.
  std::string part_prefix() const { return (dir / (frames ? "frame-####.part-" : "part-")).string(); }
  std::string part_pattern(const std::string& part) const { return part_prefix() + part + ".prism-part"; }
  std::filesystem::path part_file(int task) const {
    const std::string pattern = part_pattern(std::to_string(task % parts));
    return frames ? frame_path(pattern, frame(task)) : pattern;
  }
  // The merged image of frame index i: DIR/image.exr, or DIR/image.FFFF.exr.
  std::filesystem::path image(int i) const {
    return frames ? frame_path((dir / "image.####.exr").string(), frames->first + i) : (dir / "image.exr").string();
  }
};

// `s` quoted for the POSIX shell.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Task ids as a Slurm array: runs joined by '-', runs separated by ',' (0-3,5,7-9).
std::string array_spec(const std::vector<int>& ids) {
  std::string spec;
  for (size_t i = 0; i < ids.size();) {
    size_t j = i;
    while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
    spec += (spec.empty() ? "" : ",") + std::to_string(ids[i]) + (j > i ? "-" + std::to_string(ids[j]) : "");
    i = j + 1;
  }
  return spec;
}

std::string parts_script(const Plan& plan, const std::string& array, const std::string& render) {
  const int n = plan.parts, spp = plan.spp;
  const std::string dir = quoted(plan.dir.string());
  const std::string header = fmt::format(
      "#!/bin/sh\n"
      "#SBATCH --job-name=prism-parts\n"
      "#SBATCH --array={}\n"
      "#SBATCH --requeue\n"
      "#SBATCH --output={}/logs/part-%a.log\n",
      array, dir);
  const std::string range = fmt::format("--samples \"$((part * {1} / {0})):$(((part + 1) * {1} / {0}))\"", n, spp);
  const std::string output = quoted(plan.part_prefix()) + "\"$part\".prism-part";
  if (!plan.frames)
    return header + fmt::format(
                        "# Task P renders samples [P*{1}/{0}, (P+1)*{1}/{0}) of every pixel into {2}.\n"
                        "part=$SLURM_ARRAY_TASK_ID\n"
                        "exec {3} {4} -q -o {5}\n",
                        n, spp, plan.part_pattern("P"), render, range, output);
  return header + fmt::format(
                      "# Task T renders frame F = {2} + T / {0}, samples [P*{1}/{0}, (P+1)*{1}/{0}) of every pixel "
                      "with P = T % {0},\n# into {3}.\n"
                      "frame=$(({2} + SLURM_ARRAY_TASK_ID / {0})) part=$((SLURM_ARRAY_TASK_ID % {0}))\n"
                      "exec {4} --frames \"$frame:$frame\" {5} -q -o {6}\n",
                      n, spp, plan.frames->first, plan.part_pattern("P"), render, range, output);
}

// One `prism merge` per frame, in frame order; the job fails at the first frame that fails.
std::string merge_script(const Plan& plan, const std::string& prism) {
  std::string merges;
  for (int i = 0; i < plan.frame_count(); ++i) {
    merges += fmt::format("{} merge", quoted(prism));
    for (int p = 0; p < plan.parts; ++p)
      merges += fmt::format(" {}", quoted(plan.part_file(i * plan.parts + p).string()));
    merges += fmt::format(" -o {}\n", quoted(plan.image(i).string()));
  }
  return fmt::format(
      "#!/bin/sh\n"
      "#SBATCH --job-name=prism-merge\n"
      "#SBATCH --requeue\n"
      "#SBATCH --output={}/logs/merge.log\n"
      "set -e\n{}",
      quoted(plan.dir.string()), merges);
}

// Runs sbatch on `script` and returns the job id it prints (--parsable).
std::string submit(const std::filesystem::path& script, const std::string& extra) {
  const std::string command = "sbatch --parsable " + extra + " " + quoted(script.string());
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) fail("cannot run sbatch");
  char line[256] = {};
  const bool read = std::fgets(line, sizeof(line), pipe.get()) != nullptr;
  const int status = pclose(pipe.release());
  std::string id(line);
  id = id.substr(0, id.find_first_of(";\n"));
  if (!read || status != 0 || id.empty()) fail("`{}` failed (is Slurm installed and running here?)", command);
  return id;
}

void run(const FarmArgs& args) {
  Plan plan{std::filesystem::absolute(args.out), std::nullopt, args.parts, args.spp};
  if (args.parts > args.spp) fail("--parts {} is more than --spp {}: every part needs a sample", args.parts, args.spp);
  if (!args.frames.empty()) {
    plan.frames = parse_frames(args.frames);
    if (!(args.fps > 0 && std::isfinite(args.fps))) fail("--fps {}: must be a positive number", args.fps);
  }
  if (int64_t(plan.frame_count()) * args.parts >= kMaxArraySize)
    fail("{} frames of {} parts are more array tasks than Slurm allows ({}); farm fewer frames at a time",
         plan.frame_count(), args.parts, kMaxArraySize - 1);
  const std::filesystem::path scene = std::filesystem::absolute(args.scene);
  if (!std::filesystem::exists(scene)) fail("{}: no such scene file", scene.string());
  const std::string prism = std::filesystem::read_symlink("/proc/self/exe").string();
  std::string render = fmt::format("{} render {} --spp {}", quoted(prism), quoted(scene.string()), args.spp);
  if (plan.frames) render += fmt::format(" --fps {}", args.fps);
  for (const std::string& o : args.render_options) render += " " + quoted(o);

  std::vector<int> missing;
  for (int t = 0; t < plan.tasks(); ++t)
    if (!std::filesystem::exists(plan.part_file(t))) missing.push_back(t);
  const std::string array = array_spec(missing);
  const std::string parts = parts_script(plan, array, render), merge = merge_script(plan, prism);
  const std::filesystem::path& dir = plan.dir;
  if (args.dry_run) {
    if (!missing.empty()) std::printf("# %s/parts.sbatch\n%s\n", dir.c_str(), parts.c_str());
    std::printf("# %s/merge.sbatch (--dependency=afterok:<parts job>)\n%s", dir.c_str(), merge.c_str());
    return;
  }
  std::filesystem::create_directories(dir / "logs");
  const auto write = [&](const char* name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  std::string dependency;
  if (!missing.empty()) {
    const std::string id = submit(write("parts.sbatch", parts), "");
    std::printf("submitted parts job %s (array tasks %s of %d)\n", id.c_str(), array.c_str(), plan.tasks());
    dependency = "--dependency=afterok:" + id;
  } else {
    std::printf("all %d part files exist: submitting only the merge\n", plan.tasks());
  }
  // A merge job left from an earlier submission whose parts failed waits for a dependency that
  // can never be met: the new merge job replaces it.
  if (std::ifstream previous(dir / "merge.jobid"); previous) {
    std::string id;
    if (previous >> id && id.find_first_not_of("0123456789") == std::string::npos)
      if (std::system(("scancel " + id + " 2>/dev/null").c_str()) == 0)
        std::printf("cancelled the earlier merge job %s\n", id.c_str());
  }
  const std::string merge_id = submit(write("merge.sbatch", merge), dependency);
  write("merge.jobid", merge_id + "\n");
  std::printf("submitted merge job %s: writes %s\n", merge_id.c_str(),
              plan.frames ? (dir / "image.####.exr").c_str() : plan.image(0).c_str());
}

}  // namespace

void add_farm_command(CLI::App& app) {
  auto args = std::make_shared<FarmArgs>();
  CLI::App* farm = app.add_subcommand("farm", "Send a render to a cluster scheduler");
  farm->require_subcommand(1);
  CLI::App* cmd = farm->add_subcommand(
      "slurm",
      "Render SCENE (or its animation's --frames) as a Slurm array job of --parts sample ranges per frame plus a "
      "merge job (README: prism farm slurm)");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene (.gltf or .glb), on the shared filesystem")->required();
  cmd->add_option("--parts", args->parts,
                  "Sample ranges per frame, one array task each (default 4; with --frames 1: a task per frame)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--spp", args->spp, "Samples per pixel of the whole render")
      ->default_val(16)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--frames", args->frames,
                  "Render the animation's frames A to B (A:B), each split into --parts, to DIR/image.####.exr");
  cmd->add_option("--fps", args->fps, "Frames per second of --frames: frame N is at N / fps seconds")->default_val(24);
  cmd->add_option("--out", args->out,
                  "Directory on the shared filesystem for parts, logs and image.exr (image.####.exr with --frames)")
      ->required();
  cmd->add_flag("--dry-run", args->dry_run, "Print the batch scripts instead of submitting them");
  cmd->allow_extras();
  cmd->callback([args, cmd] {
    args->render_options = cmd->remaining();
    if (cmd->count("--parts") == 0) args->parts = args->frames.empty() ? 4 : 1;
    run(*args);
  });
}

}  // namespace prism
