#!/usr/bin/env python3
"""octrace against the fastest public CUDA port of Ray Tracing in One Weekend,
side by side in one run on one GPU (issue "Faster than the fastest").

  tools/peer/compare.py --peer PEER_DIR --octrace BIN --out DIR [--rounds 5]

PEER_DIR is a copy of the headless peer (karimsayedre/CUDA-Ray-Tracing-In-
One-Weekend at beea450, with its build.sh; see tools/peer/README.md); it is
built there with nvcc if its karim_bench is missing. Both sides time device
work only:
  peer     cudaEvent pair around its RenderKernel; one process = 1 warm-up
           frame + 5 timed frames, it prints their median
  octrace  `render --json` times_ms.render: the sum of the passes' timestamp
           queries (the accumulation passes; no set-up, readback or resolve)
Settings are matched: W x H, spp, depth (ray segments per path, the camera
ray included, on both), Russian roulette from the first bounce (octrace
--rr-depth 1), a pinhole camera at (13, 2, 3) looking at the origin with
vfov 20, the peer's scene recipe (tools/scenes/peer_field.json, written by
make_peer_field.py: same recipe, octrace's own random draws).

After one warm-up process of each, ROUNDS rounds run the peer and octrace
alternately; the table gives the median over rounds of each side's time and
paths/s (pixels x spp / time), and the ratio octrace/peer of paths/s (> 1:
octrace is faster). Writes DIR/peer_compare.{md,csv} and the raw outputs.
"""
import argparse
import csv
import datetime
import json
import os
import re
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import tool_args  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "peer_field.json")


def run(cmd, log, cwd=None):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + "\n" + p.stdout + p.stderr + "\n")
    if p.returncode != 0:
        # octrace says what it refused on a line of its own: quote that one
        # (its exit 2, bad input such as --octrace-args, stays 2).
        said = [l for l in p.stderr.splitlines() if l.startswith("octrace: error:")]
        if said:
            print(f"compare.py: octrace failed (exit {p.returncode}): {said[-1]} ({log})", file=sys.stderr)
            sys.exit(2 if p.returncode == 2 else 1)
        sys.exit(f"compare.py: {' '.join(cmd)} failed with exit {p.returncode} (see {log})")
    return p.stdout


def peer_ms(bench, a, log):
    out = run([bench, str(a.width), str(a.height), str(a.spp), str(a.depth), "0"], log)
    m = re.search(r"median_ms=([0-9.]+)", out)
    if not m:
        sys.exit(f"compare.py: no median_ms in the peer's output (see {log})")
    return float(m.group(1))


def octrace_run(a, log, extra):
    out = run([a.octrace, "render", "--scene", SCENE, "--size", f"{a.width}x{a.height}", "--spp", str(a.spp),
               "--depth", str(a.depth), "--rr-depth", "1", "--device", a.device, "-o",
               os.path.join(a.out, "octrace.png"), "--json", "-q"] + extra, log)
    return json.loads(out)


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peer", required=True, help="folder of the headless peer (build.sh, src/)")
    ap.add_argument("--octrace", required=True, type=tool_args.executable, help="octrace binary")
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--rounds", type=tool_args.positive_int, default=5)
    ap.add_argument("--size", type=tool_args.size, default="1920x1080")
    ap.add_argument("--spp", type=tool_args.positive_int, default=64)
    ap.add_argument("--depth", type=tool_args.positive_int, default=50)
    ap.add_argument("--device", default="gpu")
    ap.add_argument("--octrace-args", default="", help="extra render options for octrace (a variant)")
    a = ap.parse_args()
    # Everything checked before the peer is built or anything runs.
    a.width, a.height = (int(v) for v in a.size.split("x"))
    a.octrace = os.path.abspath(a.octrace)
    peer = os.path.abspath(a.peer)
    bench = os.path.join(peer, "karim_bench")
    if not os.path.isdir(peer):
        tool_args.fail("compare.py", f"--peer {a.peer}: no such folder (see tools/peer/README.md)")
    if not os.path.exists(bench) and not os.path.isfile(os.path.join(peer, "build.sh")):
        tool_args.fail("compare.py", f"--peer {a.peer}: neither karim_bench nor build.sh in it (see tools/peer/README.md)")
    if os.path.exists(a.out) and not os.path.isdir(a.out):
        tool_args.fail("compare.py", f"--out {a.out}: is a file, not a folder")
    try:
        os.makedirs(a.out, exist_ok=True)
    except OSError as e:
        tool_args.fail("compare.py", f"--out {a.out}: cannot make the folder: {e.strerror}")
    log = os.path.join(a.out, "compare.log")
    open(log, "w").close()
    if not os.path.exists(bench):
        print("building the peer (build.sh) ...", file=sys.stderr)
        run(["./build.sh"], log, cwd=peer)
    extra = a.octrace_args.split()

    peer_ms(bench, a, log)  # warm-up processes
    info = octrace_run(a, log, extra)
    peer_t, oct_t = [], []
    for r in range(a.rounds):
        peer_t.append(peer_ms(bench, a, log))
        info = octrace_run(a, log, extra)
        oct_t.append(info["times_ms"]["render"])
        print(f"round {r + 1}/{a.rounds}: peer {peer_t[-1]:.3f} ms, octrace {oct_t[-1]:.3f} ms", file=sys.stderr)

    paths = a.width * a.height * a.spp
    pm, om = statistics.median(peer_t), statistics.median(oct_t)
    ratio = (paths / om) / (paths / pm)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    dev = info["device"]["name"]
    lines = [
        f"Peer comparison, {date}, {dev} ({info['device']['driver']}); octrace `{a.octrace} render --scene "
        f"tools/scenes/peer_field.json --size {a.size} --spp {a.spp} --depth {a.depth} --rr-depth 1"
        + (" " + a.octrace_args if a.octrace_args else "") + "`; peer `karim_bench "
        f"{a.width} {a.height} {a.spp} {a.depth} 0`; {a.rounds} alternating rounds after a warm-up of each; "
        "device time only on both sides.",
        "",
        "| renderer | median ms | min ms | max ms | paths/s |",
        "| --- | --- | --- | --- | --- |",
        f"| CUDA peer (karim, beea450) | {pm:.2f} | {min(peer_t):.2f} | {max(peer_t):.2f} | {paths / pm * 1e3:.3g} |",
        f"| octrace | {om:.2f} | {min(oct_t):.2f} | {max(oct_t):.2f} | {paths / om * 1e3:.3g} |",
        "",
        f"octrace / peer paths/s: **{ratio:.2f}** (> 1: octrace is faster)",
    ]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "peer_compare.md"), "w") as f:
        f.write(text)
    with open(os.path.join(a.out, "peer_compare.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["round", "peer_ms", "octrace_ms"])
        for i, (p, o) in enumerate(zip(peer_t, oct_t)):
            w.writerow([i + 1, p, o])
    with open(os.path.join(a.out, "octrace_last.json"), "w") as f:
        json.dump(info, f, indent=1)
    print(text)


if __name__ == "__main__":
    main()
