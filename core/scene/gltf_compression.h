#pragma once
// Compressed glTF geometry made plain for the importer: KHR_draco_mesh_compression and
// EXT_/KHR_meshopt_compression are decoded into ordinary buffers, views and accessors of the
// parsed model, so the rest of the importer reads every file the same way.
//
// Debian's tinygltf is built without Draco and checks, while parsing, that a primitive's index
// accessor has a bufferView (a Draco primitive's has none) and that a buffer without a uri is
// the GLB's binary chunk (a meshopt fallback buffer is neither). So the file's JSON is adjusted
// before tinygltf sees it (prepare_for_tinygltf), and the data decoded after (decode_*).

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace prism {

// The bytes of a .gltf (JSON) or .glb file adjusted so that Debian's tinygltf parses what Prism
// reads (gltf_prepare.cpp): a Draco primitive's "indices" move into its extension object as
// "prism_indices"; a meshopt fallback buffer without data gets a one-byte placeholder; an image
// embedded as a data URI of a type tinygltf does not know (image/webp, image/ktx2) is relabelled
// application/octet-stream (its mimeType stays). Files that need none of it come back unchanged.
// `bytes` have passed read_gltf_file's checks (GLB chunks, JSON depth); `file` names the file in
// errors.
std::vector<unsigned char> prepare_for_tinygltf(std::vector<unsigned char> bytes, bool binary, const std::string& file);

// Decodes every EXT_/KHR_meshopt_compression bufferView into a new buffer it then refers to.
void decode_meshopt(tinygltf::Model& model, const std::string& file);

// Decodes every KHR_draco_mesh_compression primitive into new buffers, views and accessors.
void decode_draco(tinygltf::Model& model, const std::string& file);

}  // namespace prism
