// Split renders: sample ranges (`--samples A:B`) and tiles (`--crop`) rendered as separate
// processes and joined by `prism merge` give the single render's image bit for bit, at any
// thread count; merge refuses parts that do not belong together or do not cover the render,
// and then writes nothing.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "core/render/image_output.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

const std::string kCornell = "\"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\"";
constexpr int kSpp = 7;

std::string render_args(int threads, uint64_t seed = 5, const std::string& integrator = "path") {
  return fmt::format("render {} --width 32 --spp {} --seed {} --threads {} --integrator {} --aov variance,albedo -q",
                     kCornell, kSpp, seed, threads, integrator);
}

// The channels of an EXR image (by default all those render_args writes), as bytes.
std::vector<char> pixels(const std::filesystem::path& exr,
                         const std::vector<const char*>& channels = {"R", "G", "B", "variance.R", "variance.Y",
                                                                     "albedo.R", "albedo.G", "albedo.B"}) {
  std::vector<char> bytes;
  for (const char* name : channels) {
    const std::vector<float> c = read_exr_channel(exr, name);
    const char* p = reinterpret_cast<const char*>(c.data());
    bytes.insert(bytes.end(), p, p + c.size() * sizeof(float));
  }
  return bytes;
}

// Renders the parts (extra arguments each) and merges them; returns the merge's exit code.
int render_and_merge(const std::filesystem::path& dir, const std::vector<std::string>& parts, int threads,
                     const std::filesystem::path& out, std::string* err = nullptr,
                     const std::string& integrator = "path") {
  std::string files;
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::filesystem::path part = dir / fmt::format("part{}.prism-part", i);
    REQUIRE(test::run_prism(render_args(threads, 5, integrator) + " " + parts[i] + " -o \"" + part.string() + "\"") ==
            0);
    files += " \"" + part.string() + "\"";
  }
  return test::run_prism("merge" + files + " -o \"" + out.string() + "\"", err);
}

// [0, kSpp) cut into n ranges of nearly equal size.
std::vector<std::string> sample_ranges(int n) {
  std::vector<std::string> parts;
  for (int i = 0; i < n; ++i) parts.push_back(fmt::format("--samples {}:{}", i * kSpp / n, (i + 1) * kSpp / n));
  return parts;
}

}  // namespace

TEST_CASE("merge: sample ranges and tiles merge bit-identical to the single render", "[cli][merge]") {
  const auto dir = test::temp_dir("merge_exact");
  for (int threads : {1, 2}) {
    const std::filesystem::path single = dir / fmt::format("single{}.exr", threads);
    REQUIRE(test::run_prism(render_args(threads) + " -o \"" + single.string() + "\"") == 0);
    const std::vector<char> expected = pixels(single);
    for (int n : {1, 2, 3, 7}) {
      INFO(n << " sample ranges, " << threads << " threads");
      const std::filesystem::path merged = dir / "merged.exr";
      REQUIRE(render_and_merge(dir, sample_ranges(n), threads, merged) == 0);
      CHECK(pixels(merged) == expected);
    }
    INFO("4 tiles, the last two split again into sample ranges, " << threads << " threads");
    const std::filesystem::path merged = dir / "tiles.exr";
    REQUIRE(render_and_merge(dir,
                             {"--crop 0,0,16,16", "--crop 16,0,32,16", "--crop 0,16,16,32 --samples 0:3",
                              "--crop 0,16,16,32 --samples 3:7", "--crop 16,16,32,32"},
                             threads, merged) == 0);
    CHECK(pixels(merged) == expected);
  }
}

TEST_CASE("merge: a VCM render's sample ranges merge bit-identical to the single render; auto refuses its tiles",
          "[cli][merge]") {
  // The default scene's caustics make --integrator auto choose vcm, whose light paths splat over the
  // whole frame: its parts are sample ranges, never tiles.
  const auto dir = test::temp_dir("merge_vcm");
  const std::filesystem::path single = dir / "single.exr";
  REQUIRE(test::run_prism(render_args(2, 5, "auto") + " -o \"" + single.string() + "\"") == 0);
  REQUIRE(test::run_prism(render_args(2, 5, "vcm") + " -o \"" + (dir / "vcm.exr").string() + "\"") == 0);
  CHECK(pixels(dir / "vcm.exr") == pixels(single));
  const std::vector<char> expected = pixels(single);
  for (int n : {2, 3}) {
    INFO(n << " sample ranges");
    const std::filesystem::path merged = dir / "merged.exr";
    REQUIRE(render_and_merge(dir, sample_ranges(n), 2, merged, nullptr, "auto") == 0);
    CHECK(pixels(merged) == expected);
  }
  std::string err;
  CHECK(test::run_prism(render_args(2, 5, "auto") + " --crop 0,0,16,16 -o \"" + (dir / "tile").string() + "\"", &err) ==
        1);
  CHECK(err.find("render tiles with --integrator path") != std::string::npos);
  CHECK(!std::filesystem::exists(dir / "tile"));
}

