#!/usr/bin/env python3
"""Where llvmpipe spends a render's time, down to the instructions of the
shader it compiled.

  tools/llvmpipe_profile.py [--octrace build/app/octrace] [--out build/llvmpipe_profile]
                            [--wait 2.5] [--seconds 3] -- RENDER ARGS...

Starts `octrace render --device cpu RENDER ARGS` (give it enough work to
run for --wait + --seconds and more: e.g. --size 1600x900 --spp 8 for the
default scene), waits --wait seconds (device creation, the pipeline), then
samples it with `perf record -p` for --seconds, and while it still runs
copies its executable anonymous mappings (the machine code llvmpipe's LLVM
compiled: perf sees it only as [JIT] addresses) with gdb. Then it
disassembles them (objdump) and puts each sample on its instruction.

Prints: the share of samples in the compiled code, the share on scalar and
branch instructions against vector ones (llvmpipe runs a shader 8
invocations to a vector; its per-invocation work, such as a storage-buffer
load or a store to an array indexed per invocation, is a scalar loop over
the lanes with a branch per lane), the hottest mnemonics and the hottest
512-byte regions of the code. Writes to DIR: annotated.s (every
instruction with its samples), summary.txt, render.log,
perf.data, the copied code (*.bin).

Needs perf, gdb and objdump (Debian: linux-perf, gdb, binutils;
`OCTRACE_SETUP_PROFILING=1 tools/setup.sh` installs them), and the right
to attach to a child process (root, or kernel.yama.ptrace_scope 0 and
kernel.perf_event_paranoid <= 1). A tool for developers; CI does not run it.
Optimisation log 84 has what it found. Bad input exits with 2: where the
render fails, with octrace's error line; where it ends too soon, perf
fails or the tool stops early, the render is stopped.
"""
import argparse
import collections
import datetime
import glob
import os
import re
import shutil
import subprocess
import time

import tool_args


def fail(message):
    tool_args.fail("llvmpipe_profile.py", message)


def seconds(text):
    """A number of seconds >= 0 (--wait)."""
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0 <= value < 1e6:  # NaN fails this too
        raise argparse.ArgumentTypeError(f"must be a number of seconds >= 0, got {text!r}")
    return value


def positive_seconds(text):
    """A number of seconds > 0 (--seconds)."""
    if seconds(text) == 0:
        raise argparse.ArgumentTypeError(f"must be a number of seconds > 0, got {text!r}")
    return float(text)


def last_line(path):
    """The last non-empty line of a log (octrace's error, where it failed)."""
    with open(path, errors="replace") as f:
        return tool_args.last_line(f.read(), "no output")


def executable_anonymous_mappings(pid):
    """(start, end) of each executable mapping of `pid` backed by no file."""
    found = []
    with open(f"/proc/{pid}/maps") as maps:
        for line in maps:
            fields = line.split()
            if len(fields) == 5 and "x" in fields[1]:
                start, end = (int(a, 16) for a in fields[0].split("-"))
                found.append((start, end))
    return found


