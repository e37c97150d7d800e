#pragma once
// Reading a glTF or GLB file and the files its URIs name, defensively: the GLB container is
// checked chunk by chunk, JSON nesting is bounded before the (recursive) parser sees it, and
// external URIs resolve inside the scene file's folder only (after percent-decoding and
// symlink resolution) unless external paths are allowed. The checked JSON is then adjusted for
// the compression extensions (prepare_for_tinygltf) and parsed from memory. Every failure names
// the file.

#include <tiny_gltf.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/checksum.h"

namespace prism {

// JSON nesting deeper than this is refused (a glTF needs about ten levels; extras may add a few).
inline constexpr int kMaxJsonDepth = 512;

// The files a scene reads: the scene file, the files its URIs name and those its extras name
// (spectrum tables). A URI resolves inside the scene file's folder only (after symlink resolution)
// unless external paths are allowed. hash() is the FNV-1a of the scene file's bytes and of each
// other file read (URI and bytes, in the order read): the scene's content wherever its folder lies.
class SceneFiles {
 public:
  SceneFiles(const std::filesystem::path& scene_file, bool allow_external_paths);

  // The bytes of the file `uri` names (relative to the scene's folder); fails naming the scene
  // file, `what` asked for it, and why it cannot be read.
  std::vector<unsigned char> read(const std::string& uri, const std::string& what);
  // The same without failing: false, with problem() set (the first problem met).
  bool read(const std::string& uri, std::vector<unsigned char>& bytes);
  // The file `uri` names under the policy, or an empty path with problem() set.
  std::filesystem::path resolve(const std::string& uri);

  void add_scene_bytes(const std::vector<unsigned char>& bytes);
  uint64_t hash() const { return content_.h; }
  const std::string& problem() const { return problem_; }
  const std::string& base() const { return base_; }  // the scene's folder, as tinygltf is given it

 private:
  std::string scene_file_;
  std::filesystem::path root_;  // the scene file's folder, symlinks resolved
  std::string base_;
  bool allow_external_;
  std::string problem_;
  Checksum content_;
};

// Parses `file` into `model` with `reader` (whose image loader the caller has set), reading its
// URIs through `files`; fails if the parser cannot build a model, logs its warnings, and returns
// the errors it found in a model it did build (the caller fails on them once it has named any
// required extension it lacks). `json`, when the file's JSON mentions "prism" (Prism's own extras),
// gets that JSON text, which tinygltf's values cannot hold whole (they drop empty arrays).
std::string read_gltf_file(tinygltf::TinyGLTF& reader, tinygltf::Model& model, const std::filesystem::path& file,
                           SceneFiles& files, std::string& json);

// The JSON text of a file's bytes: all of a .gltf, the JSON chunk of a GLB that passed the checks.
std::string_view gltf_json(const std::vector<unsigned char>& bytes, bool binary);

// The deepest nesting of [ and { in JSON text (strings skipped), counted without recursion.
int json_depth(const char* text, size_t size);

}  // namespace prism
