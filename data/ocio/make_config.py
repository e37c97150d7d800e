#!/usr/bin/env python3
"""Generates Prism's OpenColorIO config (data/ocio/config.ocio).

Run from the repository root:   python3 data/ocio/make_config.py
(Python 3 standard library only.)  The config is written next to this script.

Every matrix is derived here from first principles rather than copied:
  * RGB -> XYZ from the chromaticities of the primaries and of the white
    point: the normalised primary matrix (NPM) of SMPTE RP 177-1993.
  * White-point changes with the linearised Bradford chromatic adaptation
    transform (von Kries scaling in Bradford "cone" space).

The reference space is CIE XYZ relative to D65 (scene-referred, linear), which
is what Prism's film records.  D65 is taken as x = 0.3127, y = 0.3290 (the
Rec.709/sRGB definition); ACES spaces use the ACES white x = 0.32168,
y = 0.33767 and are reached from XYZ-D65 by Bradford adaptation, as in the
ACES reference implementation and the OCIO ACES configs.

Re-run after editing; commit both this script and the generated config.ocio.
"""

import json
import os

# ---------------------------------------------------------------------------
# Chromaticities
# ---------------------------------------------------------------------------

# D65 as rounded by Rec.709/sRGB/ACES.  Integrating data/cie (1 nm D65 x CIE 1931 2 deg)
# gives XYZ (0.95047, 1, 1.08883), i.e. xy (0.312727, 0.329023): that white lands
# at Rec.709 (1.00016, 0.99998, 0.99976) -- kept so the matrices match the standards.
WHITE_D65 = (0.3127, 0.3290)
WHITE_ACES = (0.32168, 0.33767)

# (red, green, blue) primaries as (x, y)
PRIMARIES_REC709 = ((0.64, 0.33), (0.30, 0.60), (0.15, 0.06))        # ITU-R BT.709 / IEC 61966-2-1
PRIMARIES_AP1 = ((0.713, 0.293), (0.165, 0.830), (0.128, 0.044))     # Academy S-2014-004 (ACEScg)
PRIMARIES_AP0 = ((0.7347, 0.2653), (0.0, 1.0), (0.0001, -0.0770))    # SMPTE ST 2065-1 (ACES2065-1)

# Bradford cone-response matrix: K. M. Lam, "Metamerism and Colour Constancy", PhD thesis, University of Bradford, 1985.
BRADFORD = (
    (0.8951, 0.2664, -0.1614),
    (-0.7502, 1.7135, 0.0367),
    (0.0389, -0.0685, 1.0296),
)

# sRGB transfer function, IEC 61966-2-1:1999: V = 1.055 * L^(1/2.4) - 0.055 above
# the break point, 12.92 * L below it.  OCIO's ExponentWithLinearTransform
# derives the break point and linear slope from (gamma, offset).
SRGB_GAMMA = 2.4
SRGB_OFFSET = 0.055

# ---------------------------------------------------------------------------
# 3x3 linear algebra (row-major tuples of tuples)
# ---------------------------------------------------------------------------


def mat_mul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def mat_vec(m, v):
    return tuple(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))


def diag(v):
    return tuple(tuple(v[i] if i == j else 0.0 for j in range(3)) for i in range(3))


def transpose(m):
    return tuple(tuple(m[j][i] for j in range(3)) for i in range(3))


def mat_inv(m):
    """Inverse via the adjugate: M^-1 = adj(M) / det(M)."""
    (a, b, c), (d, e, f), (g, h, i) = m
    cof = (
        (e * i - f * h, -(d * i - f * g), d * h - e * g),
        (-(b * i - c * h), a * i - c * g, -(a * h - b * g)),
        (b * f - c * e, -(a * f - c * d), a * e - b * d),
    )
    det = a * cof[0][0] + b * cof[0][1] + c * cof[0][2]
    if abs(det) < 1e-15:
        raise ValueError("singular matrix")
    adj = transpose(cof)
    return tuple(tuple(adj[r][s] / det for s in range(3)) for r in range(3))


# ---------------------------------------------------------------------------
# Colorimetry
# ---------------------------------------------------------------------------


def xy_to_XYZ(xy):
    """Chromaticity (x, y) -> tristimulus XYZ with Y = 1."""
    x, y = xy
    return (x / y, 1.0, (1.0 - x - y) / y)


def normalised_primary_matrix(primaries, white):
    """SMPTE RP 177: RGB -> XYZ such that RGB (1,1,1) maps to the white's XYZ (Y = 1).

    P has the primaries' XYZ (each with Y = 1) as columns; the scale factors
    S = P^-1 W give each primary's luminance share; NPM = P diag(S).
    """
    P = transpose(tuple(xy_to_XYZ(p) for p in primaries))
    S = mat_vec(mat_inv(P), xy_to_XYZ(white))
    return mat_mul(P, diag(S))


