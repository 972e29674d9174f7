#!/usr/bin/env python3
"""Times `octrace render` against Mitsuba 3 (scalar_rgb) on the same machine,
side by side in one run, on octrace's default scene (the rtiow field, 488
spheres of radius 0.2, seed 1) at 400x225, 10 spp, depth 50, no roulette.

Both sides are timed as whole processes (fork + exec to exit, PNG written):
octrace `render --device cpu ... --out X.png`; Mitsuba `python3 -c` that
imports mitsuba, loads the scene file, renders and writes the PNG. One
warm-up process of each, then ROUNDS alternating rounds (octrace, Mitsuba,
octrace, ...); median, min and max of each, and the ratio of the medians.

  tools/peer/mitsuba_compare.py [--rounds 5] [--octrace build/app/octrace]
                                [--python .venv-mitsuba/bin/python] [--out DIR]
                                [--markdown docs/results/lavapipe_mitsuba.md]

Mitsuba comes from PyPI (`pip install mitsuba==3.9.1`); without --python the
tool creates the virtual environment .venv-mitsuba (git-ignored) on first use.
CI does not need it. The scene is exported from octrace itself (--dump-scene)
and written as a Mitsuba XML file before any timing; docs/results/ says what
differs between the two renders.
"""
import argparse
import datetime
import json
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import tool_args  # noqa: E402

MITSUBA_VERSION = "3.9.1"
ROOT = Path(__file__).resolve().parents[2]

SIZE = (400, 225)
SPP = 10
DEPTH = 50
SKY_ROWS = 512  # envmap rows (the gradient varies with the polar angle only)
SKY_COLS = 8

MITSUBA_RUN = (
    "import sys, mitsuba as mi; mi.set_variant('scalar_rgb'); "
    "scene = mi.load_file(sys.argv[1]); "
    "mi.util.write_bitmap(sys.argv[2], mi.render(scene))"
)


def fail(msg):
    sys.exit(f"mitsuba_compare: {msg}")


def run(cmd, **kw):
    out = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if out.returncode != 0:
        fail(f"{' '.join(map(str, cmd))} failed ({out.returncode}): {out.stderr.strip()[-2000:]}")
    return out


def python_program(text):
    """--python: an executable file, or a name on PATH."""
    if not text or not shutil.which(text):
        raise argparse.ArgumentTypeError(f"{text}: no such program, or not executable")
    return text


def check_python(py):
    """Ends the tool in one line if the --python given cannot import Mitsuba
    (or numpy, which the sky's export needs): checked before any work."""
    p = subprocess.run([py, "-c", "import mitsuba, numpy"], capture_output=True, text=True)
    if p.returncode != 0:
        why = tool_args.last_line(p.stderr, f"exit {p.returncode}")
        tool_args.fail("mitsuba_compare.py",
                       f"--python {py}: it lacks Mitsuba or numpy ({why}); give a Python with mitsuba=={MITSUBA_VERSION} "
                       "and numpy, or leave --python out and the tool makes its own venv .venv-mitsuba")


def mitsuba_python(arg):
    if arg:
        return arg
    venv = ROOT / ".venv-mitsuba"
    py = venv / "bin" / "python"
    if not py.exists():
        print(f"creating {venv} with mitsuba=={MITSUBA_VERSION} and numpy (pip)", file=sys.stderr)
        run([sys.executable, "-m", "venv", str(venv)])
        run([str(py), "-m", "pip", "install", "-q", f"mitsuba=={MITSUBA_VERSION}", "numpy"])
    return str(py)


def rgb(v):
    return ", ".join(f"{float(x):.9g}" for x in v)


def bsdf_xml(m):
    """octrace material -> Mitsuba BSDF (docs/results/lavapipe_mitsuba.md lists the differences)."""
    t = m["type"]
    if t == "lambertian":
        return f'<bsdf type="diffuse"><rgb name="reflectance" value="{rgb(m["albedo"])}"/></bsdf>'
    if t == "metal":
        fuzz = float(m.get("fuzz", 0.0))
        if fuzz == 0.0:
            # material "none": a perfect mirror (eta 0, k 1) scaled by the albedo.
            return ('<bsdf type="conductor"><string name="material" value="none"/>'
                    f'<rgb name="specular_reflectance" value="{rgb(m["albedo"])}"/></bsdf>')
        # RTIOW's fuzz perturbs the mirror direction by fuzz * a random unit
        # vector; the nearest microfacet lobe used here is GGX with alpha = fuzz
        # (not the same distribution, a similar blur).
        return ('<bsdf type="roughconductor"><string name="material" value="none"/>'
                f'<string name="distribution" value="ggx"/><float name="alpha" value="{fuzz:.9g}"/>'
                f'<rgb name="specular_reflectance" value="{rgb(m["albedo"])}"/></bsdf>')
    if t == "dielectric":
        return (f'<bsdf type="dielectric"><float name="int_ior" value="{float(m["ior"]):.9g}"/>'
                '<float name="ext_ior" value="1.0"/></bsdf>')
    fail(f"material type {t!r} has no Mitsuba counterpart in this tool")


