#!/usr/bin/env python3
"""Static checks of the macOS bundles' programs (resources/bundle.sh), which
nothing on this Debian machine can run: binutils does not read Mach-O, so the
load commands are read here.

    python3 resources/macho_check.py PROGRAM arm64|x86_64

Checks: a 64-bit Mach-O executable (magic 0xFEEDFACF, MH_EXECUTE) for the CPU
(arm64 0x0100000C, x86_64 0x01000007) with an entry point (LC_MAIN); every
library it loads (LC_LOAD_DYLIB and its weak, re-export, lazy and upward
kinds) under /usr/lib/, that is macOS's own, none from Homebrew or a build
folder; and on arm64 an embedded code signature (LC_CODE_SIGNATURE, 0x1D;
Apple silicon runs nothing unsigned, the ad-hoc signature that the linker
makes is enough) whose blob is inside the file and starts with the
signature super-blob's magic. Prints what it found, one line; exits 1 naming
each failed check.

tests/python/test_portable.py uses check() on the bundles' programs."""
import struct
import sys

MH_MAGIC_64 = 0xFEEDFACF
MH_EXECUTE = 0x2
CPU = {"arm64": 0x0100000C, "x86_64": 0x01000007}
LC_REQ_DYLD = 0x80000000
DYLIB_COMMANDS = {0xC: "LC_LOAD_DYLIB", 0x18 | LC_REQ_DYLD: "LC_LOAD_WEAK_DYLIB",
                  0x1F | LC_REQ_DYLD: "LC_REEXPORT_DYLIB", 0x20: "LC_LAZY_LOAD_DYLIB",
                  0x23 | LC_REQ_DYLD: "LC_LOAD_UPWARD_DYLIB"}
LC_CODE_SIGNATURE = 0x1D
LC_MAIN = 0x28 | LC_REQ_DYLD
LC_BUILD_VERSION = 0x32
CSMAGIC_EMBEDDED_SIGNATURE = 0xFADE0CC0  # big-endian, as all of the signature


def read(path):
    """What the load commands say: {"cputype", "filetype", "dylibs", "signature", "main", "minos"}."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 32:
        raise ValueError("%s: %d bytes, too short for a Mach-O header" % (path, len(data)))
    magic, cputype, _, filetype, ncmds, sizeofcmds, _, _ = struct.unpack_from("<IiiIIIII", data, 0)
    info = {"magic": magic, "cputype": cputype & 0xFFFFFFFF, "filetype": filetype, "dylibs": [],
            "signature": None, "main": False, "minos": None, "size": len(data)}
    if magic != MH_MAGIC_64:
        return info
    at = 32
    if 32 + sizeofcmds > len(data):
        raise ValueError("%s: load commands past the end of the file" % path)
    for _ in range(ncmds):
        cmd, cmdsize = struct.unpack_from("<II", data, at)
        if cmdsize < 8 or at + cmdsize > 32 + sizeofcmds:
            raise ValueError("%s: a load command of size %d at %d" % (path, cmdsize, at))
        if cmd in DYLIB_COMMANDS:
            offset = struct.unpack_from("<I", data, at + 8)[0]
            name = data[at + offset:at + cmdsize].split(b"\0", 1)[0].decode("utf-8", "replace")
            info["dylibs"].append((DYLIB_COMMANDS[cmd], name))
        elif cmd == LC_CODE_SIGNATURE:
            info["signature"] = struct.unpack_from("<II", data, at + 8)  # dataoff, datasize
        elif cmd == LC_MAIN:
            info["main"] = True
        elif cmd == LC_BUILD_VERSION:
            minos = struct.unpack_from("<I", data, at + 12)[0]
            info["minos"] = "%d.%d" % (minos >> 16, (minos >> 8) & 0xFF)
        at += cmdsize
    if info["signature"]:
        off, size = info["signature"]
        ok = size >= 12 and off + size <= len(data) and struct.unpack_from(">I", data, off)[0] == CSMAGIC_EMBEDDED_SIGNATURE
        info["signature_ok"] = ok
    return info


def check(path, arch):
    """The failed checks of PROGRAM for ARCH (arm64 or x86_64), and what was read."""
    if arch not in CPU:
        raise ValueError("arch: arm64 or x86_64, not %r" % arch)
    info = read(path)
    problems = []
    if info["magic"] != MH_MAGIC_64:
        problems.append("not a 64-bit Mach-O file (magic 0x%08X, not 0x%08X)" % (info["magic"], MH_MAGIC_64))
        return problems, info
    if info["cputype"] != CPU[arch]:
        problems.append("CPU type 0x%08X, not %s's 0x%08X" % (info["cputype"], arch, CPU[arch]))
    if info["filetype"] != MH_EXECUTE:
        problems.append("file type %d, not an executable (MH_EXECUTE, 2)" % info["filetype"])
    if not info["main"]:
        problems.append("no entry point (LC_MAIN)")
    if not info["dylibs"]:
        problems.append("loads no library: not even libSystem")
    for kind, name in info["dylibs"]:
        if not name.startswith("/usr/lib/"):
            problems.append("%s %s: not one of macOS's own libraries (/usr/lib/)" % (kind, name))
    if arch == "arm64":
        if not info["signature"]:
            problems.append("no code signature (LC_CODE_SIGNATURE): Apple silicon runs nothing unsigned")
        elif not info["signature_ok"]:
            problems.append("LC_CODE_SIGNATURE points at no signature blob (offset %d, %d bytes)" % info["signature"])
    return problems, info


def main(argv):
    if len(argv) != 3 or argv[2] not in CPU:
        print("usage: macho_check.py PROGRAM arm64|x86_64", file=sys.stderr)
        return 2
    path, arch = argv[1], argv[2]
    try:
        problems, info = check(path, arch)
    except (OSError, ValueError, struct.error) as e:
        print("macho_check: %s" % e, file=sys.stderr)
        return 1
    for p in problems:
        print("macho_check: %s: %s" % (path, p), file=sys.stderr)
    if problems:
        return 1
    print("macho_check: %s: Mach-O %s executable, macOS %s or later, loads %s%s" % (
        path, arch, info["minos"] or "?", ", ".join(name for _, name in info["dylibs"]),
        ", signed (ad hoc or better)" if info["signature"] else ", unsigned"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
