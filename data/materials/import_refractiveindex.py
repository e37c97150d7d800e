#!/usr/bin/env python3
"""Builds Prism's optical-constants catalogue (data/materials/) from refractiveindex.info files.

Usage:
  import_refractiveindex.py SOURCE_DIR [--check]   regenerate, then (optionally) verify
  import_refractiveindex.py --check                verify the committed files only

SOURCE_DIR is the folder holding metals/*.yml and dielectrics/*.yml: unmodified pages of the
refractiveindex.info database (CC0 1.0), e.g. data/optical-constants in the shared assets
(PRISM_SHARED_DIR). The renderer never reads SOURCE_DIR; it reads what this script writes:

  metals/<key>.csv   '#' comments, header "wavelength_nm,n,k", the measured rows with the
                     wavelength converted from um to nm (n, k copied verbatim). Kept: every row
                     in [360, 830] nm plus the nearest row below 360 and above 830 (when the
                     data has one), so linear interpolation over 360-830 uses measured points only.
  catalogue.json     index of every named material: metals -> their CSV; dielectrics -> Sellmeier
                     coefficients (convention in its "_conventions" field) or a constant n.

Parses only the YAML subset these files use (REFERENCES/COMMENTS blocks, a DATA list with
"type:", "data: |" or "coefficients:", "wavelength_range:"); standard library only.
--check prints n at the F, d, C lines and the Abbe number of each dielectric, n, k and the
normal-incidence reflectance of each metal at 450/550/650 nm, and compares them with reference
values (SCHOTT catalogue nd/Vd; the project's Fresnel test values for Cu, Au, Ag).
Exit status 1 if a reference value disagrees.
"""
import json
import sys
from decimal import Decimal
from pathlib import Path

LAMBDA_MIN, LAMBDA_MAX = 360, 830  # nm, Prism's spectral range
DATABASE = ("refractiveindex.info database (github.com/polyanskiy/refractiveindex.info-database, "
            "commit ff11b5897ef0754b15d939d921eb6c745693cbd1)")
LICENCE = "CC0 1.0 (public domain dedication of the refractiveindex.info database)"

JC72 = "P. B. Johnson, R. W. Christy, Phys. Rev. B 6, 4370 (1972), doi:10.1103/PhysRevB.6.4370"
JC74 = "P. B. Johnson, R. W. Christy, Phys. Rev. B 9, 5056 (1974), doi:10.1103/PhysRevB.9.5056"
SCHOTT = "SCHOTT optical glass catalogue (Zemax AGF) 2017-01-20b, as given by refractiveindex.info"

