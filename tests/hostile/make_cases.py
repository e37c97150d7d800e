#!/usr/bin/env python3
"""Malformed and extreme inputs for `prism render`, one broken thing per case.

    make_cases.py OUTDIR

writes OUTDIR/<case>/ (a scene folder per case) and OUTDIR/manifest.json, a list of
    {"name", "args": [...], "expect": "refused" | "usage" | "rendered", "mention": [...]}
The runner (tests/apps/test_hostile.cpp) replaces {scene} with the case's scene file, {out}
with OUTDIR/<case>/out/out.exr and {dir} with the case folder, runs prism and checks that a
refusal exits 1 (2 for usage) with one line naming the file and each `mention`, that a render
exits 0 with only finite pixels, and that nothing else is left in out/.

OUTDIR/secret/secret.bin is a valid buffer outside every scene folder: a case that reaches it
through `..`, a symlink, an absolute or percent-encoded URI renders if Prism reads it, so
"refused" proves it was not read. Standard library only; deterministic.
"""

import copy
import json
import os
import struct
import sys

# --- the valid base scene: one emissive triangle facing a camera, and a point light ---------

POSITIONS = [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (0.0, 1.0, 0.0)]
INDICES = [0, 1, 2]


def base_bin(colors=None):
    data = b"".join(struct.pack("<3f", *p) for p in POSITIONS)  # 36 bytes
    data += struct.pack("<3H", *INDICES) + b"\0\0"  # 8 bytes
    if colors is not None:
        data += b"".join(struct.pack("<3f", *c) for c in colors)  # 36 bytes
    return data


def base_gltf(uri="tri.bin", colors=False):
    g = {
        "asset": {"version": "2.0", "generator": "prism tests/hostile/make_cases.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "triangle", "mesh": 0},
            {"name": "camera", "camera": 0, "translation": [0, 0, 4]},
            {"name": "lamp", "translation": [0, 0, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"name": "cam", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"name": "bulb", "type": "point", "intensity": 5}]}},
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [
            {
                "name": "glow",
                "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0},
                "emissiveFactor": [1, 0.5, 0.25],
            }
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "buffers": [{"uri": uri, "byteLength": 44}],
    }
    if colors:
        g["bufferViews"].append({"buffer": 0, "byteOffset": 44, "byteLength": 36})
        g["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"})
        g["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = 2
        g["buffers"][0]["byteLength"] = 80
    return g


def glb(gltf, binary, version=2, total=None, json_len=None, bin_len=None, json_type=b"JSON", bin_type=b"BIN\0"):
    """A GLB container; the keyword arguments let a case lie about one field."""
    text = json.dumps(gltf).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<I", len(text) if json_len is None else json_len) + json_type + text
    if binary is not None and len(binary):
        chunks += struct.pack("<I", len(binary) if bin_len is None else bin_len) + bin_type + binary
    length = 12 + len(chunks)
    return b"glTF" + struct.pack("<II", version, length if total is None else total) + chunks


def glb_gltf(**kw):
    g = base_gltf(**kw)
    del g["buffers"][0]["uri"]
    return g


# --- small images for texture cases ----------------------------------------------------------


def png(width, height, pixels=True):
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    body = b""
    if pixels:
        raw = b"".join(b"\0" + b"\x80\x40\x20" * width for _ in range(height))
        body = chunk(b"IDAT", zlib.compress(raw))
    return b"\x89PNG\r\n\x1a\n" + header + body + chunk(b"IEND", b"")


def exr(width, height, chunk_bytes, compression=0, offsets=True, origin=(0, 0)):
    """A scanline OpenEXR file of float R, G, B whose chunks each store chunk_bytes zero bytes,
    whatever their lines need (OpenEXR 3.1 zero-fills a short chunk); offsets=False leaves the
    line offset table empty (every chunk missing); origin is the data window's top left corner."""

    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    channels = b"".join(c + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    x0, y0 = origin
    box = struct.pack("<4i", x0, y0, x0 + width - 1, y0 + height - 1)
    header = (attr("channels", "chlist", channels) + attr("compression", "compression", bytes([compression]))
              + attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box)
              + attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
              + attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0))
              + attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    start = 8 + len(header) + 8 * height
    chunks = b"".join(struct.pack("<ii", y0 + y, chunk_bytes) + b"\0" * chunk_bytes for y in range(height))
    table = b"".join(struct.pack("<Q", start + y * (8 + chunk_bytes) if offsets else 0) for y in range(height))
    return b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header + table + chunks


