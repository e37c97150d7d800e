#!/usr/bin/env python3
"""Where the shared developer assets are: the Khronos sample scenes (assets/gltf), the Blender
Cycles harness (tools/cycles) and the Embree yardstick (tools/raybench).

One setting names the folder: the environment variable PRISM_SHARED_DIR. Without it, the folder
`shared` beside the project's root (`../shared` from the root). Prism never needs the folder to
build or to pass its tests; the tools that need it say so and skip.

    python3 tools/shared_dir.py        # prints the folder's path

The Python tools import shared_dir() from here; shell scripts read ${PRISM_SHARED_DIR} and fall
back to running this file.
"""
import os
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent  # the project's root


def shared_dir():
    """The shared assets' folder (a pathlib.Path; it may not exist)."""
    value = os.environ.get("PRISM_SHARED_DIR")
    if value:
        return pathlib.Path(value).expanduser().absolute()
    return ROOT.parent / "shared"


if __name__ == "__main__":
    print(shared_dir())
    sys.exit(0)
