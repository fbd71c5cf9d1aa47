#!/usr/bin/env python3
"""The vs11 tool links no irradiance library and no image library (README, Layout).

vs11 is the VM's tool: everything it runs is in vm/ (vm/reference holds the programs' references and
`verify`). This reads the link command CMake generated for target vs11 (Ninja's build.ninja, or the
Makefile generators' link.txt) rather than asking ldd, because the image module is dlopen'ed and a
static library leaves no trace in the binary's dynamic section.
Usage: vs11_link_test.py BUILD_DIR. Exits 1 when the link line names a forbidden library, 77 (skip)
when the build folder holds no link command for vs11 (another generator).
"""
import pathlib
import re
import sys

FORBIDDEN = ("vs11_irradiance", "OpenImageIO", "vs11_image_io", "libOpenImageIO")


def ninja_link_line(build_dir: pathlib.Path):
    ninja = build_dir / "build.ninja"
    if not ninja.exists():
        return None
    lines = ninja.read_text().splitlines()
    for index, line in enumerate(lines):
        # "build <build>/vm/vs11: CXX_EXECUTABLE_LINKER__vs11_Release <objects> | <implicit deps> || <order-only>"
        if re.match(r"^build vm/vs11: CXX_EXECUTABLE_LINKER__vs11_", line):
            block = [line]
            for following in lines[index + 1:]:
                if not following.startswith("  "):
                    break
                block.append(following)
            return "\n".join(block)
    return None


def makefile_link_line(build_dir: pathlib.Path):
    link = build_dir / "vm" / "CMakeFiles" / "vs11.dir" / "link.txt"
    return link.read_text() if link.exists() else None


def main() -> int:
    build_dir = pathlib.Path(sys.argv[1])
    text = ninja_link_line(build_dir) or makefile_link_line(build_dir)
    if text is None:
        print(f"no link command for vs11 in {build_dir} (neither build.ninja nor vm/CMakeFiles/vs11.dir/link.txt)")
        return 77
    # Ninja's build statement names the libraries as inputs ("| <build>/irradiance/libvs11_irradiance.a") and the
    # LINK_LIBRARIES variable names them on the command line; both count.
    found = sorted({name for name in FORBIDDEN if name in text})
    if found:
        print(f"vs11's link command names {', '.join(found)}: the VM tool must not link the irradiance "
              f"library or an image library (vm/CMakeLists.txt)")
        return 1
    if "vs11_vm" not in text:
        print("vs11's link command names no vs11_vm: this test no longer reads the right command")
        return 1
    print("vs11 links neither vs11_irradiance nor an image library")
    return 0


if __name__ == "__main__":
    sys.exit(main())