def textured(g, image):
    g = copy.deepcopy(g)
    g["images"] = [image]
    g["textures"] = [{"source": 0}]
    g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    # TEXCOORD_0: reuse the positions' x, y as a 2-component view over the same bytes.
    g["accessors"].append({"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"})
    g["bufferViews"][0]["byteStride"] = 12
    g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = len(g["accessors"]) - 1
    return g


# --- the cases --------------------------------------------------------------------------------

CASES = []
RENDER = ["render", "{scene}", "-o", "{out}", "--width", "8", "--height", "8", "--spp", "1", "--quiet"]


def case(name, expect, files=None, scene="scene.gltf", args=None, mention=(), links=None):
    CASES.append(
        {
            "name": name,
            "expect": expect,
            "files": files or {},
            "scene": scene,
            "args": args if args is not None else list(RENDER),
            "mention": list(mention),
            "links": links or {},
        }
    )


def gltf_case(name, expect, g, mention=(), extra_files=None, args=None, binary=None, links=None):
    files = {"scene.gltf": json.dumps(g).encode(), "tri.bin": base_bin() if binary is None else binary}
    files.update(extra_files or {})
    case(name, expect, files, args=args, mention=mention, links=links)


def mutated(fn, **kw):
    g = base_gltf(**kw)
    fn(g)
    return g


def set_path(g, path, value):
    node = g
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return g


