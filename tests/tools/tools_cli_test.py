#!/usr/bin/env python3
"""The tools/ scripts meet bad input as octrace does (tools/tool_args.py):
one line on stderr naming the flag or file, exit status 2, before any
render and with no output file; and hardcases_table.py's criterion column
does not depend on Python's string hashing. No render runs here: every
case stops at its arguments.

    tests/tools/tools_cli_test.py SOURCE_DIR OCTRACE
"""
import os
import subprocess
import sys
import tempfile

source, octrace = sys.argv[1], sys.argv[2]
tools = os.path.join(source, "tools")
failures = []


def run(args, env=None):
    return subprocess.run([sys.executable] + args, capture_output=True, text=True,
                          env=dict(os.environ, **(env or {})))


def bad_input(label, args, message, must_not_exist=None):
    r = run(args)
    lines = r.stderr.strip("\n").split("\n")
    if r.returncode != 2 or len(lines) != 1 or message not in lines[0] or "Traceback" in r.stderr:
        failures.append(f"{label}: exit {r.returncode}, stderr:\n{r.stderr}(expected exit 2 and one line with {message!r})")
    if must_not_exist and os.path.exists(must_not_exist):
        failures.append(f"{label}: {must_not_exist} was written")


with tempfile.TemporaryDirectory() as tmp:
    out_md = os.path.join(tmp, "ab.md")
    bad_input("ab_render, no binary", [f"{tools}/ab_render.py", "--octrace", f"{tmp}/no_octrace", "--render", "--spp 1",
                                       "--variant", "a="], f"{tmp}/no_octrace: no such file", out_md)
    bad_input("ab_render, a variant's binary", [f"{tools}/ab_render.py", "--octrace", octrace, "--render", "--spp 1",
                                                "--variant", f"a=BIN={tmp}/no_octrace", "--out", out_md],
              f"BIN={tmp}/no_octrace: no such file", out_md)
    bad_input("ab_render, no rounds", [f"{tools}/ab_render.py", "--octrace", octrace, "--render", "--spp 1",
                                       "--variant", "a=", "--rounds", "0"], "--rounds: must be a whole number >= 1")
    bad_input("ab_render, out folder", [f"{tools}/ab_render.py", "--octrace", octrace, "--render", "--spp 1",
                                        "--variant", "a=", "--out", f"{tmp}/none/ab.md"], "does not exist")
    bad_input("dispatch_table, no binary", [f"{tools}/dispatch_table.py", "--octrace", f"{tmp}/no_octrace", "--render",
                                            "--spp 1", "--out", out_md], f"{tmp}/no_octrace: no such file", out_md)
    bad_input("dispatch_table, no rounds", [f"{tools}/dispatch_table.py", "--octrace", octrace, "--render", "--spp 1",
                                            "--rounds", "0"], "--rounds: must be a whole number >= 1")
    bad_input("dispatch_table, a render flag", [f"{tools}/dispatch_table.py", "--octrace", octrace, "--render",
                                                "--spp 0", "--out", out_md], "--spp", out_md)
    bad_input("time_render, runs", [f"{tools}/time_render.py", "--octrace", octrace, "--runs", "-3"],
              "must be a whole number >= 1")
    bad_input("walk_stats, no accel", [f"{tools}/walk_stats.py", "--octrace", octrace, "--scene", "a=--spp 1",
                                       "--accel", ",", "--out", f"{tmp}/walk.md"], "--accel", f"{tmp}/walk.md")
    bad_input("plot_bench, no csv", [f"{tools}/plot_bench.py", f"{tmp}/none.csv", "-o", f"{tmp}/plot.png"],
              f"{tmp}/none.csv: no such file", f"{tmp}/plot.png")
    bad_input("make_grid_glb, zero", [f"{tools}/make_grid_glb.py", "0", f"{tmp}/grid.glb"], "", f"{tmp}/grid.glb")
    bad_input("peer compare, size", [f"{tools}/peer/compare.py", "--peer", tmp, "--octrace", octrace, "--out",
                                     f"{tmp}/peer", "--size", "16"], "--size", f"{tmp}/peer")

    # Two variants whose bounds tie: the criterion column is the first in
    # the file's order whatever PYTHONHASHSEED is (it was max(set(...)), which
    # followed the hash).
    rows = os.path.join(tmp, "rows.tsv")
    with open(rows, "w") as f:
        f.write("c1\tq\t<1\toctree\tfp32\t0.5\tpass\nc1\tq\t<2\tbvh\tfp16\t0.7\tFAIL\n")
    tables = {run([f"{tools}/hardcases_table.py", rows], {"PYTHONHASHSEED": str(seed)}).stdout for seed in range(8)}
    if len(tables) != 1 or "| q <1 " not in next(iter(tables)).replace("`", ""):
        failures.append("hardcases_table: the table depends on PYTHONHASHSEED or does not pick the first bound:\n" +
                        "\n---\n".join(sorted(tables)))

if failures:
    print("\n\n".join(failures))
    sys.exit(1)
print("tools: bad input is one line and exit 2; hardcases_table is deterministic")