# key: (name, source file, refractiveindex.info shelf/book/page, citation, note or None)
METALS = {
    "Au": ("Gold", "Au_Johnson.yml", "main/Au/Johnson", JC72, None),
    "Ag": ("Silver", "Ag_Johnson.yml", "main/Ag/Johnson", JC72, None),
    "Cu": ("Copper", "Cu_Johnson.yml", "main/Cu/Johnson", JC72, None),
    "Al": ("Aluminium", "Al_McPeak.yml", "main/Al/McPeak",
           "K. M. McPeak, S. V. Jayanti, S. J. P. Kress, S. Meyer, S. Iotti, A. Rossinelli, "
           "D. J. Norris, ACS Photonics 2, 326 (2015), doi:10.1021/ph5004237",
           "evaporated, template-stripped film; 5 nm steps, chosen over Rakic 1995 (12 points "
           "in 360-830 nm) and the Rakic 1998 Lorentz-Drude fit"),
    "Cr": ("Chromium", "Cr_Johnson.yml", "main/Cr/Johnson", JC74, None),
    "Ni": ("Nickel", "Ni_Johnson.yml", "main/Ni/Johnson", JC74, None),
    "Ti": ("Titanium", "Ti_Johnson.yml", "main/Ti/Johnson", JC74, None),
    "Pt": ("Platinum", "Pt_Rakic-LD.yml", "main/Pt/Rakic-LD",
           "A. D. Rakić, A. B. Djurišić, J. M. Elazar, M. L. Majewski, Appl. Opt. 37, 5271 (1998), "
           "doi:10.1364/AO.37.005271",
           "Lorentz-Drude model fitted to measured data, tabulated by refractiveindex.info; "
           "Werner 2009 (from REELS) not used: 8 points in 360-830 nm, R(0) 0.85-0.97 at 450-830 nm "
           "against 0.59-0.71 here"),
    "Fe": ("Iron", "Fe_Johnson.yml", "main/Fe/Johnson", JC74, None),
    "Zn": ("Zinc", "Zn_Werner.yml", "main/Zn/Werner",
           "W. S. M. Werner, K. Glantschnig, C. Ambrosch-Draxl, J. Phys. Chem. Ref. Data 38, 1013 (2009), "
           "doi:10.1063/1.3243762",
           "from REELS, coarse in the visible; Querry 1987 (CRDEC-CR-88009) not used: its n (9-14) > k "
           "(1.3-6.5) across the visible means Re(eps) > 0, which is not metallic"),
    "W": ("Tungsten", "W_Weaver.yml", "main/W/Weaver",
          "J. H. Weaver, C. G. Olson, D. W. Lynch, Phys. Rev. B 12, 1293 (1975), "
          "doi:10.1103/PhysRevB.12.1293", "points digitised from a figure"),
    "Pb": ("Lead", "Pb_Mathewson-298K.yml", "main/Pb/Mathewson-298K",
           "A. G. Mathewson, H. P. Myers, Phys. Scr. 4, 291 (1971), doi:10.1088/0031-8949/4/6/009",
           "298 K; data start at 344 nm"),
    "Brass": ("Brass (70% Cu, 30% Zn)", "Brass-Cu70Zn30_Querry.yml",
              "other/alloys/Cu-Zn/Querry-Cu70Zn30",
              "M. R. Querry, Optical constants, Contractor Report CRDC-CR-85034 (1985), "
              "https://apps.dtic.mil/sti/citations/ADA158623", None),
    "SS316": ("Austenitic stainless steel (Avesta 832 MV, similar to SS316)",
              "StainlessSteel-austenitic_Karlsson.yml",
              "other/alloys/stainless steel/Karlsson-austenitic",
              "B. Karlsson, C. G. Ribbing, J. Appl. Phys. 53, 6340 (1982), doi:10.1063/1.331503",
              "digitised from a figure"),
}

# key: (name, source file, page, citation, note or None)
DIELECTRICS = {
    "N-BK7": ("SCHOTT N-BK7 borosilicate crown", "N-BK7_SCHOTT.yml",
              "specs/schott/optical/N-BK7", SCHOTT, None),
    "N-SF11": ("SCHOTT N-SF11 dense flint", "N-SF11_SCHOTT.yml",
               "specs/schott/optical/N-SF11", SCHOTT, "formula valid from 370 nm only"),
    "fused-silica": ("Fused silica (SiO2 glass), 20 °C", "FusedSilica_Malitson.yml",
                     "main/SiO2/Malitson",
                     "I. H. Malitson, J. Opt. Soc. Am. 55, 1205 (1965), doi:10.1364/JOSA.55.001205",
                     None),
    "water": ("Distilled water, 20 °C", "Water_Daimon-20C.yml", "main/H2O/Daimon-20.0C",
              "M. Daimon, A. Masumura, Appl. Opt. 46, 3811 (2007), doi:10.1364/AO.46.003811",
              None),
    "diamond": ("Diamond", "Diamond_Peter.yml", "main/C/Peter",
                "F. Peter, Z. Phys. 15, 358 (1923), doi:10.1007/BF01330487",
                "formula valid to 760 nm; Prism extrapolates it to 830 nm"),
    "sapphire": ("Sapphire (Al2O3), ordinary ray, 20 °C", "Sapphire-o_Malitson.yml",
                 "main/Al2O3/Malitson-o",
                 "I. H. Malitson, M. J. Dodge, J. Opt. Soc. Am. 62, 1405 (1972); M. J. Dodge, "
                 "Handbook of Laser Science and Technology IV, CRC Press (1986), p. 30", None),
}

