#!/usr/bin/env python3
"""Checks what every built plugin module links: of the framework's libraries,
the SDK alone (libesif_sdk.so). A plugin that linked esif::formats or a
higher layer would map MRPT's OpenGL, vision and OpenCV libraries into every
run that loads it, and could read files behind the host's back.

Usage: check_plugin_links.py PLUGIN_DIR
Reads each libesif_plugin_*.so's DT_NEEDED entries with `readelf -d`
(binutils, installed with the compiler), prints every framework library
other than the SDK that a plugin needs, and exits 1 if there is any (or if
no plugin module is found, which would make the check pass vacuously).
"""
import glob
import os
import re
import subprocess
import sys

ALLOWED = {"libesif_sdk.so"}
NEEDED = re.compile(r"\(NEEDED\)\s+Shared library: \[(.+)\]")


def needed(path):
    out = subprocess.run(["readelf", "-d", path], check=True, capture_output=True, text=True).stdout
    return NEEDED.findall(out)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    modules = sorted(glob.glob(os.path.join(sys.argv[1], "libesif_plugin_*.so")))
    if not modules:
        sys.exit(f"{sys.argv[1]}: no plugin module (libesif_plugin_*.so) found")
    bad = 0
    for module in modules:
        libs = needed(module)
        framework = [lib for lib in libs if lib.startswith("libesif_")]
        extra = [lib for lib in framework if lib not in ALLOWED]
        for lib in extra:
            print(f"{os.path.basename(module)}: needs {lib} (plugins link the SDK only)")
        bad += len(extra)
        if "libesif_sdk.so" not in framework:
            print(f"{os.path.basename(module)}: does not need libesif_sdk.so (is it a plugin?)")
            bad += 1
    print(f"{len(modules)} plugin modules checked")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