TEST_CASE("merge: refuses parts that do not make the render, and writes nothing", "[cli][merge]") {
  const auto dir = test::temp_dir("merge_refuse");
  const auto part = [&](const std::string& name, const std::string& args) {
    const std::filesystem::path file = dir / name;
    REQUIRE(test::run_prism(args + " -o \"" + file.string() + "\"") == 0);
    return " \"" + file.string() + "\"";
  };
  const std::string a = part("a", render_args(2) + " --samples 0:3"), b = part("b", render_args(2) + " --samples 3:7"),
                    overlap = part("overlap", render_args(2) + " --samples 2:5"),
                    seed = part("seed", render_args(2, 6) + " --samples 3:7"),
                    scene = part("scene", fmt::format("render \"{}/data/scenes/dispersion.gltf\" --width 32 "
                                                      "--spp {} --seed 5 --aov variance,albedo -q --samples 3:7",
                                                      PRISM_SOURCE_DIR, kSpp));
  const std::filesystem::path corrupt = dir / "corrupt";
  std::filesystem::copy_file(dir / "b", corrupt);
  {
    std::fstream f(corrupt, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(std::filesystem::file_size(corrupt) / 2));
    f.put('\x5a');
  }
  const std::filesystem::path out = dir / "out.exr";
  const auto refuses = [&](const std::string& files, const std::string& message) {
    std::string err;
    CHECK(test::run_prism("merge" + files + " -o \"" + out.string() + "\"", &err) == 1);
    CHECK_THAT(err, Catch::Contains(message));
    CHECK_FALSE(std::filesystem::exists(out));
  };
  refuses(a, "samples 3:7 of window 0,0,32,32 are missing");
  refuses(a + b + overlap, "overlap");
  refuses(a + seed, "seed=6 vs seed=5");
  refuses(a + scene, "another scene or other options");
  refuses(a + " \"" + corrupt.string() + "\"", "damaged");
  CHECK(test::run_prism("merge" + a + b + " -o \"" + out.string() + "\"") == 0);
}

TEST_CASE("merge: a tile's part file holds the sums of its window only", "[cli][merge]") {
  const auto dir = test::temp_dir("merge_tile_size");
  const std::filesystem::path frame = dir / "frame.prism-part", tile = dir / "tile.prism-part";
  REQUIRE(test::run_prism(render_args(2) + " --samples 0:1 -o \"" + frame.string() + "\"") == 0);
  REQUIRE(test::run_prism(render_args(2) + " --samples 0:1 --crop 8,8,16,16 -o \"" + tile.string() + "\"") == 0);
  // 64 of the frame's 1024 pixels; the header is small beside either.
  CHECK(std::filesystem::file_size(tile) * 12 < std::filesystem::file_size(frame));
}

namespace {

// `prism farm slurm --dry-run` run without Slurm: its scripts, printed as
// "# DIR/parts.sbatch\n<script>\n# DIR/merge.sbatch (...)\n<script>", written to DIR.
struct FarmScripts {
  std::filesystem::path parts, merge;
};
FarmScripts dry_run_scripts(const std::string& farm, const std::filesystem::path& dir) {
  std::string out;
  REQUIRE(test::run_prism(farm + " --dry-run", nullptr, &out) == 0);
  const size_t merge_at = out.find("# " + dir.string() + "/merge.sbatch");
  REQUIRE(merge_at != std::string::npos);
  const auto write = [&](const char* name, size_t from, size_t to) {
    const size_t begin = out.find('\n', from) + 1;
    std::ofstream(dir / name) << out.substr(begin, to - begin);
    return dir / name;
  };
  std::filesystem::create_directories(dir);
  return {merge_at == 0 ? std::filesystem::path() : write("parts.sbatch", 0, merge_at),
          write("merge.sbatch", merge_at, out.size())};
}

}  // namespace