CONSTANTS = {
    "water-1.333": ("Water (constant n)", "1.333"),
    "ice-1.309": ("Ice (constant n)", "1.309"),
    "diamond-2.42": ("Diamond (constant n)", "2.42"),
}

CONVENTIONS = (
    "Wavelengths in nm in the metal tables and in range_nm. Metals: CSV wavelength_nm,n,k "
    "(complex index n + ik), interpolate linearly. Dielectrics: n^2(l) - 1 = A + sum_i "
    "B_i l^2 / (l^2 - C_i) with l in micrometres and C_i in micrometres^2 (A = 0 when absent); "
    "refractiveindex.info formula 1 poles are squared, formula 2 copied. range_nm is the "
    "validity range of the source; outside it Prism extrapolates. 'constant' is a "
    "wavelength-independent n.")


# ---------------------------------------------------------------- refractiveindex.info YAML subset

def parse_yaml(path):
    """Returns {"REFERENCES": str, "COMMENTS": str, "DATA": [{"type":..., ...}]}."""
    lines = [l.rstrip("\n") for l in path.read_text(encoding="utf-8").splitlines()]
    out, data, i = {}, [], 0
    indent = lambda l: len(l) - len(l.lstrip(" "))

    def block(i, min_indent):  # literal block: lines indented > min_indent (or blank)
        body = []
        while i < len(lines) and (not lines[i].strip() or indent(lines[i]) > min_indent):
            body.append(lines[i].strip())
            i += 1
        return "\n".join(b for b in body if b), i

    while i < len(lines):
        line = lines[i]
        if not line.strip() or line.startswith("#") or indent(line) > 0:
            i += 1
            continue
        key, _, value = line.partition(":")
        value = value.strip()
        i += 1
        if value == "|":
            out[key], i = block(i, 0)
        elif key == "DATA":
            while i < len(lines) and (not lines[i].strip() or indent(lines[i]) > 0):
                item = lines[i].strip()
                if item.startswith("- "):
                    data.append({})
                    item = item[2:]
                name, _, val = item.partition(":")
                i += 1
                if val.strip() == "|":
                    data[-1][name.strip()], i = block(i, indent(lines[i - 1]))
                elif name.strip():
                    data[-1][name.strip()] = val.strip()
        else:
            out[key] = value
    out["DATA"] = data
    return out


def entry(doc, kind):
    found = [d for d in doc["DATA"] if d.get("type") == kind]
    if len(found) != 1:
        raise SystemExit(f"expected one '{kind}' DATA entry, found {len(found)}")
    return found[0]


def check_doi(doc, citation, file):
    if "doi:" in citation:
        doi = citation.split("doi:")[1].split()[0].rstrip(",;")
        if doi not in doc.get("REFERENCES", ""):
            raise SystemExit(f"{file}: DOI {doi} not in its REFERENCES")


def um_to_nm(text):
    return Decimal(text).scaleb(3)


def fmt(d):
    return format(d, "f")


# ---------------------------------------------------------------- generation

