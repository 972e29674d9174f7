#!/usr/bin/python3
"""What next-event estimation buys: equal-time efficiency of `--nee on`
against `--nee off`, and what it costs where it does not help.

Efficiency: for each setting, renders at a few sample counts and takes
relative MSE x device time against a reference (NEE on, --ref-spp samples,
another sample seed); the ratio off / on of that product is how many times
less time NEE needs for the same error (the product is constant in spp for
an unbiased estimator, so the ratio is read at each spp and its median
reported). Three scenes: tools/nee/small_light.json (a sphere light of radius
0.05, black sky), the same objects with a 0.2 x 0.2 quad light (two
emissive triangles, a glb this tool writes with make_grid_glb.py) in place of
the sphere, and the same objects under an environment map with a sun
(a 64 x 32 map, written by this tool as a PFM: a dim sky of radiance 0.3 to
1.2 and one texel of 5000, 4500, 4000 at 42 degrees of elevation; the sun
subtends ~0.007 sr, so BSDF sampling finds it on ~0.2% of diffuse bounces).
Cost: device time per sample with NEE on over off, on scenes where light
sampling adds little.

  tools/nee_efficiency.py [--octrace build/app/octrace] [--device cpu] [--out docs/results/nee_lavapipe]

Writes OUT/nee.md. Default settings run in a few minutes on lavapipe. Bad
input exits with 2 before any render; a render that fails ends the tool with
octrace's error line and its exit status, and removes OUT/tmp.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

import tool_args


def spp_list(text):
    """Comma-separated sample counts, each >= 1."""
    try:
        return [tool_args.positive_int(s) for s in text.split(",")]
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"expected whole numbers >= 1 separated by commas, got {text!r}")


def render(args, scene_flags, path, spp, nee, seed, size):
    cmd = [args.octrace, "render", "--json", "--quiet", "--device", args.device, "--size", size,
           "--spp", str(spp), "--sample-seed", str(seed), "--nee", nee, "--out", path] + scene_flags
    return json.loads(tool_args.run(cmd))


def rel_mse(args, test, ref):
    return json.loads(tool_args.run([args.octrace, "compare", "--json", test, ref]))["rel_mse"]


def write_sun_sky(tmp, here):
    """The sun-sky scene: small_light.json's objects without the sphere light,
    under a 64 x 32 envmap (PFM, rows bottom to top) with one bright texel."""
    import struct
    w, h = 64, 32
    texels = []
    for y in range(h):  # y = 0 the top row (+y)
        up = 1.0 - (y + 0.5) / h
        texels.append([(0.3 + 0.5 * up, 0.4 + 0.5 * up, 0.5 + 0.7 * up) for _ in range(w)])
    texels[h // 4][3 * w // 8] = (5000.0, 4500.0, 4000.0)
    pfm = os.path.abspath(os.path.join(tmp, "sun_sky.pfm"))  # the scene reads it relative to itself otherwise
    with open(pfm, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        for y in reversed(range(h)):
            for c in texels[y]:
                f.write(struct.pack("<3f", *c))
    with open(os.path.join(here, "nee", "small_light.json")) as f:
        scene = json.load(f)
    light = next(i for i, m in enumerate(scene["materials"]) if m["type"] == "emissive")
    scene["spheres"] = [s for s in scene["spheres"] if s["material"] != light]
    scene["sky"] = {"type": "envmap", "file": pfm, "strength": 1, "rotate": 0}
    path = os.path.join(tmp, "sun_sky.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def write_quad_light(tmp, here):
    """small_light.json with the sphere light replaced by a quad of two
    emissive triangles (make_grid_glb.py's one-quad sheet, 10 x 10, scaled
    to 0.2 x 0.2) of the same radiance, at the sphere's place."""
    glb = os.path.abspath(os.path.join(tmp, "quad.glb"))
    tool_args.run([sys.executable, os.path.join(here, "make_grid_glb.py"), "1", glb])
    with open(os.path.join(here, "nee", "small_light.json")) as f:
        scene = json.load(f)
    light = next(i for i, m in enumerate(scene["materials"]) if m["type"] == "emissive")
    centre = next(s["center"] for s in scene["spheres"] if s["material"] == light)
    scene["spheres"] = [s for s in scene["spheres"] if s["material"] != light]
    scene["meshes"] = [{"file": glb, "material": light, "transform": {"scale": 0.02, "translate": centre}}]
    path = os.path.join(tmp, "quad_light.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def efficiency(args, flags, tmp, spps, name):
    """Rows of (spp, (ms, rel MSE) on, off, ratio) on one scene."""
    ref = os.path.join(tmp, "ref.pfm")
    info = render(args, flags, ref, args.ref_spp, "on", 1000, args.size)
    rows = []
    for spp in spps:
        row = {"spp": spp}
        times = {"on": [], "off": []}
        for _ in range(args.repeats):
            for nee in ("on", "off"):
                path = os.path.join(tmp, f"{nee}_{spp}.pfm")
                times[nee].append(render(args, flags, path, spp, nee, 1, args.size)["times_ms"]["render"])
        for nee in ("on", "off"):
            row[nee] = (statistics.median(times[nee]), rel_mse(args, os.path.join(tmp, f"{nee}_{spp}.pfm"), ref))
        row["ratio"] = (row["off"][0] * row["off"][1]) / (row["on"][0] * row["on"][1])
        rows.append(row)
        print(f"{name}: spp {spp}: on {row['on']}, off {row['off']}, efficiency ratio {row['ratio']:.1f}",
              file=sys.stderr)
    return info["device"], rows


def far_light_scene(octrace, device, tmp):
    """The default rtiow field (dumped by OCTRACE) with one small emitter
    (r = 0.5, radiance 50) 30 above it, which lights little: where NEE costs
    a shadow ray per vertex for almost nothing. Returns the JSON's path."""
    far = os.path.join(tmp, "rtiow_far_light.json")
    tool_args.run([octrace, "render", "--quiet", "--device", device, "--size", "8x8", "--spp", "1",
         "--dump-scene", far, "--out", os.path.join(tmp, "dump.png")])
    with open(far) as f:
        scene = json.load(f)
    scene["materials"].append({"type": "emissive", "radiance": [50, 50, 50]})
    scene["spheres"].append({"center": [0, 30, 0], "radius": 0.5, "material": len(scene["materials"]) - 1})
    with open(far, "w") as f:
        json.dump(scene, f)
    return far


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", type=tool_args.executable, default="build/app/octrace")
    ap.add_argument("--device", default="auto")
    ap.add_argument("--size", default="96x54")
    ap.add_argument("--ref-spp", type=tool_args.positive_int, default=2048)
    ap.add_argument("--spps", default="16,32,64")
    ap.add_argument("--repeats", type=tool_args.positive_int, default=5, help="timed runs per setting (median)")
    ap.add_argument("--out", default="docs/results/nee")
    args = ap.parse_args()
    try:
        spps = spp_list(args.spps)  # kept as text in args: nee.md quotes it
    except argparse.ArgumentTypeError as e:
        ap.error(f"argument --spps: {e}")
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        tool_args.fail("nee_efficiency.py", f"--out {args.out}: is a file, not a folder")
    created = not os.path.isdir(args.out)
    os.makedirs(args.out, exist_ok=True)
    tmp = os.path.join(args.out, "tmp")
    os.makedirs(tmp, exist_ok=True)
    try:
        measure_all(args, tmp, spps)
    finally:
        # The renders and scenes in tmp are temporaries, on failure too.
        for name in os.listdir(tmp):
            os.remove(os.path.join(tmp, name))
        os.rmdir(tmp)
        if created and not os.listdir(args.out):
            os.rmdir(args.out)  # a failure before any output: leave no empty folder
    print(open(os.path.join(args.out, "nee.md")).read())


def measure_all(args, tmp, spps):
    """The renders, and OUT/nee.md."""
    here = os.path.dirname(os.path.abspath(__file__))
    small = ["--scene", os.path.join(here, "nee", "small_light.json")]

    device, rows = efficiency(args, small, tmp, spps, "small sphere light")
    quad = ["--scene", write_quad_light(tmp, here)]
    _, quad_rows = efficiency(args, quad, tmp, spps, "quad light (emissive triangles)")
    sun = ["--scene", write_sun_sky(tmp, here)]
    _, sun_rows = efficiency(args, sun, tmp, spps, "envmap with a sun")

    # Cost where NEE does not help: the rtiow field under the gradient sky (no
    # light is sampled: a gradient sky is no light, so NEE compiles out), and
    # the same field with one small emitter far above, which lights little.
    cost = []
    far = far_light_scene(args.octrace, args.device, tmp)
    for name, flags in (("rtiow, gradient sky (no light to sample: the same pipeline)", []),
                        ("rtiow + one emitter far above", ["--scene", far])):
        # Interleaved, so that a change in the machine's load hits both alike.
        times = {"on": [], "off": []}
        for _ in range(args.repeats):
            for nee in ("on", "off"):
                r = render(args, flags, os.path.join(tmp, "cost.pfm"), 16, nee, 1, "160x90")
                times[nee].append(r["times_ms"]["render"])
        t = {nee: statistics.median(v) for nee, v in times.items()}
        cost.append((name, t["on"], t["off"], t["on"] / t["off"]))
        print(f"{name}: on {t['on']:.1f} ms, off {t['off']:.1f} ms", file=sys.stderr)

    # The commit of the tools' checkout, whatever the current folder.
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                            cwd=here).stdout.strip() or "unknown"
    with open(os.path.join(args.out, "nee.md"), "w") as f:
        f.write(f"Device: {device['name']} ({device['type']}); commit {commit}; "
                f"`tools/nee_efficiency.py --device {args.device} --size {args.size} --ref-spp {args.ref_spp} "
                f"--spps {args.spps}`.\n\n")
        for title, table in ((f"tools/nee/small_light.json (a sphere light of radius 0.05, no sky)", rows),
                             ("a quad light (small_light.json's objects with a 0.2 x 0.2 quad of two emissive "
                              "triangles in place of the sphere light)", quad_rows),
                             ("an envmap with a sun (small_light.json's objects without the sphere light, under "
                              "the 64 x 32 sun sky this tool writes: one texel of 5000)", sun_rows)):
            f.write(f"Equal-time efficiency on {title}, {args.size}, depth 50, against a reference with NEE "
                    f"on, {args.ref_spp} spp, sample seed 1000. Time: device time of the passes, median of "
                    f"{args.repeats} runs interleaved on/off.\n\n")
            f.write("| spp | NEE on: ms | rel MSE | NEE off: ms | rel MSE | (MSE x time) off / on |\n")
            f.write("|---:|---:|---:|---:|---:|---:|\n")
            for r in table:
                f.write(f"| {r['spp']} | {r['on'][0]:.1f} | {r['on'][1]:.3g} | {r['off'][0]:.1f} | "
                        f"{r['off'][1]:.3g} | {r['ratio']:.1f} |\n")
            f.write(f"\nMedian efficiency gain: **{statistics.median(r['ratio'] for r in table):.1f}x**.\n\n")
        f.write(f"Cost where NEE helps little: device time of 16 spp at 160x90, median of {args.repeats} runs "
                f"interleaved on/off.\n\n")
        f.write("| scene | NEE on ms | NEE off ms | on / off |\n|---|---:|---:|---:|\n")
        for name, on, off, ratio in cost:
            f.write(f"| {name} | {on:.1f} | {off:.1f} | {ratio:.2f} |\n")


if __name__ == "__main__":
    main()
