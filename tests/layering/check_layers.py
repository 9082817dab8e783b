#!/usr/bin/env python3
"""Checks the framework's layering on the include graph.

Each library of framework/ (sdk, safeio, formats, render, host, app) may
include headers of its own layer and of the layers below it only; plugins
include the SDK (and the libraries their CMakeLists.txt links, passed as
--plugin-extra NAME=LAYER). Also checks that the folders
(esif/core/, esif/run/, ...) include each other without a cycle. Prints every
upward edge as `file: includes esif/<folder>/ (layer A -> layer B)` and every
cycle, and exits 1 if there is any.
The CMake target links enforce the same at build time; this check also covers
a header that is on the include path through a transitive PUBLIC link.
"""
import argparse
import os
import re
import sys

LAYERS = ["sdk", "safeio", "formats", "render", "host", "app"]
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]esif/(\w+)/')


def header_layers(framework):
    """Maps each esif/<folder>/ include prefix to the layer that owns it."""
    owner = {}
    for layer in LAYERS:
        root = os.path.join(framework, layer, "include", "esif")
        if not os.path.isdir(root):
            continue
        for folder in os.listdir(root):
            if folder in owner:
                sys.exit(f"esif/{folder}/ is public in both {owner[folder]} and {layer}")
            owner[folder] = layer
    return owner


def sources(root):
    """The library's or plugin's own sources. Its tests/ folder is left out:
    tests link esif::host and may use any layer (a simulated rawlog, the
    host's replay) to exercise a lower one."""
    for dirpath, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d != "tests"]
        for f in sorted(files):
            if f.endswith((".h", ".cpp")):
                yield os.path.join(dirpath, f)


def upward_edges(path, layer, allowed, owner):
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = INCLUDE.match(line)
            if not m:
                continue
            target = owner.get(m.group(1))
            if target is None:
                yield f"{path}: includes esif/{m.group(1)}/, which no layer owns"
            elif target not in allowed:
                yield f"{path}: includes esif/{m.group(1)}/ ({layer} -> {target})"


def folder_of(path, framework):
    """The esif/<folder>/ a source belongs to: its public folder, or the one
    its src/ subfolder or its library is named after."""
    parts = os.path.relpath(path, framework).split(os.sep)
    if "include" in parts:
        return parts[parts.index("include") + 2]
    if parts[1] == "src" and len(parts) > 3:
        return parts[2]
    return parts[0]


def folder_cycles(framework):
    edges = {}
    for path in sources(framework):
        src = folder_of(path, framework)
        with open(path, encoding="utf-8", errors="replace") as f:
            for line in f:
                m = INCLUDE.match(line)
                if m and m.group(1) != src:
                    edges.setdefault(src, set()).add(m.group(1))
    cycles, state = [], {}

    def visit(node, stack):
        state[node] = "open"
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == "open":
                cycles.append(" -> ".join(stack[stack.index(nxt):] + [node, nxt]) if nxt in stack
                              else f"{node} -> {nxt}")
            elif nxt not in state:
                visit(nxt, stack + [node])
        state[node] = "done"

    for node in sorted(edges):
        if node not in state:
            visit(node, [])
    return [f"folder include cycle: {c}" for c in cycles]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source_dir")
    parser.add_argument("--plugin-extra", action="append", default=[],
                        help="PLUGIN=LAYER: a plugin that also links LAYER")
    args = parser.parse_args()
    framework = os.path.join(args.source_dir, "framework")
    plugins = os.path.join(args.source_dir, "plugins")
    owner = header_layers(framework)
    errors = []
    for i, layer in enumerate(LAYERS):
        allowed = set(LAYERS[: i + 1])
        for path in sources(os.path.join(framework, layer)):
            errors += upward_edges(path, layer, allowed, owner)
    extra = dict(e.split("=", 1) for e in args.plugin_extra)
    for name in sorted(os.listdir(plugins)):
        folder = os.path.join(plugins, name)
        if not os.path.isdir(folder):
            continue
        allowed = {"sdk"} | set(LAYERS[: LAYERS.index(extra[name]) + 1] if name in extra else [])
        for path in sources(folder):
            errors += upward_edges(path, f"plugin {name}", allowed, owner)
    errors += folder_cycles(framework)
    for e in errors:
        print(e)
    print(f"{len(errors)} layering errors" if errors else "layering holds: no upward include edge, no folder cycle")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
