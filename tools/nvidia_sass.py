#!/usr/bin/env python3
"""The machine code NVIDIA's Vulkan driver builds from octrace's pipelines.

Nsight Compute does not see Vulkan dispatches (optimisation log 31) and the
driver's pipeline statistics (`render --pipeline-stats`) give registers and
sizes only. This reads the code itself, in two steps:

  1. On the GPU machine, `octrace render ...` with
     OCTRACE_DUMP_PIPELINE_CACHE=FILE set writes the Vulkan pipeline cache's
     data (vkGetPipelineCacheData) to FILE at exit: every pipeline the render
     built.
  2. tools/nvidia_sass.py unpack FILE DIR
     The NVIDIA driver's cache data holds each pipeline as a zstd frame
     (zstandard: Debian's python3-zstandard) whose content starts "NVDA"
     "NVVM", then the driver's shader object ("NVuc"), a table of sections
     (sections() below). Writes the code section of each as
     DIR/pipeline_N.code and prints its size, registers and local memory.
     (Where the GPU machine's python cannot import zstandard, as its 3.12
     could not with Debian 12's package in session 36, bring FILE back and
     unpack it here; step 3 needs only the .code files.)
  3. tools/nvidia_sass.py disasm DIR --nvdisasm PATH [--arch SM90]
     nvdisasm -b ARCH (raw code) on each .code file -> DIR/pipeline_N.sass,
     on the GPU machine (nvdisasm comes with the CUDA toolkit). Where
     nvdisasm fails on a file, the tool stops with its error (exit 2) and
     removes the .sass files it wrote.
  4. tools/nvidia_sass.py stats FILE.sass[.gz] ...
     Counts per file: instructions, global loads and stores, local memory
     (the walks' stacks), shared memory, branches, convergence barriers,
     floating-point operations.

The layout of the driver's object is not documented; what this relies on
(zstd frames, the section table) was found on the H200 with driver
580.159.04 (optimisation log 58, docs/results/h200/session17/). Bad input
exits with 2.
"""
import argparse
import gzip
import os
import re
import subprocess
import zlib

import tool_args

ZSTD_MAGIC = bytes.fromhex("28b52ffd")


def fail(message):
    tool_args.fail("nvidia_sass.py", message)


def sections(obj):
    """The NVuc object's section table: six words for each section, the
    first three its type, size and offset.
    Header (32 bytes): "NVuc", a version, the section count (16 bits at
    byte 8), the object's size at byte 24; then one 32-byte entry per
    section: type, size, offset, and three more words (32 bits each).
    Types seen: 1 the code, 3 the register count, 0x15 local memory (the
    walks' stacks: its bytes per invocation in the entry's fifth word)."""
    count = int.from_bytes(obj[8:10], "little")
    out = []
    for i in range(count):
        e = obj[32 + 32 * i:32 + 32 * (i + 1)]
        out.append(tuple(int.from_bytes(e[4 * k:4 * k + 4], "little") for k in range(6)))
    return out


def unpack(cache, out_dir):
    try:
        import zstandard
    except ImportError:
        fail("unpack needs the zstandard module (Debian: python3-zstandard; tools/setup.sh installs it)")

    data = open(cache, "rb").read()
    n = 0
    at = data.find(ZSTD_MAGIC)
    while at >= 0:
        try:
            obj = zstandard.ZstdDecompressor().decompressobj().decompress(data[at:])
        except zstandard.ZstdError:
            obj = b""
        at_uc = obj.find(b"NVuc")
        if obj.startswith(b"NVDA") and at_uc >= 0:
            uc = obj[at_uc:]
            secs = sections(uc)
            code = [e for e in secs if e[0] == 1]
            if code:
                size, offset = code[0][1], code[0][2]
                os.makedirs(out_dir, exist_ok=True)
                path = os.path.join(out_dir, f"pipeline_{n}.code")
                open(path, "wb").write(uc[offset:offset + size])
                regs = [int.from_bytes(uc[e[2]:e[2] + 4], "little") for e in secs if e[0] == 3 and e[1] >= 4]
                lmem = [e[4] for e in secs if e[0] == 0x15]
                print(f"{path}: {size // 16} instructions, registers {regs[0] if regs else '?'}, "
                      f"local memory {lmem[0] if lmem else 0} bytes")
                n += 1
        at = data.find(ZSTD_MAGIC, at + 1)
    if n == 0:
        fail(f"{cache}: no driver shader object in it (not an NVIDIA pipeline cache?)")


