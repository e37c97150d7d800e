#include "core/scene/gltf_file.h"

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/base/checksum.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/scene/gltf_compression.h"
#include "core/scene/gltf_import.h"

namespace prism {

namespace fs = std::filesystem;

namespace {

bool inside(const fs::path& root, const fs::path& p) {
  return std::mismatch(root.begin(), root.end(), p.begin(), p.end()).first == root.end();
}

// tinygltf asks for "<base>/<decoded URI>", then for "./<decoded URI>" (the current folder, never
// allowed here): the URI, or nothing for the latter.
std::optional<std::string> uri_of(const SceneFiles& files, const std::string& joined) {
  const std::string& base = files.base();
  if (joined.size() <= base.size() || joined.compare(0, base.size(), base) != 0 || joined[base.size()] != '/')
    return std::nullopt;
  return joined.substr(base.size() + 1);
}

bool file_exists(const std::string& path, void* user) {
  auto& files = *static_cast<SceneFiles*>(user);
  const auto uri = uri_of(files, path);
  return uri && !files.resolve(*uri).empty();
}

std::string expand_path(const std::string& path, void*) { return path; }

bool read_bytes(const fs::path& file, std::vector<unsigned char>& out, std::string& error) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (ec) return error = ec.message(), false;
  std::ifstream in(file, std::ios::binary);
  if (!in) return error = std::strerror(errno), false;
  // 8 zero bytes past the end: tinygltf's GLB reader may look up to 8 bytes beyond a BIN chunk
  // (its bound omits the chunk header); checked below, but never a read outside the allocation.
  out.assign(size + 8, 0);
  out.resize(size);
  in.read(reinterpret_cast<char*>(out.data()), std::streamsize(size));
  if (in.gcount() != std::streamsize(size)) return error = "read error", false;
  return true;
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& files = *static_cast<SceneFiles*>(user);
  const auto uri = uri_of(files, path);
  if (!uri) return false;
  const bool ok = files.read(*uri, *out);
  if (!ok && err) *err += files.problem();
  return ok;
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed";
  return false;
}

uint32_t le32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// GLB 2.0 container (glTF 2.0 §4.4): 12-byte header, a JSON chunk, an optional BIN chunk, and
// chunks of other types to ignore. Returns the BIN chunk's length.
size_t check_glb(const std::vector<unsigned char>& bytes, const std::string& file, size_t& json_length) {
  if (bytes.size() < 20) fail("{}: GLB file of {} bytes is too short for its header", file, bytes.size());
  const uint32_t version = le32(&bytes[4]), length = le32(&bytes[8]);
  if (version != 2) fail("{}: GLB version {} (Prism reads glTF 2.0 GLB files, version 2)", file, version);
  if (length != bytes.size())
    fail("{}: GLB header gives a length of {} bytes, the file has {}", file, length, bytes.size());
  size_t at = 12, bin = 0;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8) fail("{}: GLB chunk {} at byte {} is cut short", file, chunk, at);
    const size_t size = le32(&bytes[at]);
    const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    if (size > bytes.size() - at - 8)
      fail("{}: GLB chunk {} claims {} bytes, the file has {} after its header", file, chunk, size,
           bytes.size() - at - 8);
    if (chunk == 0 && (type != "JSON" || size == 0)) fail("{}: GLB's first chunk must be a non-empty JSON chunk", file);
    if (chunk == 0) json_length = size;
    if (chunk == 1 && type == std::string("BIN\0", 4)) bin = size;
    at += 8 + size;
  }
  return bin;
}

void check_depth(const char* text, size_t size, const std::string& file) {
  if (json_depth(text, size) > kMaxJsonDepth)
    fail("{}: JSON nested deeper than {} levels (refused: no glTF needs that)", file, kMaxJsonDepth);
}

std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n') c = ';';
  return text;
}

// The file's first extension in extensionsRequired that Prism lacks, or "".
std::string unsupported_required_extension(std::string_view json) {
  const auto doc = nlohmann::json::parse(json, nullptr, false);
  if (!doc.is_object() || !doc.contains("extensionsRequired") || !doc["extensionsRequired"].is_array()) return {};
  for (const auto& ext : doc["extensionsRequired"])
    if (ext.is_string() && !extension_handling(ext.get<std::string>())) return ext.get<std::string>();
  return {};
}

// The parser's errors less those glTF 2.0 does not make errors: tinygltf 2.7 calls a skin's
// inverseBindMatrices required, which the spec makes optional (identity matrices, §5.28).
std::string spec_errors(const std::string& errors) {
  std::string kept, line;
  std::istringstream lines(errors);
  while (std::getline(lines, line))
    if (line != "'inverseBindMatrices' property is missing in Skin.") kept += line + '\n';
  return kept;
}

// glTF 2.0 §5.10: a buffer's byteLength is at least 1 (tinygltf throws on a GLB buffer of 0 bytes).
void check_buffer_lengths(std::string_view json, const std::string& file) {
  const nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return;
  for (size_t b = 0; b < doc["buffers"].size(); ++b) {
    const nlohmann::json& buffer = doc["buffers"][b];
    if (buffer.is_object() && buffer.contains("byteLength") && buffer["byteLength"].is_number() &&
        !(buffer["byteLength"].get<double>() >= 1))
      fail("{}: buffer {} declares a byteLength of {} (at least 1)", file, b, buffer["byteLength"].dump());
  }
}

}  // namespace

