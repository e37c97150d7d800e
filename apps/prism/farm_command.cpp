// `prism farm slurm SCENE --parts N [render options] --out DIR`: splits a render into N sample
// ranges, writes a Slurm array job that renders them (one part file each, DIR/part-I.prism-part)
// and a merge job that runs after all of them succeed (--dependency=afterok), and submits both
// with sbatch, printing their job ids. DIR must be on a filesystem every node sees (as Slurm
// sites have); the scene path and this executable are used by absolute path. Submitting again
// renders only the parts whose files are missing (and cancels the previous merge job, whose
// dependency a failed part left unmet). --dry-run prints the scripts instead.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "apps/prism/commands.h"
#include "base/error.h"

namespace prism {

namespace {

struct FarmArgs {
  std::string scene, out;
  int parts = 4, spp = 16;
  bool dry_run = false;
  std::vector<std::string> render_options;
};

// `s` quoted for the POSIX shell.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::filesystem::path part_file(const std::filesystem::path& dir, int i) {
  return dir / fmt::format("part-{}.prism-part", i);
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
  if (args.parts > args.spp) fail("--parts {} is more than --spp {}: every part needs a sample", args.parts, args.spp);
  const std::filesystem::path dir = std::filesystem::absolute(args.out);
  const std::filesystem::path scene = std::filesystem::absolute(args.scene);
  if (!std::filesystem::exists(scene)) fail("{}: no such scene file", scene.string());
  const std::string prism = std::filesystem::read_symlink("/proc/self/exe").string();
  std::string options;
  for (const std::string& o : args.render_options) options += " " + quoted(o);

  std::vector<int> missing;
  for (int i = 0; i < args.parts; ++i)
    if (!std::filesystem::exists(part_file(dir, i))) missing.push_back(i);
  std::string array, cases;
  for (int i : missing) array += (array.empty() ? "" : ",") + std::to_string(i);
  for (int i = 0; i < args.parts; ++i)
    cases += fmt::format("  {}) range={}:{} ;;\n", i, int64_t(i) * args.spp / args.parts,
                         int64_t(i + 1) * args.spp / args.parts);
  const std::string parts_script = fmt::format(
      "#!/bin/sh\n"
      "#SBATCH --job-name=prism-parts\n"
      "#SBATCH --array={}\n"
      "#SBATCH --requeue\n"
      "#SBATCH --output={}/logs/part-%a.log\n"
      "# Part I renders samples [I*spp/N, (I+1)*spp/N) of every pixel into {}/part-I.prism-part.\n"
      "case \"$SLURM_ARRAY_TASK_ID\" in\n{}esac\n"
      "exec {} render {} --spp {}{} --samples \"$range\" -q -o {}/part-\"$SLURM_ARRAY_TASK_ID\".prism-part\n",
      array, quoted(dir.string()), dir.string(), cases, quoted(prism), quoted(scene.string()), args.spp, options,
      quoted(dir.string()));
  std::string files;
  for (int i = 0; i < args.parts; ++i) files += " " + quoted(part_file(dir, i).string());
  const std::string merge_script = fmt::format(
      "#!/bin/sh\n"
      "#SBATCH --job-name=prism-merge\n"
      "#SBATCH --requeue\n"
      "#SBATCH --output={}/logs/merge.log\n"
      "exec {} merge{} -o {}\n",
      quoted(dir.string()), quoted(prism), files, quoted((dir / "image.exr").string()));
  if (args.dry_run) {
    if (!missing.empty()) std::printf("# %s/parts.sbatch\n%s\n", dir.c_str(), parts_script.c_str());
    std::printf("# %s/merge.sbatch (--dependency=afterok:<parts job>)\n%s", dir.c_str(), merge_script.c_str());
    return;
  }
  std::filesystem::create_directories(dir / "logs");
  const auto write = [&](const char* name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  std::string dependency;
  if (!missing.empty()) {
    const std::string id = submit(write("parts.sbatch", parts_script), "");
    std::printf("submitted parts job %s (array tasks %s of %d)\n", id.c_str(), array.c_str(), args.parts);
    dependency = "--dependency=afterok:" + id;
  } else {
    std::printf("all %d part files exist: submitting only the merge\n", args.parts);
  }
  // A merge job left from an earlier submission whose parts failed waits for a dependency that
  // can never be met: the new merge job replaces it.
  if (std::ifstream previous(dir / "merge.jobid"); previous) {
    std::string id;
    if (previous >> id && id.find_first_not_of("0123456789") == std::string::npos)
      if (std::system(("scancel " + id + " 2>/dev/null").c_str()) == 0)
        std::printf("cancelled the earlier merge job %s\n", id.c_str());
  }
  const std::string merge_id = submit(write("merge.sbatch", merge_script), dependency);
  write("merge.jobid", merge_id + "\n");
  std::printf("submitted merge job %s: writes %s\n", merge_id.c_str(), (dir / "image.exr").c_str());
}

}  // namespace

void add_farm_command(CLI::App& app) {
  auto args = std::make_shared<FarmArgs>();
  CLI::App* farm = app.add_subcommand("farm", "Send a render to a cluster scheduler");
  farm->require_subcommand(1);
  CLI::App* cmd = farm->add_subcommand(
      "slurm", "Render SCENE as a Slurm array job of --parts sample ranges plus a merge job (README: Slurm)");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene (.gltf or .glb), on the shared filesystem")->required();
  cmd->add_option("--parts", args->parts, "Array tasks: sample ranges of the render")
      ->default_val(4)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--spp", args->spp, "Samples per pixel of the whole render")
      ->default_val(16)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", args->out, "Directory on the shared filesystem for parts, logs and image.exr")->required();
  cmd->add_flag("--dry-run", args->dry_run, "Print the batch scripts instead of submitting them");
  cmd->allow_extras();
  cmd->callback([args, cmd] {
    args->render_options = cmd->remaining();
    run(*args);
  });
}

}  // namespace prism