def bradford_cat(src_white, dst_white):
    """XYZ under src_white -> corresponding XYZ under dst_white (linearised Bradford).

    M^-1 diag(rho_dst / rho_src) M, where rho = M XYZ_white are cone responses.
    """
    rho_src = mat_vec(BRADFORD, xy_to_XYZ(src_white))
    rho_dst = mat_vec(BRADFORD, xy_to_XYZ(dst_white))
    scale = diag(tuple(d / s for d, s in zip(rho_dst, rho_src)))
    return mat_mul(mat_inv(BRADFORD), mat_mul(scale, BRADFORD))


# Each colour space's to_scene_reference matrix: RGB -> XYZ(D65).
NPM_REC709 = normalised_primary_matrix(PRIMARIES_REC709, WHITE_D65)
CAT_ACES_TO_D65 = bradford_cat(WHITE_ACES, WHITE_D65)
AP1_TO_XYZ_D65 = mat_mul(CAT_ACES_TO_D65, normalised_primary_matrix(PRIMARIES_AP1, WHITE_ACES))
AP0_TO_XYZ_D65 = mat_mul(CAT_ACES_TO_D65, normalised_primary_matrix(PRIMARIES_AP0, WHITE_ACES))

# ---------------------------------------------------------------------------
# Config text
# ---------------------------------------------------------------------------


def num(v):
    """12 significant digits: exact far beyond float precision, still readable."""
    s = "{:.12g}".format(v)
    return "0" if s == "-0" else s


def matrix_transform(m3):
    """OCIO MatrixTransform: 4x4 row-major, 3x3 in the upper left, no offset."""
    m44 = [m3[0][0], m3[0][1], m3[0][2], 0.0,
           m3[1][0], m3[1][1], m3[1][2], 0.0,
           m3[2][0], m3[2][1], m3[2][2], 0.0,
           0.0, 0.0, 0.0, 1.0]
    return "!<MatrixTransform> {matrix: [" + ", ".join(num(v) for v in m44) + "]}"


def colorspace(name, aliases, family, encoding, description, isdata=False, to_reference=None):
    lines = [
        "  - !<ColorSpace>",
        "    name: " + name,
        "    family: " + family,
        "    equalitygroup: \"\"",
        "    bitdepth: 32f",
        "    description: " + json.dumps(description),
        "    isdata: " + ("true" if isdata else "false"),
        "    encoding: " + encoding,
        "    allocation: uniform",
    ]
    # Aliases need profile 2.1.  OCIO matches names and aliases case-insensitively and
    # silently drops an alias equal to the name, so "acescg" etc. need no alias.
    if aliases:
        lines.insert(2, "    aliases: [" + ", ".join(aliases) + "]")
    if to_reference is not None:
        if len(to_reference) == 1:
            lines.append("    to_scene_reference: " + to_reference[0])
        else:
            lines.append("    to_scene_reference: !<GroupTransform>")
            lines.append("      children:")
            lines.extend("        - " + t for t in to_reference)
    return "\n".join(lines) + "\n"


XYZ = "CIE-XYZ-D65"
LIN_REC709 = "Linear Rec.709 (sRGB)"
ACESCG = "ACEScg"
ACES2065 = "ACES2065-1"
SRGB_ENCODED = "sRGB Encoded Rec.709 (sRGB)"
RAW = "Raw"