def main():
    parser = tool_args.Parser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog="\n\n".join(__doc__.split("\n\n")[1:]))
    parser.add_argument("--octrace", type=tool_args.executable, default="build/app/octrace")
    parser.add_argument("--out", default="build/llvmpipe_profile")
    parser.add_argument("--wait", type=seconds, default=2.5, help="seconds before sampling starts")
    parser.add_argument("--seconds", type=positive_seconds, default=3.0, help="seconds of sampling")
    parser.add_argument("render", nargs=argparse.REMAINDER, help="-- then the render arguments")
    args = parser.parse_args()
    render = args.render[1:] if args.render[:1] == ["--"] else args.render
    if not render:
        fail("no render arguments: give them after --, e.g. -- --size 1600x900 --spp 8")
    for tool in ("perf", "gdb", "objdump"):
        if shutil.which(tool) is None:
            fail(f"{tool} is not installed (Debian: OCTRACE_SETUP_PROFILING=1 tools/setup.sh)")
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        fail(f"--out {args.out}: is a file, not a folder")
    os.makedirs(args.out, exist_ok=True)
    env = dict(os.environ)
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")

    command = [args.octrace, "render", "--device", "cpu", *render, "--out", os.path.join(args.out, "image.png")]
    log_path = os.path.join(args.out, "render.log")
    with open(log_path, "w") as log:
        proc = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env)
        try:
            time.sleep(args.wait)
            if proc.poll() is not None:
                if proc.returncode != 0:  # octrace refused its arguments, or failed
                    fail(f"the render failed (exit {proc.returncode}): {last_line(log_path)}")
                fail(f"the render ended within --wait ({args.wait} s); give it more work (see {log_path})")
            perf_data = os.path.join(args.out, "perf.data")
            # perf dies too where the render ends while it samples: that is
            # checked first, as the likelier cause.
            perf = subprocess.run(["perf", "record", "-F", "4000", "-p", str(proc.pid), "-o", perf_data, "--",
                                   "sleep", str(args.seconds)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                  text=True)
            if proc.poll() is not None:
                if proc.returncode != 0:
                    fail(f"the render failed (exit {proc.returncode}): {last_line(log_path)}")
                fail(f"the render ended while perf sampled it; give it more work (see {log_path})")
            if perf.returncode != 0:
                fail(f"perf record failed (exit {perf.returncode}): {tool_args.last_line(perf.stderr, 'no message')}")
            for old in glob.glob(os.path.join(args.out, "code_*.bin")):
                os.remove(old)
            mappings = executable_anonymous_mappings(proc.pid)
            gdb = ["gdb", "-p", str(proc.pid), "-batch"]
            for start, end in mappings:
                gdb += ["-ex", f"dump binary memory {args.out}/code_{start:x}.bin {start:#x} {end:#x}"]
            subprocess.run(gdb, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            proc.wait()
        finally:
            if proc.poll() is None:  # the tool stops early: stop the render too
                proc.terminate()
                proc.wait()
    if proc.returncode != 0:
        fail(f"the render failed (exit {proc.returncode}): {last_line(log_path)}")

    script = subprocess.run(["perf", "script", "-i", perf_data, "-F", "ip,dso"], capture_output=True, text=True)
    if script.returncode != 0:
        fail(f"perf script failed (exit {script.returncode}): {tool_args.last_line(script.stderr)}")
    script = script.stdout
    counts = collections.Counter()  # address -> samples in code of no file (perf's "[JIT]")
    total = 0
    for line in script.splitlines():
        fields = line.split()
        if not fields:
            continue
        total += 1
        if len(fields) == 1 or fields[1].startswith("(/tmp/perf-") or fields[1] == "([unknown])":
            counts[int(fields[0], 16)] += 1
    if total == 0:
        fail("perf recorded no samples")
    samples = {a: 100.0 * n / total for a, n in counts.items()}  # address -> share of all samples, %
    jit_share = sum(samples.values())

    # Each instruction of the copied code with its samples; then llvmpipe's
    # loops over the lanes of one vector: `cmp $0x8,%eXX` and a forward jump
    # out (the loop's exit) right after it; the loop's body lies between.
    instructions = []  # (address, mnemonic, operands, samples)
    annotated = []
    for path in sorted(glob.glob(os.path.join(args.out, "code_*.bin"))):
        base = int(re.search(r"code_([0-9a-f]+)\.bin", path).group(1), 16)
        disassembly = subprocess.run(["objdump", "-D", "-b", "binary", "-m", "i386:x86-64",
                                      f"--adjust-vma={base:#x}", path],
                                     check=True, capture_output=True, text=True).stdout
        for line in disassembly.splitlines():
            m = re.match(r"\s*([0-9a-f]+):\t[0-9a-f ]+\t(\S+)\s*(.*)", line)
            if not m:
                continue
            address = int(m.group(1), 16)
            n = counts.get(address, 0)
            instructions.append((address, m.group(2), m.group(3), n))
            annotated.append(f"{n:6d} {line}" if n else f"       {line}")
    with open(os.path.join(args.out, "annotated.s"), "w") as f:
        f.write("samples per instruction, of " + str(total) + " in all\n" + "\n".join(annotated) + "\n")
    lane_loops = []
    for here, after in zip(instructions, instructions[1:]):
        if here[1] == "cmp" and here[2].startswith("$0x8,%e") and after[1] in ("je", "jae", "jnb", "jge"):
            target = int(after[2].split()[0], 16)
            if here[0] < target < here[0] + 4096:
                lane_loops.append((here[0] - 16, target))
    mnemonics = collections.Counter()
    regions = collections.Counter()
    scalar = vector = in_lane_loops = 0.0
    for address, mnemonic, _, n in instructions:
        if not n:
            continue
        share = 100.0 * n / total
        mnemonics[mnemonic] += share
        regions[address // 512 * 512] += share
        if mnemonic.startswith(("v", "k")):
            vector += share
        else:
            scalar += share
        if any(lo <= address < hi for lo, hi in lane_loops):
            in_lane_loops += share
    attributed = scalar + vector
    lines = [
        f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC; "
        f"`{' '.join(command)}`; perf at 4000 Hz for {args.seconds} s after {args.wait} s",
        "",
        f"samples in the compiled shader code ([JIT]): {jit_share:.1f}%",
        f"of those found in the copied code: {attributed:.1f}% of all samples, "
        f"{100 * scalar / max(attributed, 1e-9):.1f}% on scalar and branch instructions, "
        f"{100 * vector / max(attributed, 1e-9):.1f}% on vector and mask ones",
        f"in loops over the lanes of a vector ({len(lane_loops)} such loops: `cmp $0x8` and the exit): "
        f"{in_lane_loops:.1f}% of all samples",
        "",
        "hottest mnemonics (% of all samples): " +
        ", ".join(f"{m} {s:.1f}" for m, s in mnemonics.most_common(16)),
        "",
        "hottest 512-byte regions (% of all samples):",
    ]
    for address, share in sorted(regions.items(), key=lambda kv: -kv[1])[:12]:
        lines.append(f"  {address:#x}  {share:5.1f}")
    lines.append("")
    lines.append(f"annotated disassembly: {args.out}/annotated.s")
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(args.out, "summary.txt"), "w") as f:
        f.write(text + "\n")


if __name__ == "__main__":
    main()