def write_sky(py, sky, path):
    """The RTIOW gradient (t = 0.5 (dir.y + 1), (1 - t) down + t up) as a
    latitude-longitude map: Mitsuba's envmap row v looks at polar angle
    theta = pi v from +y, so dir.y = cos(pi (v + 0.5) / rows) at a row's centre."""
    if sky.get("type") != "gradient":
        fail(f"sky type {sky.get('type')!r}: only the gradient sky is exported")
    code = (
        "import sys, json, math, numpy as np, mitsuba as mi; mi.set_variant('scalar_rgb'); "
        "down, up, rows, cols = json.loads(sys.argv[1]); "
        "a = np.zeros((rows, cols, 3), np.float32); "
        "t = 0.5 * (np.cos(np.pi * (np.arange(rows) + 0.5) / rows) + 1.0); "
        "a[:] = ((1 - t)[:, None] * np.array(down)[None, :] + t[:, None] * np.array(up)[None, :])[:, None, :]; "
        "mi.Bitmap(a).write(sys.argv[2])"
    )
    run([py, "-c", code, json.dumps([sky["down"], sky["up"], SKY_ROWS, SKY_COLS]), str(path)])


def write_scene(scene, sky_file, path):
    c = scene["camera"]
    lines = ['<scene version="3.0.0">',
             f'<integrator type="path"><integer name="max_depth" value="{DEPTH}"/>'
             f'<integer name="rr_depth" value="{DEPTH + 1}"/></integrator>']
    sensor = "thinlens" if float(c.get("aperture", 0)) > 0 else "perspective"
    lens = (f'<float name="aperture_radius" value="{float(c["aperture"]) / 2:.9g}"/>'
            f'<float name="focus_distance" value="{float(c["focus_dist"]):.9g}"/>') if sensor == "thinlens" else ""
    lines.append(
        f'<sensor type="{sensor}"><float name="fov" value="{float(c["vfov"]):.9g}"/>'
        '<string name="fov_axis" value="y"/>' + lens +
        f'<transform name="to_world"><lookat origin="{rgb(c["lookfrom"])}" target="{rgb(c["lookat"])}" '
        f'up="{rgb(c["vup"])}"/></transform>'
        f'<sampler type="independent"><integer name="sample_count" value="{SPP}"/></sampler>'
        f'<film type="hdrfilm"><integer name="width" value="{SIZE[0]}"/><integer name="height" value="{SIZE[1]}"/>'
        '<rfilter type="box"/></film></sensor>')
    lines.append(f'<emitter type="envmap"><string name="filename" value="{sky_file}"/></emitter>')
    mats = scene["materials"]
    for s in scene["spheres"]:
        lines.append(f'<shape type="sphere"><point name="center" value="{rgb(s["center"])}"/>'
                     f'<float name="radius" value="{float(s["radius"]):.9g}"/>{bsdf_xml(mats[s["material"]])}</shape>')
    lines.append("</scene>")
    path.write_text("\n".join(lines) + "\n")


