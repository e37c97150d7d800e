#include "core/scene/gltf_file.h"

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/base/checksum.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/scene/gltf_compression.h"
#include "core/scene/gltf_import.h"

namespace prism {

namespace fs = std::filesystem;

namespace {

// The files a glTF may read: tinygltf asks through these callbacks for "<base>/<decoded URI>",
// then for "./<decoded URI>" (the current folder, never allowed here).
struct UriPolicy {
  fs::path root;     // the scene file's folder, symlinks resolved
  std::string base;  // the base folder as handed to tinygltf
  bool allow_external = false;
  std::string problem;  // the first file refused or missing, for the error message
  Checksum content;     // of every file read (read_gltf_file)
};

bool inside(const fs::path& root, const fs::path& p) {
  return std::mismatch(root.begin(), root.end(), p.begin(), p.end()).first == root.end();
}

// The file `joined` (= base/URI) names after the policy, or an empty path with policy.problem set.
fs::path resolve(UriPolicy& policy, const std::string& joined) {
  if (joined.size() <= policy.base.size() || joined.compare(0, policy.base.size(), policy.base) != 0 ||
      joined[policy.base.size()] != '/')
    return {};  // tinygltf's fallback to the current folder
  const std::string uri = joined.substr(policy.base.size() + 1);
  const fs::path named = uri.front() == '/' ? fs::path(uri) : policy.root / uri;
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(named, ec);
  const auto refuse = [&](const std::string& why) {
    if (policy.problem.empty()) policy.problem = why;
    return fs::path();
  };
  if (ec) return refuse(fmt::format("URI '{}' cannot be resolved (tried {}): {}", uri, named.string(), ec.message()));
  if (!policy.allow_external && !inside(policy.root, resolved))
    return refuse(
        fmt::format("URI '{}' resolves to {}, outside the scene's folder {} (--allow-external-paths allows it)", uri,
                    resolved.string(), policy.root.string()));
  if (!fs::exists(resolved, ec))
    return refuse(fmt::format("URI '{}': no such file (tried {})", uri, resolved.string()));
  if (!fs::is_regular_file(resolved, ec))
    return refuse(fmt::format("URI '{}': {} is not a regular file", uri, resolved.string()));
  return resolved;
}

bool file_exists(const std::string& path, void* user) { return !resolve(*static_cast<UriPolicy*>(user), path).empty(); }

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
  auto& policy = *static_cast<UriPolicy*>(user);
  const fs::path file = resolve(policy, path);
  if (file.empty()) return false;
  std::string error;
  if (read_bytes(file, *out, error)) {
    policy.content.add(path.substr(std::min(path.size(), policy.base.size())));  // "/URI"
    policy.content.add(out->data(), out->size());
    return true;
  }
  if (policy.problem.empty()) policy.problem = fmt::format("cannot read {}: {}", file.string(), error);
  if (err) *err += policy.problem;
  return false;
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

std::string read_gltf_file(tinygltf::TinyGLTF& reader, tinygltf::Model& model, const fs::path& file,
                           bool allow_external_paths, uint64_t& content_hash) {
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) fail("{}: no such file", name);
  UriPolicy policy;
  policy.root = fs::weakly_canonical(fs::absolute(file).parent_path(), ec);
  if (ec) fail("{}: cannot resolve its folder: {}", name, ec.message());
  policy.base = policy.root.string();
  policy.allow_external = allow_external_paths;
  reader.SetFsCallbacks({file_exists, expand_path, read_whole_file, write_whole_file, &policy});

  std::vector<unsigned char> bytes;
  std::string error, warn;
  if (!read_bytes(file, bytes, error)) fail("{}: cannot read: {}", name, error);
  policy.content.add(bytes.data(), bytes.size());
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  size_t bin_length = 0;
  if (binary) {
    size_t json_length = 0;
    bin_length = check_glb(bytes, name, json_length);
    check_depth(reinterpret_cast<const char*>(&bytes[20]), json_length, name);
  } else {
    check_depth(reinterpret_cast<const char*>(bytes.data()), bytes.size(), name);
  }
  bytes = prepare_for_tinygltf(std::move(bytes), binary, name);
  if (bytes.size() > std::numeric_limits<unsigned>::max()) fail("{}: glTF and GLB files are limited to 4 GB", name);
  const bool ok =
      binary ? reader.LoadBinaryFromMemory(&model, &error, &warn, bytes.data(), unsigned(bytes.size()), policy.base)
             : reader.LoadASCIIFromString(&model, &error, &warn, reinterpret_cast<const char*>(bytes.data()),
                                          unsigned(bytes.size()), policy.base);
  if (!policy.problem.empty()) fail("{}: {}", name, policy.problem);
  content_hash = policy.content.h;
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
