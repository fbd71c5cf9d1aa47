#!/usr/bin/env python3
"""Includes point down only (README, Layout): a file includes its own folder or a lower layer.

vm:          core <- asm, io <- engines <- reference, mesh, translate <- gl (the gl engine runs the translation), capi (the C library)
irradiance:  io <- sh <- render <- report <- jobs <- mesh_input, gpu (the GPU frame, over vm/gl)
tools:       vm/cli (vs11) <- irradiance/cli (irrmap, which shares vs11's command-line parse)
python:      the Python module, over the vm and irradiance libraries (not the tools, not vm/mesh)
The irradiance library sits above vm's library folders (core, asm, io, engines, reference); only irrmap's mesh
reader (irradiance/mesh_input) reaches vm/mesh, only the tools and irradiance/gpu reach vm/gl (they register the gl engine
with vm/engines' factory, which cannot include it); the vs11 tool (vm/cli) includes no irradiance folder
(its link line is checked by tests/ci/vs11_link_test.py).
Folders on the same layer (asm and io; reference, mesh and translate) do not include each other.
Usage: include_layers_test.py SOURCE_DIR. Prints each violation as file:line and exits 1 on any.
"""
import pathlib
import re
import sys

# (folder, layer): a file may include from folders of a lower layer, or from its own folder.
LAYERS = {
    "vm/core": 0, "vm/ir": 1, "vm/asm": 1, "vm/io": 1, "vm/engines": 2, "vm/reference": 3, "vm/mesh": 3, "vm/translate": 3, "vm/gl": 4, "vm/capi": 4,
    "irradiance/io": 5, "irradiance/sh": 6, "irradiance/render": 7, "irradiance/report": 8,
    "irradiance/jobs": 9, "irradiance/mesh_input": 10, "irradiance/gpu": 10, "vm/cli": 11, "irradiance/cli": 12,
    "python": 13,
}
# The Python module binds the libraries only: what the tools do is theirs.
NOT_FROM = {"python": {"vm/cli", "irradiance/cli", "irradiance/mesh_input"},
            # The C library (libvs11c) is the machine alone.
            "vm/capi": {folder for folder in LAYERS if folder.startswith("irradiance/")},
            # The VM tool needs nothing of irradiance: what it verifies is vm/reference's.
            "vm/cli": {folder for folder in LAYERS if folder.startswith("irradiance/")}}
# Exceptions to "any lower layer": vm/mesh is below the irradiance library's layers but only
# mesh_input and the tools may use it (vs11_irradiance is installed without Assimp).
# vm/gl (EGL, GLES) likewise: the irradiance library and the Python module are built without it.
ONLY_FROM = {"vm/mesh": {"vm/mesh", "irradiance/mesh_input", "irradiance/cli", "vm/cli"},
             "vm/gl": {"vm/gl", "irradiance/gpu", "irradiance/cli", "vm/cli"},
             "irradiance/gpu": {"irradiance/gpu", "irradiance/cli"}}
INCLUDE = re.compile(r'^\s*#\s*include\s+"((?:vm|irradiance)/[^"]+)"')


def folder_of(path: str):
    for folder in sorted(LAYERS, key=len, reverse=True):
        if path.startswith(folder + "/"):
            return folder
    return None


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    violations = []
    checked = 0
    for top in ("vm", "irradiance", "python"):
        for source in sorted((root / top).rglob("*")):
            if source.suffix not in (".h", ".cc"):
                continue
            relative = source.relative_to(root).as_posix()
            here = folder_of(relative)
            if here is None:
                violations.append(f"{relative}: in no folder of the layering (add it to LAYERS)")
                continue
            checked += 1
            for number, line in enumerate(source.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                target = folder_of(match.group(1))
                if target is None:
                    violations.append(f"{relative}:{number}: includes {match.group(1)}, in no known folder")
                elif target != here and (LAYERS[target] >= LAYERS[here] or
                                         here not in ONLY_FROM.get(target, {here}) or
                                         target in NOT_FROM.get(here, set())):
                    violations.append(f"{relative}:{number}: {here} (layer {LAYERS[here]}) includes "
                                      f"{match.group(1)} ({target}, layer {LAYERS[target]}): includes point down only")
    for violation in violations:
        print(violation)
    print(f"include layers: {checked} files checked, {len(violations)} violations")
    return 1 if violations or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