def stats(xs):
    return statistics.median(xs), min(xs), max(xs)


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=tool_args.positive_int, default=5)
    ap.add_argument("--octrace", type=tool_args.executable, default=str(ROOT / "build/app/octrace"))
    ap.add_argument("--python", type=python_program,
                    help="a Python with mitsuba installed (default: .venv-mitsuba, created if missing)")
    ap.add_argument("--out", default="/tmp/mitsuba_compare")
    ap.add_argument("--markdown", type=tool_args.output_file,
                    help="also write the table and settings to this markdown file")
    ap.add_argument("--octrace-flags", default="",
                    help="extra render flags for octrace's timed runs (e.g. \"--tail-depth 2\"); default none")
    args = ap.parse_args()
    # The cheap checks first: the venv and Mitsuba's install come after them.
    if args.rounds < 5:
        tool_args.fail("mitsuba_compare.py", "--rounds: at least 5 (the table reports a median of >= 5)")
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        tool_args.fail("mitsuba_compare.py", f"--out {out}: is a file, not a folder")
    if args.python:
        check_python(args.python)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        tool_args.fail("mitsuba_compare.py", f"--out {out}: cannot make the folder: {e.strerror}")
    env = dict(os.environ, XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp"))
    py = mitsuba_python(args.python)

    # The scene as octrace builds it, exported once (a tiny render: --dump-scene
    # writes the scene the render uses).
    scene_json = out / "scene.json"
    run([args.octrace, "render", "--device", "cpu", "--size", "8x8", "--spp", "1", "--quiet",
         "--dump-scene", str(scene_json), "--out", str(out / "dump.png")], env=env)
    scene = json.loads(scene_json.read_text())
    write_sky(py, scene["sky"], out / "sky.exr")
    write_scene(scene, out / "sky.exr", out / "scene.xml")

    w, h = SIZE
    oct_cmd = [args.octrace, "render", "--device", "cpu", "--size", f"{w}x{h}", "--spp", str(SPP),
               "--depth", str(DEPTH), "--quiet"] + args.octrace_flags.split() + ["--out", str(out / "octrace.png")]
    mts_cmd = [py, "-c", MITSUBA_RUN, str(out / "scene.xml"), str(out / "mitsuba.png")]
    info = json.loads(run(oct_cmd[:-2] + ["--json", "--out", str(out / "octrace_info.png")], env=env).stdout)
    mts_version = run([py, "-c", "import mitsuba; print(mitsuba.__version__)"]).stdout.strip()

    # Wall time is the goal's measure; CPU time (user + sys of the child, from
    # getrusage) is reported beside it because it moves far less when other
    # processes share the cores.
    times = {"octrace": [], "mitsuba": []}
    cpu = {"octrace": [], "mitsuba": []}
    load_before = os.getloadavg()[0]
    for i in range(args.rounds + 1):
        for name, cmd in (("octrace", oct_cmd), ("mitsuba", mts_cmd)):
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            run(cmd, env=env)
            ms = (time.perf_counter() - start) * 1000
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            if i > 0:  # round 0 is the warm-up
                times[name].append(ms)
                cpu[name].append(1000 * (r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime))
    load_after = os.getloadavg()[0]
    cmp = run([args.octrace, "compare", str(out / "octrace.png"), str(out / "mitsuba.png")], env=env).stdout

    # Two 10-spp renders of the same scene measured 25.7 dB apart; a broken
    # export (a mirrored camera, a missing sky) falls far below 20 dB.
    psnr = float(next(l.split()[1] for l in cmp.splitlines() if l.startswith("psnr")))
    if psnr < 20:
        print(f"mitsuba_compare: warning: the two images differ by more than noise (PSNR {psnr:.1f} dB): "
              "is the exported scene the same?", file=sys.stderr)
    o, m = stats(times["octrace"]), stats(times["mitsuba"])
    oc, mc = stats(cpu["octrace"]), stats(cpu["mitsuba"])
    ratio = o[0] / m[0]
    commit = run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"]).stdout.strip()
    dirty = run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"]).stdout.strip()
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    d = info["device"]
    table = [
        f"{when}, {platform.node()}: {os.cpu_count()} CPU threads; octrace on {d['name']} ({d['driver']}), "
        f"commit {commit}{' (with local changes)' if dirty else ''}; Mitsuba {mts_version} scalar_rgb; "
        f"{w}x{h}, {SPP} spp, depth {DEPTH}, no roulette; one warm-up, {args.rounds} alternating rounds" +
        "".join(f"; {k}={os.environ[k]}" for k in ("OCTRACE_SPECIALIZE", "OCTRACE_CACHE_DIR", "LP_NUM_THREADS") if k in os.environ) + ".",
        "",
        f"Load average (1 min) {load_before:.1f} before, {load_after:.1f} after, on {os.cpu_count()} CPU threads.",
        "",
        "| renderer | whole process wall, median (min–max) | CPU time (user + sys), median (min–max) |",
        "|---|---:|---:|",
        f"| octrace (`render --device cpu{(' ' + args.octrace_flags) if args.octrace_flags else ''}`) | {o[0]:.0f} ms ({o[1]:.0f}–{o[2]:.0f}) | {oc[0]:.0f} ms ({oc[1]:.0f}–{oc[2]:.0f}) |",
        f"| Mitsuba 3 scalar_rgb (`python3 -c`) | {m[0]:.0f} ms ({m[1]:.0f}–{m[2]:.0f}) | {mc[0]:.0f} ms ({mc[1]:.0f}–{mc[2]:.0f}) |",
        f"| **octrace / Mitsuba** | **{ratio:.2f}** | {oc[0] / mc[0]:.2f} |",
        "",
        "octrace's own timings of the last run (ms): " +
        ", ".join(f"{k} {v:.0f}" for k, v in info["times_ms"].items() if k != "render_wall"),
        "",
        "Image difference (`octrace compare octrace.png mitsuba.png`, both 10 spp, so mostly noise): " +
        "; ".join(" ".join(l.split()) for l in cmp.strip().splitlines()),
    ]
    text = "\n".join(table)
    print(text)
    raw = json.dumps({"wall": {k: [round(x, 1) for x in v] for k, v in times.items()},
                      "cpu": {k: [round(x, 1) for x in v] for k, v in cpu.items()}})
    print("raw ms: " + raw)
    if args.markdown:
        md = Path(args.markdown)
        body = md.read_text() if md.exists() else ""
        marker = "<!-- mitsuba_compare.py writes below this line -->"
        head = body.split(marker)[0] if marker in body else body
        md.write_text(head.rstrip("\n") + "\n\n" + marker + "\n\n" + text + "\n\nRaw (ms): `" + raw + "`\n")


if __name__ == "__main__":
    main()
