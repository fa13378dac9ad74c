#!/usr/bin/env python3
"""The universal bundle (resources/bundle.sh all): one zip with one folder
PlungeRough/, the addon once and every platform's program in its own folder,
PlungeRough/bin/OS-ARCH/plunge-rough[.exe] with its build-info.txt; and
beside that folder a package.xml that leads FreeCAD to it.

FreeCAD's Addon Manager installs a release zip (a catalogue entry's zip_url)
by unpacking it as it is into Mod/PlungeRough/: the addon would end up one
folder too deep, in Mod/PlungeRough/PlungeRough/, where FreeCAD does not look.
FreeCAD (0.20 and later) reads Mod/<folder>/package.xml first and runs the
Init.py of each workbench's <subdirectory>: the outer package.xml (the
addon's own, its subdirectory and icon one folder down) makes that folder
PlungeRough/. Unzipped by hand into Mod, the zip gives Mod/PlungeRough/ as
before, and a package.xml in Mod that FreeCAD passes over.

    python3 resources/universal_zip.py OUT.zip OS-ARCH=PLATFORM.zip...

Each platform's zip (dist/PlungeRough-OS-ARCH.zip) gives its program and
build-info.txt from PlungeRough/bin/; everything else must be the same in all
of them (the same checkout built them) and is taken once. Entries are written
in the platform zips' order (a folder's files, then its folders, by name),
with their dates and modes (the execute bit) as there, so the same zips make
the same universal zip."""
import os
import re
import sys
import zipfile

BIN = "PlungeRough/bin/"
PROGRAM_FILES = ("plunge-rough", "plunge-rough.exe", "build-info.txt")


def outer_package(inner):
    """The addon's package.xml as seen from the folder above it: its
    workbench's subdirectory and its icon in PlungeRough/."""
    text = inner.decode("utf-8")
    text, subdirectories = re.subn(r"<subdirectory>\./?</subdirectory>", "<subdirectory>./PlungeRough</subdirectory>",
                                   text)
    text, icons = re.subn(r"<icon>([^<]+)</icon>", r"<icon>PlungeRough/\1</icon>", text)
    if subdirectories != 1 or icons != 1:
        raise ValueError("PlungeRough/package.xml: expected one <subdirectory>./</subdirectory> and one <icon>")
    return text.encode("utf-8")


def walk_order(name):
    """The order bundle.sh writes a platform's zip in (os.walk, sorted): a
    folder's files, then its folders."""
    parts = name.split("/")
    return [(1, p) for p in parts[:-1]] + [(0, parts[-1])]


def main(argv):
    if len(argv) < 3 or not all("=" in a for a in argv[2:]):
        print("usage: universal_zip.py OUT.zip OS-ARCH=PLATFORM.zip...", file=sys.stderr)
        return 2
    out = argv[1]
    entries = {}  # name in the universal zip -> (ZipInfo, bytes)
    common = None  # the addon's files, from the first platform's zip
    for arg in argv[2:]:
        name, path = arg.split("=", 1)
        if not os.path.isfile(path):
            print("universal_zip: %s: no %s" % (name, path), file=sys.stderr)
            return 1
        programs, addon = [], {}
        with zipfile.ZipFile(path) as z:
            for info in z.infolist():
                data = z.read(info)
                if info.filename.startswith(BIN) and info.filename[len(BIN):] in PROGRAM_FILES:
                    programs.append(info.filename[len(BIN):])
                    entries[BIN + name + "/" + info.filename[len(BIN):]] = (info, data)
                elif info.filename.startswith(BIN) and "/" in info.filename[len(BIN):]:
                    print("universal_zip: %s holds %s: a platform zip has no folder in bin/" % (path, info.filename),
                          file=sys.stderr)
                    return 1
                else:
                    addon[info.filename] = (info, data)
        if "build-info.txt" not in programs or not {"plunge-rough", "plunge-rough.exe"} & set(programs):
            print("universal_zip: %s: no program and build-info.txt in %s" % (path, BIN), file=sys.stderr)
            return 1
        if common is None:
            common = addon
        else:
            differ = sorted(n for n in set(common) | set(addon)
                            if n not in common or n not in addon or common[n][1] != addon[n][1])
            if differ:
                print("universal_zip: %s is not the same addon as %s (built from another checkout?): %s" % (
                    path, argv[2].split("=", 1)[1], ", ".join(differ[:5])), file=sys.stderr)
                return 1
    entries.update(common)
    inner, data = entries["PlungeRough/package.xml"]
    entries["package.xml"] = (inner, outer_package(data))
    with zipfile.ZipFile(out + ".part", "w", zipfile.ZIP_DEFLATED) as z:
        for name in sorted(entries, key=walk_order):
            info, data = entries[name]
            copy = zipfile.ZipInfo(name, date_time=info.date_time)
            copy.external_attr = info.external_attr  # the execute bit
            copy.create_system = info.create_system
            copy.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(copy, data)
    os.replace(out + ".part", out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
