// Hostile input: every case of tests/hostile/make_cases.py through `prism render`. Each ends in
// its expected class: refused (exit 1, one line naming the file and the problem), a usage error
// (exit 2), or rendered (exit 0, only finite pixels); never a crash or a hang, and nothing left
// in the output folder but the image of a successful render.

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/render/image_output.h"
#include "tests/support/test_scenes.h"

using namespace prism;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string shell_quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string replace_all(const std::string& s, const std::string& from, const std::string& to) {
  std::string out;
  size_t at = 0;
  for (size_t hit; (hit = s.find(from, at)) != std::string::npos; at = hit + from.size())
    out += s.substr(at, hit - at) + to;
  return out + s.substr(at);
}

}  // namespace

TEST_CASE("hostile input: every generated case is refused cleanly or rendered cleanly") {
  const fs::path dir = test::temp_dir("hostile");
  const std::string generate = "python3 " + shell_quoted(PRISM_SOURCE_DIR "/tests/hostile/make_cases.py") + " " +
                               shell_quoted(dir.string()) + " >/dev/null";
  REQUIRE(std::system(generate.c_str()) == 0);
  const auto manifest = nlohmann::json::parse(slurp(dir / "manifest.json"));
  REQUIRE(manifest.size() > 150);

  int refused = 0, rendered = 0, crashed = 0, hung = 0;
  for (const auto& c : manifest) {
    const std::string name = c["name"], expect = c["expect"];
    const fs::path case_dir = dir / name, out_dir = case_dir / "out";
    const std::string scene = (case_dir / c["scene"].get<std::string>()).string();
    std::string command = "cd " + shell_quoted(dir.string()) + " && timeout 120 " + shell_quoted(PRISM_EXECUTABLE);
    for (std::string arg : c["args"]) {
      arg = replace_all(arg, "{scene}", scene);
      arg = replace_all(arg, "{out}", (out_dir / "out.exr").string());
      arg = replace_all(arg, "{dir}", case_dir.string());
      command.append(" ").append(shell_quoted(arg));
    }
    command.append(" >").append(shell_quoted((case_dir / "stdout.txt").string()));
    command.append(" 2>").append(shell_quoted((case_dir / "stderr.txt").string()));
    const int status = std::system(command.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    const std::string err = slurp(case_dir / "stderr.txt");
    INFO("case " << name << " (expected " << expect << "): exit " << code << "\n" << err);
    CHECK(code != -1);
    CHECK(code != 124);  // timeout(1): hung
    crashed += code == -1 || code > 2 && code != 124;
    hung += code == 124;

    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(out_dir)) left.push_back(entry.path().filename().string());
    if (expect == "rendered") {
      CHECK(code == 0);
      if (code != 0) continue;
      ++rendered;
      CHECK(left == std::vector<std::string>{"out.exr"});
      const RgbImage image = read_exr(out_dir / "out.exr");
      CHECK(image.rgb.size() > 0);
      CHECK(std::all_of(image.rgb.begin(), image.rgb.end(), [](float v) { return std::isfinite(v); }));
    } else {
      CHECK(code == (expect == "usage" ? 2 : 1));
      CHECK(left.empty());
      for (const std::string mention : c["mention"]) CHECK(err.find(mention) != std::string::npos);
      if (expect != "refused") continue;
      refused += code == 1;
      // One line, naming the file it is about and what is wrong.
      const std::string line =
          err.substr(err.rfind("prism: error: ") == std::string::npos ? 0 : err.rfind("prism: error: "));
      CHECK(line.rfind("prism: error: ", 0) == 0);
      CHECK(std::count(line.begin(), line.end(), '\n') == 1);
      CHECK(line.find("internal error") == std::string::npos);
      const bool names_a_file = line.find('/') != std::string::npos || line.find("--") != std::string::npos;
      CHECK(names_a_file);
    }
  }
  WARN(manifest.size() << " cases: " << refused << " refused cleanly, " << rendered << " rendered cleanly, " << crashed
                       << " crashed, " << hung << " hung");
  CHECK(crashed == 0);
  CHECK(hung == 0);
}