def disasm(out_dir, nvdisasm, arch):
    if not os.path.isdir(out_dir):
        fail(f"{out_dir}: no such folder")
    codes = sorted(f for f in os.listdir(out_dir) if f.endswith(".code"))
    if not codes:
        fail(f"{out_dir}: no .code files (run unpack first)")
    written = []
    for f in codes:
        src = os.path.join(out_dir, f)
        dst = src[:-len(".code")] + ".sass"
        p = subprocess.run([nvdisasm, "-b", arch, src], capture_output=True, text=True)
        if p.returncode != 0:
            for done in written:
                os.remove(done)  # no half set of .sass files
            fail(f"{nvdisasm} -b {arch} {src}: exit {p.returncode}: {tool_args.last_line(p.stderr, 'no message')}")
        open(dst, "w").write(p.stdout)
        written.append(dst)
        print(f"{dst}: nvdisasm exit {p.returncode}, {p.stdout.count(chr(10))} lines"
              + (f" ({p.stderr.strip()[:200]})" if p.returncode else ""))


# An instruction line: its address, an optional predicate, the opcode.
INSTRUCTION = re.compile(r"/\*[0-9a-f]{4,}\*/\s+(?:@!?U?P\w+\s+)?([A-Z][A-Z0-9_]*)")
CLASSES = [
    ("global loads", lambda op, line: op == "LDG"),
    ("global stores", lambda op, line: op == "STG"),
    ("local loads", lambda op, line: op == "LDL"),
    ("local stores", lambda op, line: op == "STL"),
    ("shared", lambda op, line: op in ("LDS", "STS", "ATOMS")),
    ("constant loads", lambda op, line: op in ("LDC", "ULDC")),
    ("branches", lambda op, line: op in ("BRA", "BRX", "JMP", "CALL", "RET")),
    ("convergence barriers", lambda op, line: op in ("BSSY", "BSYNC", "WARPSYNC", "BMOV")),
    ("float ops", lambda op, line: op.startswith(("FADD", "FMUL", "FFMA", "FMNMX", "FSET", "FSEL", "MUFU", "HFMA2"))),
    # A descriptor's range is read from constant bank 0: an integer compare
    # against it is a bounds check of a buffer access (log 58).
    ("bounds compares", lambda op, line: op == "ISETP" and "c[0x0][" in line),
]


def stats(files):
    for f in files:
        if not os.path.isfile(f):
            fail(f"{f}: no such file")
    rows = []  # every file is counted before the table starts, so that a bad one leaves no half table
    for f in files:
        counts = [0] * len(CLASSES)
        total = 0
        try:
            with (gzip.open(f, "rt") if f.endswith(".gz") else open(f)) as text:
                for line in text:
                    m = INSTRUCTION.search(line)
                    if not m:
                        continue
                    total += 1
                    for i, (_, test) in enumerate(CLASSES):
                        if test(m.group(1), line):
                            counts[i] += 1
        except (OSError, EOFError, zlib.error) as e:  # gzip's BadGzipFile is an OSError
            fail(f"{f}: not readable{' gzip' if f.endswith('.gz') else ''} text ({e})")
        except UnicodeDecodeError:
            fail(f"{f}: not text (nvdisasm's output, a .sass or .sass.gz file)")
        rows.append(f"| {os.path.basename(f)} | {total} | " + " | ".join(str(c) for c in counts) + " |")
    print("| file | instructions | " + " | ".join(c for c, _ in CLASSES) + " |")
    print("|---|" + "---:|" * (len(CLASSES) + 1))
    for row in rows:
        print(row)


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    u = sub.add_parser("unpack", help="the pipelines' code out of a pipeline cache dump")
    u.add_argument("cache")
    u.add_argument("out_dir")
    d = sub.add_parser("disasm", help="nvdisasm on every .code file of a folder")
    d.add_argument("out_dir")
    d.add_argument("--nvdisasm", type=tool_args.executable, default="nvdisasm")
    d.add_argument("--arch", default="SM90")
    s = sub.add_parser("stats", help="instruction counts of .sass files")
    s.add_argument("files", nargs="+")
    a = ap.parse_args()
    if a.cmd == "unpack":
        if not os.path.isfile(a.cache):
            fail(f"{a.cache}: no such file")
        if os.path.exists(a.out_dir) and not os.path.isdir(a.out_dir):
            fail(f"{a.out_dir}: is a file, not a folder")
        unpack(a.cache, a.out_dir)
    elif a.cmd == "disasm":
        disasm(a.out_dir, a.nvdisasm, a.arch)
    else:
        stats(a.files)


if __name__ == "__main__":
    main()
