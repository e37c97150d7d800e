#!/usr/bin/env python3
"""Builds Prism's CIE tables (data/cie/*.csv) from the CIE's published CSV files.

Usage: import_cie.py SOURCE_DIR   (the folder holding CIE_xyz_1931_2deg.csv and
CIE_std_illum_D65.csv as published by the CIE; see data/README.md for DOIs).
Values are copied verbatim; only the range is cut to Prism's 360-830 nm.
"""
import csv
import sys
from pathlib import Path

LAMBDA_MIN, LAMBDA_MAX = 360, 830


def read_rows(path):
    with open(path, newline="") as f:
        for row in csv.reader(f):
            try:
                wavelength = int(float(row[0]))
            except ValueError:
                continue  # header line added by some redistributions
            if LAMBDA_MIN <= wavelength <= LAMBDA_MAX:
                yield [wavelength] + [cell.strip() for cell in row[1:]]


def write_table(path, header_comment, columns, rows):
    with open(path, "w", newline="\n") as f:
        for line in header_comment:
            f.write(f"# {line}\n")
        f.write(",".join(columns) + "\n")
        for row in rows:
            f.write(",".join(str(cell) for cell in row) + "\n")


def main():
    source = Path(sys.argv[1])
    here = Path(__file__).resolve().parent
    licence = "Licence: CC BY-SA 4.0, (c) International Commission on Illumination (CIE), Vienna, Austria."
    write_table(
        here / "cie1931_2deg_xyz.csv",
        ["CIE 1931 2-degree colour-matching functions xbar, ybar, zbar, 1 nm steps, 360-830 nm.",
         "Source: CIE 018:2019 Table 6, doi:10.25039/CIE.DS.xvudnb9b (values unchanged).",
         licence],
        ["wavelength_nm", "xbar", "ybar", "zbar"],
        read_rows(source / "CIE_xyz_1931_2deg.csv"))
    write_table(
        here / "cie_d65.csv",
        ["CIE standard illuminant D65, relative spectral power distribution, 1 nm steps, 360-830 nm.",
         "Source: ISO/CIE 11664-2:2022 Table B.1, doi:10.25039/CIE.DS.hjfjmt59 (values unchanged).",
         licence],
        ["wavelength_nm", "relative_power"],
        read_rows(source / "CIE_std_illum_D65.csv"))


if __name__ == "__main__":
    main()