def build_cases():
    B = base_gltf
    # Valid references, so the suite proves the base scene itself renders.
    gltf_case("valid", "rendered", B())
    case("valid_glb", "rendered", {"scene.glb": glb(glb_gltf(), base_bin())}, scene="scene.glb")
    gltf_case("valid_subfolder_uri", "rendered", B("sub/tri.bin"), extra_files={"sub/tri.bin": base_bin()})
    gltf_case("valid_dotdot_inside", "rendered", B("sub/../tri.bin"), extra_files={"sub/keep": b""})
    gltf_case("valid_percent_encoded", "rendered", B("tri%20copy.bin"), extra_files={"tri copy.bin": base_bin()})
    gltf_case("valid_symlink_inside", "rendered", B("link.bin"), links={"link.bin": "tri.bin"})
    gltf_case("allowed_external_dotdot", "rendered", B("../secret/secret.bin"), args=RENDER + ["--allow-external-paths"])

    # Reads outside the scene's folder: refused by name, never read.
    for name, uri in [
        ("outside_dotdot", "../secret/secret.bin"),
        ("outside_deep_dotdot", "../../../../../../../../etc/passwd"),
        ("outside_percent_dotdot", "%2e%2e/secret/secret.bin"),
        ("outside_percent_slash", "..%2fsecret%2fsecret.bin"),
        ("outside_absolute", "{secret}"),
        ("outside_absolute_etc", "/etc/passwd"),
        ("outside_file_scheme", "file:///etc/passwd"),
    ]:
        gltf_case(name, "refused", B(uri), mention=["outside the scene"] if "scheme" not in name else [])
    gltf_case("outside_symlink", "refused", B("link.bin"), mention=["link.bin", "outside the scene"],
              links={"link.bin": "../secret/secret.bin"})
    gltf_case("outside_symlink_dir", "refused", B("d/secret.bin"), mention=["outside the scene"],
              links={"d": "../secret"})
    gltf_case("outside_image_uri", "refused", textured(B(), {"uri": "../secret/tex.png"}), mention=["outside the scene"])
    gltf_case("missing_buffer", "refused", B("absent.bin"), mention=["absent.bin", "tried"])
    gltf_case("missing_buffer_in_cwd", "refused", B("tri_only_in_cwd.bin"), mention=["tri_only_in_cwd.bin"])
    gltf_case("missing_image", "refused", textured(B(), {"uri": "absent.png"}), mention=["absent.png"])
    gltf_case("buffer_is_directory", "refused", B("sub"), extra_files={"sub/keep": b""}, mention=["sub"])
    gltf_case("buffer_wrong_size", "refused", B(), binary=base_bin()[:40], mention=["tri.bin"])
    gltf_case("buffer_empty_uri", "refused", B(""))
    gltf_case("buffer_bad_data_uri", "refused", B("data:application/octet-stream;base64,!!!!"))

    # JSON: deep nesting, truncation, garbage.
    deep = 100000
    case("json_deep_arrays", "refused", {"scene.gltf": b'{"asset":{"version":"2.0"},"extras":' + b"[" * deep + b"]" * deep + b"}"},
         mention=["nest"])
    case("json_deep_objects", "refused", {"scene.gltf": b'{"asset":{"version":"2.0"},"extras":' + b'{"a":' * deep + b"1" + b"}" * deep + b"}"},
         mention=["nest"])
    case("json_deep_unclosed", "refused", {"scene.gltf": b"[" * 1000000})
    case("json_deep_in_glb", "refused", {"scene.glb": glb({"asset": {"version": "2.0"}}, b"").replace(
        b'{"asset"', b'{"extras":' + b"[" * 50000 + b"]" * 50000 + b',"asset"', 1)}, scene="scene.glb")
    case("json_empty", "refused", {"scene.gltf": b""})
    case("json_truncated", "refused", {"scene.gltf": json.dumps(B()).encode()[:200]})
    case("json_garbage", "refused", {"scene.gltf": bytes(range(256)) * 4})
    case("json_not_object", "refused", {"scene.gltf": b"[1,2,3]"})
    case("json_no_asset", "refused", {"scene.gltf": b"{}"})
    case("json_number_overflow", "refused", {"scene.gltf": json.dumps(B()).encode().replace(b"0.8, 0.8, 0.8", b"1e400, 0.8, 0.8")})
    gltf_case("json_huge_string", "rendered", set_path(B(), ["nodes", 0, "name"], "n" * 1000000))

    # GLB containers that lie.
    G, bb = glb_gltf(), base_bin()
    for name, data, mention in [
        ("glb_version_1", glb(G, bb, version=1), "version"),
        ("glb_version_3", glb(G, bb, version=3), "version"),
        ("glb_total_too_long", glb(G, bb, total=10**6), "length"),
        ("glb_total_too_short", glb(G, bb, total=20), "length"),
        ("glb_json_too_long", glb(G, bb, json_len=2**31), "chunk"),
        ("glb_json_len_zero", glb(G, bb, json_len=0), ""),
        ("glb_bin_8_too_long", glb(G, bb, bin_len=len(bb) + 8), "chunk"),
        ("glb_bin_huge", glb(G, bb, bin_len=2**32 - 1), "chunk"),
        ("glb_json_type_wrong", glb(G, bb, json_type=b"JSOX"), "JSON"),
        ("glb_header_only", b"glTF" + struct.pack("<II", 2, 12), ""),
        ("glb_magic_only", b"glTF", ""),
        ("glb_truncated", glb(G, bb)[:-10], ""),
        ("glb_empty_bin", glb(set_path(glb_gltf(), ["buffers", 0, "byteLength"], 0), b""), "BIN"),
        ("glb_buffer_length_zero", glb(set_path(glb_gltf(), ["buffers", 0, "byteLength"], 0), bb), "buffer 0"),
        ("glb_no_bin_chunk", glb(G, b""), "BIN"),
    ]:
        case(name, "refused", {"scene.glb": data}, scene="scene.glb", mention=[mention] if mention else [])

    # Accessors and buffer views whose ranges overflow or lie.
    near = 2**64 - 8
    for name, path, value in [
        ("accessor_offset_2p64", ["accessors", 0, "byteOffset"], near),
        ("accessor_offset_2p63", ["accessors", 0, "byteOffset"], 2**63),
        ("accessor_offset_past_view", ["accessors", 0, "byteOffset"], 40),
        ("view_offset_2p64", ["bufferViews", 0, "byteOffset"], near),
        ("view_length_2p64", ["bufferViews", 0, "byteLength"], near),
        ("view_length_past_buffer", ["bufferViews", 1, "byteLength"], 100),
        ("accessor_count_huge", ["accessors", 0, "count"], 2**62),
        ("accessor_count_2p32", ["accessors", 1, "count"], 2**32 + 3),
        ("accessor_count_negative", ["accessors", 0, "count"], -3),
        ("accessor_component_bad", ["accessors", 0, "componentType"], 5130),
        ("accessor_type_bad", ["accessors", 0, "type"], "MAT9"),
        ("view_stride_small", ["bufferViews", 0, "byteStride"], 4),
        ("view_stride_huge", ["bufferViews", 0, "byteStride"], 2**40),
        ("view_buffer_missing", ["bufferViews", 0, "buffer"], 7),
        ("view_buffer_negative", ["bufferViews", 0, "buffer"], -1),
        ("prim_position_negative", ["meshes", 0, "primitives", 0, "attributes", "POSITION"], -2),
        ("prim_position_missing", ["meshes", 0, "primitives", 0, "attributes", "POSITION"], 99),
        ("prim_indices_missing", ["meshes", 0, "primitives", 0, "indices"], 99),
        ("prim_material_missing", ["meshes", 0, "primitives", 0, "material"], 99),
        ("node_mesh_missing", ["nodes", 0, "mesh"], 5),
        ("node_camera_missing", ["nodes", 1, "camera"], 5),
        ("node_light_missing", ["nodes", 2, "extensions", "KHR_lights_punctual", "light"], 5),
        ("scene_negative", ["scene"], -5),
        ("scene_missing", ["scene"], 3),
        ("scene_node_missing", ["scenes", 0, "nodes"], [0, 17]),
        ("scene_node_negative", ["scenes", 0, "nodes"], [-1]),
    ]:
        gltf_case(name, "refused", set_path(B(), path, value))
    sparse = B()
    sparse["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                                        "values": {"bufferView": 0}}
    sparse["bufferViews"][1]["byteLength"] = 6
    gltf_case("sparse_index_out_of_range", "refused",
              set_path(copy.deepcopy(sparse), ["accessors", 0, "count"], 1), mention=["sparse"])
    gltf_case("sparse_count_huge", "refused", set_path(copy.deepcopy(sparse), ["accessors", 0, "sparse", "count"], 2**31 - 1))
    gltf_case("sparse_offset_2p64", "refused",
              set_path(copy.deepcopy(sparse), ["accessors", 0, "sparse", "values", "byteOffset"], near))
    bad_index = base_bin()[:36] + struct.pack("<3H", 0, 1, 9) + b"\0\0"
    gltf_case("index_out_of_range", "refused", B(), binary=bad_index, mention=["index 9"])
    nan_pos = struct.pack("<3f", float("nan"), 0, 0) + base_bin()[12:]
    gltf_case("position_nan", "refused", B(), binary=nan_pos, mention=["POSITION"])
    inf_pos = struct.pack("<3f", float("inf"), 0, 0) + base_bin()[12:]
    gltf_case("position_inf", "refused", B(), binary=inf_pos, mention=["POSITION"])

    # Materials: silently wrong values that must be errors.
    for name, path, value, mention in [
        ("base_color_3_entries", ["materials", 0, "pbrMetallicRoughness", "baseColorFactor"], [1, 1, 1], "baseColorFactor"),
        ("emissive_2_entries", ["materials", 0, "emissiveFactor"], [1, 1], "emissiveFactor"),
        ("emissive_negative", ["materials", 0, "emissiveFactor"], [-1, 0, 0], "emissiveFactor"),
        ("emissive_strength_negative", ["materials", 0, "extensions"],
         {"KHR_materials_emissive_strength": {"emissiveStrength": -2}}, "emissiveStrength"),
        ("attenuation_distance_zero", ["materials", 0, "extensions"],
         {"KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 0}}, "attenuationDistance"),
        ("attenuation_distance_negative", ["materials", 0, "extensions"],
         {"KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": -1}}, "attenuationDistance"),
        ("ior_below_one", ["materials", 0, "extensions"], {"KHR_materials_ior": {"ior": 0.5}}, "ior"),
        ("alpha_mode_unknown", ["materials", 0, "alphaMode"], "GLOW", "alphaMode"),
        ("light_intensity_negative", ["extensions", "KHR_lights_punctual", "lights", 0, "intensity"], -1, "intensity"),
        ("light_color_2_entries", ["extensions", "KHR_lights_punctual", "lights", 0, "color"], [1, 1], "color"),
        ("camera_yfov_zero", ["cameras", 0, "perspective", "yfov"], 0, "yfov"),
        ("camera_type_unknown", ["cameras", 0, "type"], "fisheye", "fisheye"),
        ("texture_missing", ["materials", 0, "pbrMetallicRoughness", "baseColorTexture"], {"index": 4}, "texture"),
        ("required_extension_unknown", ["extensionsRequired"], ["EXT_hostile"], "EXT_hostile"),
    ]:
        gltf_case(name, "refused", set_path(B(), path, value), mention=[mention])

    # Legal but extreme values: a defined (clamped) result, never NaN/Inf.
    for name, path, value in [
        ("emissive_1e38", ["materials", 0, "extensions"], {"KHR_materials_emissive_strength": {"emissiveStrength": 1e38}}),
        ("emissive_1e300", ["materials", 0, "extensions"], {"KHR_materials_emissive_strength": {"emissiveStrength": 1e300}}),
        ("emissive_factor_1e300", ["materials", 0, "emissiveFactor"], [1e300, 1e300, 1e300]),
        ("light_intensity_1e38", ["extensions", "KHR_lights_punctual", "lights", 0, "intensity"], 1e38),
        ("light_intensity_1e300", ["extensions", "KHR_lights_punctual", "lights", 0, "intensity"], 1e300),
        ("light_color_1e300", ["extensions", "KHR_lights_punctual", "lights", 0, "color"], [1e300, 1, 1]),
        ("base_color_1e300", ["materials", 0, "pbrMetallicRoughness", "baseColorFactor"], [1e300, 1, 1, 1]),
        ("spot_light_1e38", ["extensions", "KHR_lights_punctual", "lights", 0],
         {"type": "spot", "intensity": 1e38, "spot": {"outerConeAngle": 1.0}}),
        ("directional_1e300", ["extensions", "KHR_lights_punctual", "lights", 0], {"type": "directional", "intensity": 1e300}),
        ("attenuation_distance_tiny", ["materials", 0, "extensions"],
         {"KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 1e-300, "attenuationColor": [0.5, 0.5, 0.5]}}),
    ]:
        gltf_case(name, "rendered", set_path(B(), path, value))
    for name, values in [("color_nan", [float("nan")] * 3), ("color_inf", [float("inf"), -float("inf"), 1e30])]:
        gltf_case(name, "rendered", B(colors=True), binary=base_bin([values, (1, 1, 1), (0.5, 0.5, 0.5)]))

    # Spectral inputs (extras.prism), each broken one way: one error naming the material or light.
    bad_csv = {"bad.csv": b"wavelength_nm,value\n400,0.5\n500,x\n"}
    for name, prism, mention in [
        ("spectrum_unknown_name", {"emission": "D66"}, ["glow", "D66"]),
        ("spectrum_table_empty", {"reflectance": {"wavelengths": [], "values": []}}, ["glow", "empty"]),
        ("spectrum_not_increasing", {"reflectance": {"wavelengths": [500, 400], "values": [0.1, 0.2]}},
         ["glow", "increase"]),
        ("spectrum_negative", {"emission": {"wavelengths": [400, 500], "values": [1, -1]}}, ["glow", "non-negative"]),
        ("spectrum_reflectance_above_1", {"reflectance": {"wavelengths": [400, 500], "values": [0.5, 1.5]}},
         ["glow", "[0, 1]"]),
        ("spectrum_file_outside", {"reflectance": {"file": "../secret/secret.bin"}}, ["glow", "outside"]),
        ("spectrum_file_missing", {"reflectance": {"file": "nowhere.csv"}}, ["glow", "nowhere.csv"]),
        ("spectrum_file_malformed", {"reflectance": {"file": "bad.csv"}}, ["glow", "line 3"]),
        ("spectrum_blackbody_cold", {"emission": {"blackbody": 1}}, ["glow", "blackbody"]),
        ("metal_nk_file_malformed", {"metal": {"nk": "bad.csv"}}, ["glow", "wl,n"]),
        ("glass_sellmeier_short", {"glass": {"sellmeier": [1, 2]}}, ["glow", "sellmeier"]),
    ]:
        gltf_case(name, "refused", set_path(B(), ["materials", 0, "extras"], {"prism": prism}), mention=mention,
                  extra_files=bad_csv)
    gltf_case("light_spectrum_unknown_name", "refused",
              set_path(B(), ["extensions", "KHR_lights_punctual", "lights", 0, "extras"], {"prism": {"emission": "D66"}}),
              mention=["bulb", "D66"])

    # Transforms that overflow only in world space.
    gltf_case("scale_overflow", "refused", set_path(B(), ["nodes", 0, "scale"], [1e39, 1e39, 1e39]), mention=["triangle"])
    big = [(x * 3e38, y * 3e38, z) for x, y, z in POSITIONS]
    gltf_case("positions_times_scale", "refused", set_path(B(), ["nodes", 0, "scale"], [10, 10, 10]),
              binary=b"".join(struct.pack("<3f", *p) for p in big) + base_bin()[36:], mention=["triangle"])
    gltf_case("translation_overflow", "refused", set_path(B(), ["nodes", 0, "translation"], [1e300, 0, 0]),
              mention=["triangle"])
    gltf_case("camera_overflow", "refused", set_path(B(), ["nodes", 1, "translation"], [0, 0, 1e39]), mention=["cam"])
    gltf_case("camera_scale_zero", "refused", set_path(B(), ["nodes", 1, "scale"], [0, 0, 0]), mention=["cam"])
    for name, mag in [("ortho_camera_mag_overflow", 1e300), ("ortho_camera_mag_zero", 0)]:
        gltf_case(name, "refused", set_path(B(), ["cameras", 0], {"name": "cam", "type": "orthographic", "orthographic": {
            "xmag": mag, "ymag": mag, "znear": 0.1, "zfar": 100}}), mention=["cam", "mag"])
    gltf_case("indices_negative", "refused", set_path(B(), ["meshes", 0, "primitives", 0, "indices"], -5),
              mention=["indices", "-5"])
    gltf_case("matrix_nan_free_degenerate", "refused", set_path(B(), ["nodes", 1, "matrix"], [0] * 16), mention=["cam"])
    gltf_case("light_overflow", "refused", set_path(B(), ["nodes", 2, "translation"], [1e39, 0, 0]), mention=["lamp"])

    # Hierarchies: depth, cycles, DAG blow-up, coincident instances.
    chain = B()
    n = 20000
    chain["nodes"] = chain["nodes"][:1] + chain["nodes"][1:] + [{"children": [3 + i + 1]} for i in range(n - 1)] + [{"mesh": 0}]
    chain["scenes"][0]["nodes"] = [1, 2, 3]
    chain["nodes"][0] = {"name": "unused"}
    gltf_case("node_chain_20000", "rendered", chain)
    cycle = B()
    cycle["nodes"][0]["children"] = [3]
    cycle["nodes"].append({"children": [0]})
    gltf_case("node_cycle", "refused", cycle, mention=["cycle"])
    gltf_case("node_self_child", "refused", set_path(B(), ["nodes", 0, "children"], [0]), mention=["cycle"])
    gltf_case("node_child_negative", "refused", set_path(B(), ["nodes", 0, "children"], [-4]))
    dag = B()
    levels = 63
    dag["nodes"] += [{"children": [4 + i, 4 + i]} for i in range(levels)] + [{"mesh": 0}]
    dag["scenes"][0]["nodes"] = [1, 2, 3]
    gltf_case("node_dag_2p63", "refused", dag, mention=["visits", "--max-memory"])
    dag_empty = B()  # found by fuzz_gltf: visits of nodes without meshes are work too
    dag_empty["nodes"] += [{"children": [4 + i, 4 + i]} for i in range(levels)] + [{"name": "leaf"}]
    dag_empty["scenes"][0]["nodes"] = [1, 2, 3]
    gltf_case("node_dag_2p63_no_mesh", "refused", dag_empty, mention=["visits", "--max-memory"])
    dag_small = B()
    dag_small["nodes"] += [{"children": [4 + i, 4 + i]} for i in range(30)] + [{"mesh": 0}]
    dag_small["scenes"][0]["nodes"] = [1, 2, 3]
    gltf_case("node_dag_2p30", "refused", dag_small, mention=["--max-memory"])
    coincident = B()
    coincident["nodes"] += [{"children": [4] * 1000}, {"children": [5] * 1000}, {"mesh": 0}]
    coincident["scenes"][0]["nodes"] = [1, 2, 3]
    gltf_case("coincident_1e6", "rendered", coincident)

    # Images: lies in headers, huge dimensions, garbage.
    for name, image, mention in [
        ("image_huge_dimensions", png(100000, 100000, pixels=False), "too large"),
        ("image_truncated", png(4, 4)[:40], ""),
        ("image_garbage", b"\x89PNG garbage" * 10, ""),
        ("image_zero_size", png(0, 0), ""),
        ("image_pnm_16bit", b"P6683 36 36333 ", "PNG or JPEG"),  # crashed stb_image's PNM reader (fuzz_image)
        ("image_bmp", b"BM" + bytes(60), "PNG or JPEG"),
    ]:
        gltf_case(name, "refused", textured(B(), {"uri": "tex.png"}), extra_files={"tex.png": image},
                  mention=[mention] if mention else ["tex.png"])
    gltf_case("image_valid", "rendered", textured(B(), {"uri": "tex.png"}), extra_files={"tex.png": png(4, 4)})

    # The scene argument itself.
    case("scene_missing", "refused", {}, scene="absent.gltf", mention=["absent.gltf"])
    case("scene_directory", "refused", {"scene.gltf/keep": b""}, mention=["scene.gltf"])
    case("scene_device", "refused", {}, args=["render", "/dev/zero", "-o", "{out}", "--spp", "1"], mention=["/dev/zero"])
    case("scene_extension_txt", "refused", {"scene.txt": b"hello"}, scene="scene.txt", mention=["scene.txt"])

    # Command lines: usage errors (exit 2) and values that must be refused.
    usage = [
        ("spp_zero", ["--spp", "0"], "spp"),
        ("spp_negative", ["--spp", "-4"], "spp"),
        ("spp_overflow", ["--spp", "99999999999999999999"], "spp"),
        ("seed_negative", ["--seed", "-1"], "seed"),
        ("seed_2p64", ["--seed", "18446744073709551616"], "seed"),
        ("seed_text", ["--seed", "abc"], "seed"),
        ("width_zero", ["--width", "0"], "width"),
        ("width_text", ["--width", "wide"], "width"),
        ("height_negative", ["--height", "-1"], "height"),
        ("wavelengths_3", ["--wavelengths", "3"], "wavelengths"),
        ("threads_negative", ["--threads", "-2"], "threads"),
        ("max_depth_negative", ["--max-depth", "-1"], "max-depth"),
        ("integrator_unknown", ["--integrator", "mlt"], "integrator"),
        ("sampler_unknown", ["--sampler", "halton"], "sampler"),
        ("unknown_option", ["--frobnicate"], "frobnicate"),
        ("camera_negative", ["--camera", "-1"], "camera"),
        ("env_scale_negative", ["--env-map", "{dir}/sky.hdr", "--env-scale", "-1"], "env-scale"),
        ("max_memory_zero", ["--max-memory", "0"], "max-memory"),
    ]
    for name, extra, mention in usage:
        gltf_case("cli_" + name, "usage", B(), args=RENDER + extra, mention=[mention])
    case("cli_no_output", "usage", {"scene.gltf": json.dumps(B()).encode(), "tri.bin": base_bin()},
         args=["render", "{scene}"], mention=["output"])
    case("cli_no_subcommand", "usage", {}, args=[], mention=[])

    refused = [
        ("camera_out_of_range", ["--camera", "5"], "camera"),
        ("huge_image", ["--width", "100000", "--height", "100000"], "--max-memory"),
        ("huge_width_from_aspect", ["--height", "2000000000"], "--max-memory"),
        ("env_3e38", ["--env", "3e38,3e38,3e38"], "--env"),
        ("env_nan", ["--env", "nan,1,1"], "--env"),
        ("env_two_values", ["--env", "1,1"], "--env"),
        ("env_map_missing", ["--env-map", "{dir}/absent.exr"], "absent.exr"),
        ("output_device", ["-o", "{dir}/fifo"], "regular file"),  # never a real device: a regression would replace it
        ("output_directory", ["-o", "{dir}/out"], "out"),
        ("output_under_a_file", ["-o", "{dir}/scene.gltf/out.exr"], "not a folder"),
        ("preview_directory", ["--preview", "{dir}/out"], "out"),
        ("preview_device", ["--preview", "{dir}/fifo"], "regular file"),
        ("colorspace_unknown", ["--colorspace", "Rec.9999"], "Rec.9999"),
        ("max_memory_tiny", ["--max-memory", "0.000001"], "--max-memory"),
    ]
    for name, extra, mention in refused:
        args = list(RENDER)
        for i in range(0, len(extra)):
            if extra[i] in ("-o", "--width", "--height") and extra[i] in args:
                j = args.index(extra[i])
                del args[j : j + 2]
        gltf_case("cli_" + name, "refused", B(), args=args + extra, mention=[mention])
    case("cli_camera_aspect_tiny", "refused",
         {"scene.gltf": json.dumps(set_path(B(), ["cameras", 0, "perspective", "aspectRatio"], 1e-7)).encode(),
          "tri.bin": base_bin()}, args=RENDER[:6] + RENDER[8:],
         mention=["--max-memory"])
    sky = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n" + b"\xff\xff\xff\xff" * 2  # FLT_MAX-ish RGBE
    gltf_case("env_map_flt_max", "refused", B(), extra_files={"sky.hdr": sky},
              args=RENDER + ["--env-map", "{dir}/sky.hdr"], mention=["sky.hdr"])
    fine_sky = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n" + b"\x80\x80\x80\x81" * 2
    gltf_case("env_scale_1e38", "refused", B(), extra_files={"sky.hdr": fine_sky},
              args=RENDER + ["--env-map", "{dir}/sky.hdr", "--env-scale", "1e38"], mention=["--env-scale"])
    gltf_case("env_map_valid", "rendered", B(), extra_files={"sky.hdr": fine_sky},
              args=RENDER + ["--env-map", "{dir}/sky.hdr", "--env-scale", "2"])
    # Found by fuzz_env_map: a zero-length run looped forever in stb_image's HDR reader.
    zero_run = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 16\n\x02\x02\x00\x10\x90\x80\x90\x00\x10"
    gltf_case("env_map_zero_run", "refused", B(), extra_files={"sky.hdr": zero_run},
              args=RENDER + ["--env-map", "{dir}/sky.hdr"], mention=["sky.hdr"])
    gltf_case("env_map_cut_short", "refused", B(), extra_files={"sky.hdr": fine_sky[:-3]},
              args=RENDER + ["--env-map", "{dir}/sky.hdr"], mention=["sky.hdr"])
    gltf_case("env_map_huge_header", "refused", B(),
              extra_files={"sky.hdr": b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n"},
              args=RENDER + ["--env-map", "{dir}/sky.hdr"], mention=["100000x100000"])
    gltf_case("env_1e6", "rendered", B(), args=RENDER + ["--env", "1e6,1e6,1e6"])
    # Found by fuzz_env_map: chunks of 4 bytes for lines of 24 MB, read as 40 million zero pixels.
    for compression, kind in ((0, "none"), (1, "rle")):
        gltf_case(f"env_map_exr_short_chunks_{kind}", "refused", B(),
                  extra_files={"sky.exr": exr(2000000, 20, 4, compression)},
                  args=RENDER + ["--env-map", "{dir}/sky.exr"], mention=["sky.exr", "cut short"])
    gltf_case("env_map_exr_missing_chunks", "refused", B(),
              extra_files={"sky.exr": exr(200000, 400, 0, offsets=False)},
              args=RENDER + ["--env-map", "{dir}/sky.exr"], mention=["sky.exr", "incomplete"])
    gltf_case("env_map_exr_valid", "rendered", B(), extra_files={"sky.exr": exr(4, 2, 48)},
              args=RENDER + ["--env-map", "{dir}/sky.exr"])
    # Found by fuzz_env_map: a data window at (-1, -1) made the reader offset its pointer out of bounds.
    gltf_case("env_map_exr_negative_origin", "rendered", B(), extra_files={"sky.exr": exr(4, 2, 48, origin=(-1, -1))},
              args=RENDER + ["--env-map", "{dir}/sky.exr"])
    gltf_case("env_map_hdr_claims_more", "refused", B(),
              extra_files={"sky.hdr": b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8000 +X 16000\n" + bytes(64)},
              args=RENDER + ["--env-map", "{dir}/sky.hdr"], mention=["sky.hdr", "cut short"])


def write(outdir):
    os.makedirs(outdir, exist_ok=True)
    secret = os.path.join(outdir, "secret")
    os.makedirs(secret, exist_ok=True)
    with open(os.path.join(secret, "secret.bin"), "wb") as f:
        f.write(base_bin())
    with open(os.path.join(outdir, "tri_only_in_cwd.bin"), "wb") as f:  # the runner's working folder
        f.write(base_bin())
    with open(os.path.join(secret, "tex.png"), "wb") as f:
        f.write(png(2, 2))
    manifest = []
    for c in CASES:
        d = os.path.join(outdir, c["name"])
        os.makedirs(os.path.join(d, "out"), exist_ok=True)
        for rel, data in c["files"].items():
            path = os.path.join(d, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            data = data.replace(b"{secret}", os.path.join(secret, "secret.bin").encode())
            with open(path, "wb") as f:
                f.write(data)
        if c["name"] in ("cli_output_device", "cli_preview_device") and not os.path.exists(os.path.join(d, "fifo")):
            os.mkfifo(os.path.join(d, "fifo"))
        for rel, target in c["links"].items():
            path = os.path.join(d, rel)
            if not os.path.lexists(path):
                os.symlink(target, path)
        manifest.append({k: c[k] for k in ("name", "expect", "scene", "args", "mention")})
    with open(os.path.join(outdir, "manifest.json"), "w") as f:
        json.dump(manifest, f, indent=1)
    return len(manifest)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: make_cases.py OUTDIR")
    build_cases()
    print(f"{write(sys.argv[1])} cases in {sys.argv[1]}")