def write_metal(source, here, key, spec):
    name, file, page, citation, note = spec
    doc = parse_yaml(source / "metals" / file)
    check_doi(doc, citation, file)
    rows = []
    for line in entry(doc, "tabulated nk")["data"].splitlines():
        lam, n, k = line.split()
        rows.append((um_to_nm(lam), n, k))
    rows.sort(key=lambda r: r[0])
    unique = [r for j, r in enumerate(rows) if j == 0 or r[0] != rows[j - 1][0]]
    if len(unique) != len(rows):
        print(f"note: {file}: dropped {len(rows) - len(unique)} repeated wavelength(s)")
    below = [r for r in unique if r[0] < LAMBDA_MIN][-1:]
    above = [r for r in unique if r[0] > LAMBDA_MAX][:1]
    kept = below + [r for r in unique if LAMBDA_MIN <= r[0] <= LAMBDA_MAX] + above
    comments = [
        f"{name}: complex refractive index n + ik.",
        f"Source: {citation}.",
        *( [f"Note: {note}."] if note else []),
        f"refractiveindex.info page {page} ({file}), {DATABASE}.",
        f"Licence: {LICENCE}.",
        f"Converted from µm to nm by import_refractiveindex.py (n, k unchanged); rows kept: "
        f"{LAMBDA_MIN}-{LAMBDA_MAX} nm plus the nearest row outside each end.",
    ]
    (here / "metals").mkdir(exist_ok=True)
    with open(here / "metals" / f"{key}.csv", "w", encoding="utf-8", newline="\n") as f:
        f.writelines(f"# {c}\n" for c in comments)
        f.write("wavelength_nm,n,k\n")
        f.writelines(f"{fmt(l)},{n},{k}\n" for l, n, k in kept)
    out = {"name": name, "nk": f"metals/{key}.csv", "range_nm": [kept[0][0], kept[-1][0]],
           "source": citation, "page": page}
    if note:
        out["note"] = note
    return out


def dielectric(source, spec):
    name, file, page, citation, note = spec
    doc = parse_yaml(source / "dielectrics" / file)
    check_doi(doc, citation, file)
    formula = [d for d in doc["DATA"] if d["type"] in ("formula 1", "formula 2")]
    if len(formula) != 1:
        raise SystemExit(f"{file}: expected one Sellmeier formula")
    c = [Decimal(x) for x in formula[0]["coefficients"].split()]
    B, C = c[1::2], c[2::2]
    if formula[0]["type"] == "formula 1":
        C = [x * x for x in C]  # formula 1 has poles C_i^2
    sellmeier = {"A": c[0]} if c[0] != 0 else {}
    sellmeier.update({"B": B, "C": C})
    lo, hi = formula[0]["wavelength_range"].split()
    out = {"name": name, "sellmeier": sellmeier, "range_nm": [um_to_nm(lo), um_to_nm(hi)],
           "source": citation, "page": page}
    if note:
        out["note"] = note
    return out


def to_json(value, level=0):
    """json.dumps, but Decimals keep their exact digits and short lists stay on one line."""
    pad = "  " * (level + 1)
    if isinstance(value, Decimal):
        return fmt(value.normalize())
    if isinstance(value, list):
        return "[" + ", ".join(to_json(v, level) for v in value) + "]"
    if isinstance(value, dict):
        inline = all(not isinstance(v, dict) for v in value.values()) and level >= 2
        items = [f"{json.dumps(k)}: {to_json(v, level + 1)}" for k, v in value.items()]
        if inline:
            return "{" + ", ".join(items) + "}"
        return "{\n" + ",\n".join(pad + i for i in items) + "\n" + "  " * level + "}"
    return json.dumps(value, ensure_ascii=False)


def generate(source, here):
    metals = {key: write_metal(source, here, key, spec) for key, spec in METALS.items()}
    dielectrics = {key: dielectric(source, spec) for key, spec in DIELECTRICS.items()}
    for key, (name, n) in CONSTANTS.items():
        dielectrics[key] = {"name": name, "constant": Decimal(n), "source": "common textbook value"}
    catalogue = {"_conventions": CONVENTIONS, "_source": f"{DATABASE}, {LICENCE}; generated by "
                 "import_refractiveindex.py", "metals": metals, "dielectrics": dielectrics}
    (here / "catalogue.json").write_text(to_json(catalogue) + "\n", encoding="utf-8")
    print(f"wrote {len(metals)} metal tables and catalogue.json "
          f"({len(dielectrics)} dielectrics) to {here}")


# ---------------------------------------------------------------- verification

