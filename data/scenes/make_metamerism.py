#!/usr/bin/env python3
"""Generate data/scenes/metamerism.gltf: two paints that match in daylight and part under a lamp.

Two square patches on a grey card. The left patch's reflectance is a smooth spectrum; the right
one's is the same plus a metameric black for D65: a spectrum whose XYZ under D65 is exactly 0,
found by projecting an oscillation out of the three-dimensional space that D65's x̄, ȳ and z̄
weights span. Both are tables at 10 nm from 380 to 780 nm (glTF extras, "reflectance"); since
the renderer interpolates them linearly, the projection is made on that piecewise-linear basis,
so the two patches have the same XYZ under D65 as rendered, and different ones under any light
of another spectrum (illuminant A, F11, a 3000 K LED, ...).

The scene has no light of its own: render it under a constant environment of the illuminant's
spectrum, balanced for it, e.g.
    prism render data/scenes/metamerism.gltf -o out.exr --env 1,1,1 --env-spectrum A --white-balance A
The script prints the patches' CIEDE2000 colour difference under D65, A and F11 (CIELAB relative to
the illuminant's white, the CIE 1931 observer), as the colorimetry computes it.

Run:  python3 data/scenes/make_metamerism.py
Standard library only (helpers in gltf_builder.py); reads data/cie/.
"""
import csv
import math
import os

from gltf_builder import build_gltf, lambert, look_at_camera, quad, write_gltf

HERE = os.path.dirname(os.path.abspath(__file__))
CIE = os.path.join(HERE, "..", "cie")
NODES = list(range(380, 781, 10))  # nm


def read_table(name):
    rows = [line for line in open(os.path.join(CIE, name)) if not line.startswith("#")]
    table = list(csv.reader(rows))
    return table[0], [[float(x) for x in row] for row in table[1:]]


def cie_tables():
    """x̄, ȳ, z̄ and D65 at every nm from 360 to 830 (dicts)."""
    _, cmf = read_table("cie1931_2deg_xyz.csv")
    _, d65 = read_table("cie_d65.csv")
    return {int(r[0]): r[1:4] for r in cmf}, {int(r[0]): r[1] for r in d65}


def linear(points, values, l):
    """Linear interpolation through (points, values), 0 outside them."""
    if l < points[0] or l > points[-1]:
        return 0.0
    for i in range(len(points) - 1):
        if points[i] <= l <= points[i + 1]:
            t = (l - points[i]) / (points[i + 1] - points[i])
            return values[i] + t * (values[i + 1] - values[i])
    return values[-1]


def xyz(reflectance, illuminant, cmf, step=0.1):
    """XYZ of a reflectance table under an illuminant (a function of nm), white Y = 1."""
    x = y = z = norm = 0.0
    l = 360.0 + step / 2
    while l < 830:
        s = illuminant(l)
        r = linear(NODES, reflectance, l)
        a = int(l)
        f = l - a
        bar = [cmf[a][i] + f * (cmf[a + 1][i] - cmf[a][i]) for i in range(3)]
        x += r * s * bar[0]
        y += r * s * bar[1]
        z += r * s * bar[2]
        norm += s * bar[1]
        l += step
    return x / norm, y / norm, z / norm


def metameric_black(oscillation, d65, cmf):
    """oscillation minus its projection on the span of the hat functions' D65-weighted x̄ȳz̄
    integrals: a piecewise-linear spectrum with zero XYZ under D65."""
    n = len(NODES)
    # A[c][i] = ∫ hat_i(λ) D65(λ) c̄(λ) dλ (c = x, y, z), by a fine sum.
    a = [[0.0] * n for _ in range(3)]
    step = 0.1
    l = 360.0 + step / 2
    while l < 830:
        k = int(l)
        f = l - k
        s = d65[k] + f * (d65[k + 1] - d65[k])
        bar = [cmf[k][c] + f * (cmf[k + 1][c] - cmf[k][c]) for c in range(3)]
        if NODES[0] <= l <= NODES[-1]:
            i = min(int((l - NODES[0]) // 10), n - 2)  # l between nodes i and i + 1
            t = (l - NODES[i]) / 10
            for j, hat in ((i, 1 - t), (i + 1, t)):
                for c in range(3):
                    a[c][j] += hat * s * bar[c] * step
        l += step
    # b = p − Aᵀ (A Aᵀ)⁻¹ A p
    ap = [sum(a[c][i] * oscillation[i] for i in range(n)) for c in range(3)]
    g = [[sum(a[r][i] * a[c][i] for i in range(n)) for c in range(3)] for r in range(3)]
    coeffs = solve3(g, ap)
    return [oscillation[i] - sum(a[c][i] * coeffs[c] for c in range(3)) for i in range(n)]


def solve3(m, v):
    det = lambda q: (q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0])
                     + q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]))
    d = det(m)
    out = []
    for c in range(3):
        q = [row[:] for row in m]
        for r in range(3):
            q[r][c] = v[r]
        out.append(det(q) / d)
    return out


def lab(c, white):
    """CIELAB of XYZ c relative to `white` (CIE 15)."""
    def f(t):
        return t ** (1 / 3) if t > (6 / 29) ** 3 else t / (3 * (6 / 29) ** 2) + 4 / 29
    fx, fy, fz = (f(c[i] / white[i]) for i in range(3))
    return 116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)