def build_config():
    luma = NPM_REC709[1]  # Y row of the Rec.709 NPM: the Rec.709 luma weights
    out = []
    out.append(
        "# Prism OpenColorIO config -- GENERATED FILE, do not edit by hand.\n"
        "# Generated by data/ocio/make_config.py (run: python3 data/ocio/make_config.py).\n"
        "# Reference space: CIE XYZ relative to D65 (scene-referred, linear), as recorded by Prism's film.\n"
        "# Matrices: SMPTE RP 177 normalised primary matrices; Bradford adaptation D65 <-> ACES white.\n"
        "\n"
    )
    out.append(
        "ocio_profile_version: 2.1\n"
        "\n"
        "environment:\n"
        "  {}\n"
        "search_path: \"\"\n"
        "strictparsing: true\n"
        "luma: [" + ", ".join(num(v) for v in luma) + "]\n"
        "name: prism\n"
        "description: " + json.dumps("Prism spectral path tracer colour management (reference space CIE-XYZ-D65).") + "\n"
        "\n"
    )
    out.append(
        "roles:\n"
        "  aces_interchange: " + ACES2065 + "\n"
        "  cie_xyz_d65_interchange: " + XYZ + "\n"
        "  color_picking: " + SRGB_ENCODED + "\n"
        "  data: " + RAW + "\n"
        "  default: " + LIN_REC709 + "\n"
        "  matte_paint: " + SRGB_ENCODED + "\n"
        "  reference: " + XYZ + "\n"
        "  rendering: " + LIN_REC709 + "\n"
        "  scene_linear: " + LIN_REC709 + "\n"
        "  texture_paint: " + SRGB_ENCODED + "\n"
        "\n"
    )
    out.append(
        "file_rules:\n"
        "  - !<Rule> {name: Default, colorspace: default}\n"
        "\n"
        "displays:\n"
        "  sRGB:\n"
        "    - !<View> {name: Standard, colorspace: " + SRGB_ENCODED + "}\n"
        "    - !<View> {name: Raw, colorspace: " + RAW + "}\n"
        "\n"
        "active_displays: [sRGB]\n"
        "active_views: [Standard, Raw]\n"
        "\n"
    )
    out.append("colorspaces:\n")
    out.append(colorspace(
        XYZ, ["xyz", "cie_xyz_d65"], "Utility", "scene-linear",
        "CIE 1931 XYZ, D65 white has Y = 1 (reference space; Prism's film).",
    ))
    out.append(colorspace(
        LIN_REC709, ["lin_rec709", "lin_srgb"], "Rec.709", "scene-linear",
        "Linear Rec.709 / sRGB primaries, D65 white.",
        to_reference=[matrix_transform(NPM_REC709)],
    ))
    out.append(colorspace(
        ACESCG, ["lin_ap1"], "ACES", "scene-linear",
        "ACEScg: ACES AP1 primaries, ACES white; Bradford-adapted to D65.",
        to_reference=[matrix_transform(AP1_TO_XYZ_D65)],
    ))
    out.append(colorspace(
        ACES2065, ["aces", "lin_ap0"], "ACES", "scene-linear",
        "ACES2065-1: ACES AP0 primaries, ACES white; Bradford-adapted to D65.",
        to_reference=[matrix_transform(AP0_TO_XYZ_D65)],
    ))
    out.append(colorspace(
        SRGB_ENCODED, ["srgb_display", "srgb_encoded", "srgb"], "Rec.709", "sdr-video",
        "Rec.709 primaries with the IEC 61966-2-1 sRGB transfer curve, clamped to [0, 1] (8-bit previews).",
        to_reference=[
            "!<RangeTransform> {min_in_value: 0, max_in_value: 1, min_out_value: 0, max_out_value: 1}",
            "!<ExponentWithLinearTransform> {gamma: " + num(SRGB_GAMMA) + ", offset: " + num(SRGB_OFFSET) + "}",
            matrix_transform(NPM_REC709),
        ],
    ))
    out.append(colorspace(
        RAW, [], "Utility", "data",
        "Non-colour data (normals, depth, AOVs); never converted.",
        isdata=True,
    ))
    return "".join(out)


def build_chromaticities():
    """Native primaries and white of each RGB space, for OpenEXR's chromaticities attribute.

    They cannot be read back from the config: its matrices include the adaptation to D65.
    """
    rows = [
        (XYZ, ((1, 0), (0, 1), (0, 0)), (1 / 3, 1 / 3)),  # OpenEXR's convention for XYZ data
        (LIN_REC709, PRIMARIES_REC709, WHITE_D65),
        (ACESCG, PRIMARIES_AP1, WHITE_ACES),
        (ACES2065, PRIMARIES_AP0, WHITE_ACES),
        (SRGB_ENCODED, PRIMARIES_REC709, WHITE_D65),
    ]
    out = ["# Native CIE 1931 xy primaries and white point of the RGB colour spaces in config.ocio\n"
           "# (OpenEXR's chromaticities attribute). GENERATED by data/ocio/make_config.py with config.ocio.\n"
           "colorspace,red_x,red_y,green_x,green_y,blue_x,blue_y,white_x,white_y\n"]
    for name, primaries, white in rows:
        values = [v for xy in primaries for v in xy] + list(white)
        out.append(name + "," + ",".join(num(v) for v in values) + "\n")
    return "".join(out)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    for name, text in (("config.ocio", build_config()), ("chromaticities.csv", build_chromaticities())):
        path = os.path.join(here, name)
        with open(path, "w", newline="\n") as f:
            f.write(text)
        print("wrote " + path)


if __name__ == "__main__":
    main()