FRAUNHOFER = {"F": 486.1327, "d": 587.5618, "C": 656.2725}  # nm
GLASS_REFERENCE = {"N-BK7": (1.51680, 64.17), "N-SF11": (1.78472, 25.68)}  # SCHOTT nd, Vd
R_REFERENCE = {"Cu": {550: 0.6235}, "Au": {450: 0.408, 550: 0.792, 650: 0.957},
               "Ag": {450: 0.980, 550: 0.983, 650: 0.990}}  # project tests, tolerance 3e-3


def sellmeier_n(entry, nm):
    if "constant" in entry:
        return entry["constant"]
    s, l2 = entry["sellmeier"], (nm / 1000) ** 2
    return (1 + s.get("A", 0) + sum(b * l2 / (l2 - c) for b, c in zip(s["B"], s["C"]))) ** 0.5


def read_nk(path):
    rows = [l for l in path.read_text(encoding="utf-8").splitlines() if l and l[0] != "#"]
    assert rows[0] == "wavelength_nm,n,k", path
    return [tuple(float(x) for x in r.split(",")) for r in rows[1:]]


def interp(rows, nm):
    for (l0, n0, k0), (l1, n1, k1) in zip(rows, rows[1:]):
        if l0 <= nm <= l1:
            t = (nm - l0) / (l1 - l0)
            return n0 + t * (n1 - n0), k0 + t * (k1 - k0)
    raise ValueError(f"{nm} nm outside the table")


def check(here):
    cat = json.loads((here / "catalogue.json").read_text(encoding="utf-8"))
    bad = []
    print("dielectric      nF        nd        nC        Vd")
    for key, e in cat["dielectrics"].items():
        n = {line: sellmeier_n(e, nm) for line, nm in FRAUNHOFER.items()}
        vd = (n["d"] - 1) / (n["F"] - n["C"]) if n["F"] != n["C"] else float("inf")
        verdict = ""
        if key in GLASS_REFERENCE:
            nd_ref, vd_ref = GLASS_REFERENCE[key]
            ok = abs(n["d"] - nd_ref) <= 1e-5 and abs(vd - vd_ref) <= 0.01
            verdict = f"  {'ok' if ok else 'DISAGREES'} (SCHOTT nd {nd_ref}, Vd {vd_ref})"
            if not ok:
                bad.append(key)
        print(f"{key:14s} {n['F']:.6f}  {n['d']:.6f}  {n['C']:.6f}  {vd:8.3f}{verdict}")
    print("\nmetal   lambda      n        k       R(0)")
    for key, e in cat["metals"].items():
        rows = read_nk(here / e["nk"])
        if rows[0][0] > LAMBDA_MIN or rows[-1][0] < LAMBDA_MAX:
            bad.append(f"{key} range")
            print(f"{key}: table covers only {rows[0][0]}-{rows[-1][0]} nm  DISAGREES")
        for nm in (450, 550, 650):
            n, k = interp(rows, nm)
            r = ((n - 1) ** 2 + k * k) / ((n + 1) ** 2 + k * k)
            ref = R_REFERENCE.get(key, {}).get(nm)
            verdict = "" if ref is None else f"  {'ok' if abs(r - ref) <= 3e-3 else 'DISAGREES'} (test {ref})"
            if ref is not None and abs(r - ref) > 3e-3:
                bad.append(f"{key} {nm}")
            print(f"{key:6s} {nm:4d} nm  {n:7.4f}  {k:7.4f}  {r:.4f}{verdict}")
    print("\nall reference values agree" if not bad else f"\nDISAGREEMENTS: {', '.join(bad)}")
    return not bad


def main(argv):
    here = Path(__file__).resolve().parent
    args = [a for a in argv if a != "--check"]
    if len(args) > 1 or (not args and "--check" not in argv):
        raise SystemExit(__doc__)
    if args:
        generate(Path(args[0]), here)
    if "--check" in argv and not check(here):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
