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

namespace prism {

// JSON nesting deeper than this is refused (a glTF needs about ten levels; extras may add a few).
inline constexpr int kMaxJsonDepth = 512;

// Parses `file` into `model` with `reader` (whose image loader the caller has set); fails if the
// parser cannot build a model, logs its warnings, and returns the errors it found in a model it
// did build (the caller fails on them once it has named any required extension it lacks).
// `content_hash` gets the FNV-1a of the file's bytes and of each file its URIs name (URI and
// bytes, in the order read): the scene's content wherever its folder lies.
std::string read_gltf_file(tinygltf::TinyGLTF& reader, tinygltf::Model& model, const std::filesystem::path& file,
                           bool allow_external_paths, uint64_t& content_hash);

// The JSON text of a file's bytes: all of a .gltf, the JSON chunk of a GLB that passed the checks.
std::string_view gltf_json(const std::vector<unsigned char>& bytes, bool binary);

// The deepest nesting of [ and { in JSON text (strings skipped), counted without recursion.
int json_depth(const char* text, size_t size);

}  // namespace prism