std::string_view gltf_json(const std::vector<unsigned char>& bytes, bool binary) {
  if (!binary) return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  return {reinterpret_cast<const char*>(&bytes[20]), le32(&bytes[12])};
}

int json_depth(const char* text, size_t size) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

SceneFiles::SceneFiles(const fs::path& scene_file, bool allow_external_paths)
    : scene_file_(scene_file.string()), allow_external_(allow_external_paths) {
  std::error_code ec;
  if (!fs::is_regular_file(scene_file, ec)) fail("{}: no such file", scene_file_);
  root_ = fs::weakly_canonical(fs::absolute(scene_file).parent_path(), ec);
  if (ec) fail("{}: cannot resolve its folder: {}", scene_file_, ec.message());
  base_ = root_.string();
}

fs::path SceneFiles::resolve(const std::string& uri) {
  const fs::path named = !uri.empty() && uri.front() == '/' ? fs::path(uri) : root_ / uri;
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(named, ec);
  const auto refuse = [&](const std::string& why) {
    if (problem_.empty()) problem_ = why;
    return fs::path();
  };
  if (uri.empty()) return refuse("an empty URI");
  if (ec) return refuse(fmt::format("URI '{}' cannot be resolved (tried {}): {}", uri, named.string(), ec.message()));
  if (!allow_external_ && !inside(root_, resolved))
    return refuse(
        fmt::format("URI '{}' resolves to {}, outside the scene's folder {} (--allow-external-paths allows it)", uri,
                    resolved.string(), root_.string()));
  if (!fs::exists(resolved, ec))
    return refuse(fmt::format("URI '{}': no such file (tried {})", uri, resolved.string()));
  if (!fs::is_regular_file(resolved, ec))
    return refuse(fmt::format("URI '{}': {} is not a regular file", uri, resolved.string()));
  return resolved;
}

bool SceneFiles::read(const std::string& uri, std::vector<unsigned char>& out) {
  const fs::path file = resolve(uri);
  if (file.empty()) return false;
  std::string error;
  if (!read_bytes(file, out, error)) {
    if (problem_.empty()) problem_ = fmt::format("cannot read {}: {}", file.string(), error);
    return false;
  }
  content_.add("/" + uri);
  content_.add(out.data(), out.size());
  return true;
}

std::vector<unsigned char> SceneFiles::read(const std::string& uri, const std::string& what) {
  std::vector<unsigned char> bytes;
  if (!read(uri, bytes)) {
    std::string why;
    std::swap(why, problem_);
    fail("{}: {}: {}", scene_file_, what, why);
  }
  return bytes;
}

void SceneFiles::add_scene_bytes(const std::vector<unsigned char>& bytes) { content_.add(bytes.data(), bytes.size()); }

std::string read_gltf_file(tinygltf::TinyGLTF& reader, tinygltf::Model& model, const fs::path& file, SceneFiles& files,
                           std::string& json) {
  const std::string name = file.string();
  reader.SetFsCallbacks({file_exists, expand_path, read_whole_file, write_whole_file, &files});

  std::vector<unsigned char> bytes;
  std::string error, warn;
  if (!read_bytes(file, bytes, error)) fail("{}: cannot read: {}", name, error);
  files.add_scene_bytes(bytes);
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  size_t bin_length = 0;
  if (binary) {
    size_t json_length = 0;
    bin_length = check_glb(bytes, name, json_length);
    check_depth(reinterpret_cast<const char*>(&bytes[20]), json_length, name);
  } else {
    check_depth(reinterpret_cast<const char*>(bytes.data()), bytes.size(), name);
  }
  if (const std::string_view text = gltf_json(bytes, binary); text.find("\"prism\"") != std::string_view::npos)
    json = text;
  bytes = prepare_for_tinygltf(std::move(bytes), binary, name);
  if (bytes.size() > std::numeric_limits<unsigned>::max()) fail("{}: glTF and GLB files are limited to 4 GB", name);
  bool ok = false;
  try {
    ok = binary ? reader.LoadBinaryFromMemory(&model, &error, &warn, bytes.data(), unsigned(bytes.size()), files.base())
                : reader.LoadASCIIFromString(&model, &error, &warn, reinterpret_cast<const char*>(bytes.data()),
                                             unsigned(bytes.size()), files.base());
  } catch (const std::exception& e) {  // the parser's own checks missed something: name what we can
    check_buffer_lengths(gltf_json(bytes, binary), name);
    fail("{}: not a valid glTF file: the parser stopped on it ({})", name, e.what());
  }
  if (!files.problem().empty()) fail("{}: {}", name, files.problem());
  // A required extension the parser cannot follow (its data elsewhere) is the real cause.
  if (!ok)
    if (const std::string ext = unsupported_required_extension(gltf_json(bytes, binary)); !ext.empty())
      fail("{}: requires extension {}, which Prism does not support", name, ext);
  if (!ok) fail("{}: not a valid glTF file: {}", name, error.empty() ? "unknown error" : one_line(error));
  if (!warn.empty()) log::warn("{}: {}", name, one_line(warn));
  if (binary)
    for (size_t b = 0; b < model.buffers.size(); ++b)
      if (model.buffers[b].uri.empty() && model.buffers[b].data.size() > bin_length)
        fail("{}: buffer {} claims {} bytes, the GLB's BIN chunk holds {}", name, b, model.buffers[b].data.size(),
             bin_length);
  return one_line(spec_errors(error));
}

}  // namespace prism