def ciede2000(lab1, lab2):
    """CIEDE2000 colour difference (Sharma, Wu & Dalal 2005, kL = kC = kH = 1)."""
    l1, a1, b1 = lab1
    l2, a2, b2 = lab2
    c1, c2 = math.hypot(a1, b1), math.hypot(a2, b2)
    cm = (c1 + c2) / 2
    g = 0.5 * (1 - math.sqrt(cm ** 7 / (cm ** 7 + 25 ** 7)))
    a1p, a2p = (1 + g) * a1, (1 + g) * a2
    c1p, c2p = math.hypot(a1p, b1), math.hypot(a2p, b2)
    h1p = math.degrees(math.atan2(b1, a1p)) % 360 if c1p else 0.0
    h2p = math.degrees(math.atan2(b2, a2p)) % 360 if c2p else 0.0
    dlp, dcp = l2 - l1, c2p - c1p
    dh = h2p - h1p
    if c1p * c2p == 0:
        dh = 0.0
    elif dh > 180:
        dh -= 360
    elif dh < -180:
        dh += 360
    dhp = 2 * math.sqrt(c1p * c2p) * math.sin(math.radians(dh / 2))
    lpm, cpm = (l1 + l2) / 2, (c1p + c2p) / 2
    if c1p * c2p == 0:
        hpm = h1p + h2p
    elif abs(h1p - h2p) <= 180:
        hpm = (h1p + h2p) / 2
    else:
        hpm = (h1p + h2p + 360) / 2 if h1p + h2p < 360 else (h1p + h2p - 360) / 2
    t = (1 - 0.17 * math.cos(math.radians(hpm - 30)) + 0.24 * math.cos(math.radians(2 * hpm))
         + 0.32 * math.cos(math.radians(3 * hpm + 6)) - 0.20 * math.cos(math.radians(4 * hpm - 63)))
    dtheta = 30 * math.exp(-(((hpm - 275) / 25) ** 2))
    rc = 2 * math.sqrt(cpm ** 7 / (cpm ** 7 + 25 ** 7))
    sl = 1 + 0.015 * (lpm - 50) ** 2 / math.sqrt(20 + (lpm - 50) ** 2)
    sc = 1 + 0.045 * cpm
    sh = 1 + 0.015 * cpm * t
    rt = -math.sin(math.radians(2 * dtheta)) * rc
    return math.sqrt((dlp / sl) ** 2 + (dcp / sc) ** 2 + (dhp / sh) ** 2 + rt * (dcp / sc) * (dhp / sh))


def illuminants(d65):
    _, fl = read_table("cie_illuminants_fl_led.csv")
    f11 = {int(r[0]): r[11] for r in fl}
    return {
        "D65": lambda l: d65[int(l)] + (l - int(l)) * (d65[min(int(l) + 1, 830)] - d65[int(l)]),
        "A": lambda l: 100 * (560 / l) ** 5 * math.expm1(1.435e7 / (2848 * 560)) / math.expm1(1.435e7 / (2848 * l)),
        "F11": lambda l: linear(sorted(f11), [f11[k] for k in sorted(f11)], l),
    }


def main():
    cmf, d65 = cie_tables()
    # A muted green-grey paint, and an oscillation of three periods over the visible.
    base = [0.38 + 0.12 * math.exp(-((l - 530) / 60) ** 2) for l in NODES]
    oscillation = [0.16 * math.sin(2 * math.pi * (l - 380) / 133) for l in NODES]
    black = metameric_black(oscillation, d65, cmf)
    left = [round(v, 6) for v in base]
    right = [round(b + k, 6) for b, k in zip(base, black)]
    assert all(0 < v < 1 for v in right), "the second paint must stay a reflectance"
    for name, light in illuminants(d65).items():
        white = xyz([1.0] * len(NODES), light, cmf)
        d = ciede2000(lab(xyz(left, light, cmf), white), lab(xyz(right, light, cmf), white))
        print("%-4s CIEDE2000 between the patches: %.2f" % (name, d))

    def paint(name, values):
        m = lambert(name, (0.5, 0.5, 0.5))
        m["extras"] = {"prism": {"reflectance": {"wavelengths": NODES, "values": values}}}
        return m

    card = lambert("grey_card", (0.18, 0.18, 0.18))
    objects = [
        ("card", quad((-1.6, -1.0, 0), (1.6, -1.0, 0), (1.6, 1.0, 0), (-1.6, 1.0, 0)), card),
        ("left_paint", quad((-1.3, -0.7, 0.002), (-0.1, -0.7, 0.002), (-0.1, 0.7, 0.002), (-1.3, 0.7, 0.002)),
         paint("paint_smooth", left)),
        ("right_paint", quad((0.1, -0.7, 0.002), (1.3, -0.7, 0.002), (1.3, 0.7, 0.002), (0.1, 0.7, 0.002)),
         paint("paint_metamer", right)),
    ]
    gltf = build_gltf(objects, look_at_camera("camera", (0.0, 0.0, 4.2), (0.0, 0.0, 0.0), 32.0),
                      "Prism make_metamerism.py", "Prism project", "metamerism")
    gltf["cameras"][0]["perspective"]["aspectRatio"] = 1.6
    write_gltf(os.path.join(HERE, "metamerism.gltf"), gltf)


if __name__ == "__main__":
    main()