TEST_CASE("merge: an animation's frames split into parts by the farm's scripts give `prism render --frames`",
          "[cli][merge]") {
  const auto dir = test::temp_dir("merge_frames");
  const std::string scene = test::write_animated_triangle(dir).string();
  // The morph-target triangle turning about +y (animation "linear"): frames 0 and 1 at 2 fps.
  const std::string options = "--width 16 --height 16 --env 1,1,1 --animation linear --seed 3";
  const std::string animation = "--frames 0:1 --fps 2 --spp 7";
  for (int threads : {1, 2}) {
    INFO(threads << " threads");
    const std::filesystem::path farm_dir = dir / fmt::format("farm{}", threads);
    const std::string farm = fmt::format("farm slurm \"{}\" {} --parts 3 {} --threads {} --out \"{}\"", scene,
                                         animation, options, threads, farm_dir.string());
    const FarmScripts scripts = dry_run_scripts(farm, farm_dir);
    REQUIRE(!scripts.parts.empty());
    for (int task = 0; task < 6; ++task)
      REQUIRE(std::system(fmt::format("SLURM_ARRAY_TASK_ID={} sh \"{}\"", task, scripts.parts.string()).c_str()) == 0);
    for (const char* part : {"frame-0000.part-0", "frame-0000.part-2", "frame-0001.part-0", "frame-0001.part-2"})
      CHECK(std::filesystem::exists(farm_dir / (part + std::string(".prism-part"))));
    REQUIRE(std::system(fmt::format("sh \"{}\" >/dev/null", scripts.merge.string()).c_str()) == 0);

    const std::string single = (dir / fmt::format("single{}.####.exr", threads)).string();
    REQUIRE(test::run_prism(fmt::format("render \"{}\" {} {} --threads {} -q -o \"{}\"", scene, animation, options,
                                        threads, single)) == 0);
    for (const char* frame : {"0000", "0001"}) {
      INFO("frame " << frame);
      CHECK(pixels(farm_dir / fmt::format("image.{}.exr", frame), {"R", "G", "B"}) ==
            pixels(dir / fmt::format("single{}.{}.exr", threads, frame), {"R", "G", "B"}));
    }
    CHECK(pixels(farm_dir / "image.0000.exr", {"R", "G", "B"}) != pixels(farm_dir / "image.0001.exr", {"R", "G", "B"}));

    INFO("resubmission renders only the missing parts");
    std::filesystem::remove(farm_dir / "frame-0001.part-1.prism-part");
    std::string out;
    REQUIRE(test::run_prism(farm + " --dry-run", nullptr, &out) == 0);
    CHECK_THAT(out, Catch::Contains("#SBATCH --array=4\n"));
  }
  std::string scripts;
  REQUIRE(test::run_prism(
              fmt::format("farm slurm \"{}\" {} --out \"{}\" --dry-run", scene, animation, (dir / "default").string()),
              nullptr, &scripts) == 0);
  CHECK_THAT(scripts, Catch::Contains("#SBATCH --array=0-1\n"));  // one part per frame by default

  INFO("parts of different frames do not merge");
  const auto part = [&](const char* frame, int part) {
    return fmt::format(" \"{}\"", (dir / fmt::format("farm1/frame-{}.part-{}.prism-part", frame, part)).string());
  };
  std::string err;
  const std::filesystem::path out = dir / "mixed.exr";
  CHECK(test::run_prism("merge" + part("0000", 0) + part("0001", 0) + part("0000", 2) + " -o \"" + out.string() + "\"",
                        &err) == 1);
  CHECK_THAT(err, Catch::Contains("frame-0001.part-0.prism-part: a part of the frame at 0.5 s") &&
                      Catch::Contains("parts of different frames never merge"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("merge: parts name the scene and the environment map by file name and content, not by path", "[cli][merge]") {
  const auto dir = test::temp_dir("merge_relocated");
  // tri.gltf with its vertices in tri.bin and a sky.exr, in five folders: b a copy of a, c with
  // one vertex moved; d a's scene with a brighter sky, e a's with the sky under another name.
  const auto write_sky = [&](const char* folder, const char* name, float value) {
    write_exr(dir / folder / name,
              {4,
               2,
               std::vector<float>(4 * 2 * 3, value),
               ColorPipeline::standard().chromaticities(ColorPipeline::kDefaultOutput),
               {}},
              false);
  };
  const auto write = [&](const char* folder, float top, float sky = 0.5f, const char* sky_name = "sky.exr") {
    std::filesystem::create_directories(dir / folder);
    std::ofstream(dir / folder / "tri.gltf") << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 2, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"uri": "tri.bin", "byteLength": 36}]})";
    const float vertices[9] = {0, 0, 0, 1, 0, 0, 0, top, 0};
    std::ofstream(dir / folder / "tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(vertices), sizeof(vertices));
    write_sky(folder, sky_name, sky);
  };
  write("a", 1), write("b", 1), write("c", 2), write("d", 1, 0.6f), write("e", 1, 0.5f, "sky2.exr");
  const auto part = [&](const char* folder, const char* samples, const char* sky_name = "sky.exr") {
    const std::filesystem::path file = dir / fmt::format("{}{}.prism-part", folder, samples[0]);
    REQUIRE(test::run_prism(fmt::format("render \"{}\" --width 16 --height 16 --env-map \"{}\" --spp 7 --samples {} "
                                        "-q -o \"{}\"",
                                        (dir / folder / "tri.gltf").string(), (dir / folder / sky_name).string(),
                                        samples, file.string())) == 0);
    return " \"" + file.string() + "\"";
  };
  const std::filesystem::path out = dir / "out.exr";
  CHECK(test::run_prism("merge" + part("a", "0:3") + part("b", "3:7") + " -o \"" + out.string() + "\"") == 0);
  std::string err;
  CHECK(test::run_prism("merge" + part("a", "0:3") + part("c", "3:7") + " -o \"" + out.string() + "\"", &err) == 1);
  CHECK_THAT(err, Catch::Contains("another scene or other options") && Catch::Contains("scene-hash="));
  CHECK(test::run_prism("merge" + part("a", "0:3") + part("d", "3:7") + " -o \"" + out.string() + "\"", &err) == 1);
  CHECK_THAT(err, Catch::Contains("env-map-hash="));
  CHECK(test::run_prism("merge" + part("a", "0:3") + part("e", "3:7", "sky2.exr") + " -o \"" + out.string() + "\"",
                        &err) == 1);
  CHECK_THAT(err, Catch::Contains("env-map=sky2.exr"));
}
