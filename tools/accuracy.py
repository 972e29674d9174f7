#!/usr/bin/python3
"""What accuracy costs in time: renders a reference (fp32, --ref-spp samples,
its own sample seed), then every precision x spp (1, 2, 4, ..., --max-spp) x
depth, recording the device render time (timestamp queries, from
`octrace render --json`) and the error against the reference (relative MSE
and SSIM, from `octrace compare --json`). Writes OUT/accuracy.csv,
OUT/accuracy.md and OUT/accuracy.png (error against time, log-log, one line
per precision and depth: for an error budget, read off the fastest setting).
With --nee-off, fp32 at depth 50 with next-event estimation off is swept too
(every other render uses the default, NEE on; the reference too).

It also measures the precision targets of the fp16 variant:
  * the study's comparison: 10 spp at --study-size, same sample seed: SSIM of
    each half level against fp32, beside the noise floor (SSIM of two fp32
    renders with different seeds);
  * converged: --converged-spp at --size: relative MSE of each level against
    the reference, beside that of an fp32 render with another seed.
These go to OUT/precision.md. Both compare with fp32, so --precisions must
include it.

  tools/accuracy.py [--octrace build/app/octrace] [--device cpu] [--size 160x90] [--out docs/results/accuracy_lavapipe]
  tools/accuracy.py --replot DIR     (redraw DIR/accuracy.png from DIR/accuracy.csv)

Default settings run in a few minutes on lavapipe. Uses Debian's
python3-matplotlib (installed by tools/setup.sh). Bad input exits with 2
before any render; a render that fails ends the tool with octrace's error
line and its exit status, and removes OUT/tmp.
"""
import argparse
import csv
import json
import os
import sys

import tool_args

PRECISIONS = ["fp32", "fp16", "fp16-all"]


def depth_list(text):
    """Comma-separated bounce limits, each >= 1."""
    try:
        return [tool_args.positive_int(d) for d in text.split(",")]
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"expected whole numbers >= 1 separated by commas, got {text!r}")


def precision_list(text):
    """Comma-separated precisions octrace knows, fp32 among them."""
    names = text.split(",")
    for name in names:
        if name not in PRECISIONS:
            raise argparse.ArgumentTypeError(f"{name!r} is not one of {', '.join(PRECISIONS)}")
    if "fp32" not in names:
        raise argparse.ArgumentTypeError("must include fp32 (the precision targets compare against it)")
    return names


def remove_tmp(tmp):
    """Removes the renders in tmp (OUT/tmp) and the folder."""
    if os.path.isdir(tmp):
        for name in os.listdir(tmp):
            os.remove(os.path.join(tmp, name))
        os.rmdir(tmp)


class Octrace:
    def __init__(self, binary, device, scene_flags):
        self.binary, self.device, self.scene_flags = binary, device, scene_flags

    def render(self, path, size, spp, depth, precision, seed, extra=()):
        cmd = [self.binary, "render", "--json", "--quiet", "--device", self.device, "--size", size,
               "--spp", str(spp), "--depth", str(depth), "--precision", precision,
               "--sample-seed", str(seed), "--out", path] + self.scene_flags + list(extra)
        return json.loads(tool_args.run(cmd))

    def compare(self, test, reference):
        return json.loads(tool_args.run([self.binary, "compare", "--json", test, reference]))


def plot(rows, path, title):
    """Error against time, log-log, one line per precision and depth. Without
    matplotlib (e.g. on a GPU machine) it says so; --replot draws it later."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("accuracy: matplotlib not available: run tools/accuracy.py --replot DIR elsewhere", file=sys.stderr)
        return
    fig, ax = plt.subplots(figsize=(8.5, 6))
    styles = {"fp32": "-", "fp16": "--", "fp16-all": ":"}
    rr_color = "black"
    colors = {4: "tab:red", 8: "tab:orange", 16: "tab:green", 50: "tab:blue"}
    for precision in dict.fromkeys(r["precision"] for r in rows):
        for depth in dict.fromkeys(int(r["depth"]) for r in rows):
            pts = [r for r in rows if r["precision"] == precision and int(r["depth"]) == depth]
            if not pts:
                continue
            rr = "+rr" in precision
            nee_off = "+nee-off" in precision
            ax.plot([float(p["render_ms"]) for p in pts], [max(float(p["rel_mse"]), 1e-12) for p in pts],
                    "-." if rr or nee_off else styles.get(precision, "-"), marker="o", markersize=3,
                    color="tab:purple" if nee_off else rr_color if rr else colors.get(depth),
                    label=f"{precision} depth {depth}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time, ms (device)")
    ax.set_ylabel("relative MSE vs the fp32 reference")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def progress(msg):
    print(msg, file=sys.stderr, flush=True)


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", type=tool_args.executable, default="build/app/octrace")
    ap.add_argument("--device", default="auto")
    ap.add_argument("--size", type=tool_args.size, default="160x90", help="image size of the sweep and the converged test")
    ap.add_argument("--study-size", type=tool_args.size, default="1200x800", help="image size of the study's 10 spp comparison")
    ap.add_argument("--ref-spp", type=tool_args.positive_int, default=4096)
    ap.add_argument("--max-spp", type=tool_args.positive_int, default=256)
    ap.add_argument("--converged-spp", type=tool_args.positive_int, default=1024)
    ap.add_argument("--depths", type=depth_list, default="4,8,16,50")
    ap.add_argument("--precisions", type=precision_list, default=",".join(PRECISIONS))
    ap.add_argument("--rr-depth", type=int, default=3,
                    help="also sweep fp32 at depth 50 with Russian roulette from this bounce (0: no)")
    ap.add_argument("--nee-off", action="store_true",
                    help="also sweep fp32 at depth 50 with --nee off (the renders above use the default, on); "
                         "for scenes with lights, e.g. --scene-flags '--scene tools/nee/small_light.json'")
    ap.add_argument("--scene-flags", default="", help="extra scene flags for octrace render, e.g. '--spheres 1000'")
    ap.add_argument("--out", default="docs/results/accuracy")
    ap.add_argument("--replot", metavar="DIR", help="only redraw DIR/accuracy.png from DIR/accuracy.csv")
    args = ap.parse_args()

    if args.replot:
        for name in ("accuracy.csv", "accuracy.md"):
            if not os.path.isfile(os.path.join(args.replot, name)):
                tool_args.fail("accuracy.py", f"--replot {args.replot}: no {name} there")
        with open(os.path.join(args.replot, "accuracy.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        with open(os.path.join(args.replot, "accuracy.md")) as f:
            title = f.readline().split(".")[0]
        plot(rows, os.path.join(args.replot, "accuracy.png"), title)
        return

    if os.path.exists(args.out) and not os.path.isdir(args.out):
        tool_args.fail("accuracy.py", f"--out {args.out}: is a file, not a folder")
    created = not os.path.isdir(args.out)
    os.makedirs(args.out, exist_ok=True)
    tmp = os.path.join(args.out, "tmp")
    os.makedirs(tmp, exist_ok=True)
    try:
        measure_all(args, tmp)
    finally:
        remove_tmp(tmp)  # on success too: the renders are temporaries
        if created and not os.listdir(args.out):
            os.rmdir(args.out)  # a failure before any output: leave no empty folder
    print(open(os.path.join(args.out, "precision.md")).read())


def measure_all(args, tmp):
    """The sweep and the precision targets, renders in tmp."""
    o = Octrace(args.octrace, args.device, args.scene_flags.split())
    precisions = args.precisions
    depths = args.depths

    ref = os.path.join(tmp, "reference.pfm")
    progress(f"reference: fp32, {args.ref_spp} spp, {args.size}")
    ref_info = o.render(ref, args.size, args.ref_spp, 50, "fp32", 1000)
    device = ref_info["device"]

    rows = []
    spps = []
    s = 1
    while s <= args.max_spp:
        spps.append(s)
        s *= 2
    def measure(label, precision, depth, spp, extra=()):
        """One render of the sweep: its device time and its error against the reference."""
        path = os.path.join(tmp, f"{label}_{depth}_{spp}.pfm")
        info = o.render(path, args.size, spp, depth, precision, 1, extra)
        err = o.compare(path, ref)
        rows.append({"precision": label, "depth": depth, "spp": spp,
                     "render_ms": info["times_ms"]["render"], "rel_mse": err["rel_mse"],
                     "ssim": err["ssim"], "nonfinite": info["nonfinite_samples"]})

    for precision in precisions:
        for depth in depths:
            for spp in spps:
                measure(precision, precision, depth, spp)
            progress(f"sweep: {precision} depth {depth} done")
    if args.rr_depth > 0:
        for spp in spps:
            measure(f"fp32+rr{args.rr_depth}", "fp32", 50, spp, ["--rr-depth", str(args.rr_depth)])
        progress("sweep: Russian roulette done")
    if args.nee_off:
        for spp in spps:
            measure("fp32+nee-off", "fp32", 50, spp, ["--nee", "off"])
        progress("sweep: NEE off done")

    with open(os.path.join(args.out, "accuracy.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    header = (f"Device: {device['name']} ({device['type']}). Image {args.size}, scene "
              f"{ref_info['scene']['source']}; reference fp32 {args.ref_spp} spp (sample seed 1000); "
              f"renders with sample seed 1; time = device time of the passes.\n\n")
    with open(os.path.join(args.out, "accuracy.md"), "w") as f:
        f.write(header)
        f.write("| precision | depth | spp | render ms | rel MSE | SSIM | NaN/Inf samples |\n")
        f.write("|---|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            f.write(f"| {r['precision']} | {r['depth']} | {r['spp']} | {r['render_ms']:.1f} | "
                    f"{r['rel_mse']:.3g} | {r['ssim']:.4f} | {r['nonfinite']} |\n")

    plot(rows, os.path.join(args.out, "accuracy.png"),
         f"{device['name']}: {args.size}, spp 1..{args.max_spp}, reference {args.ref_spp} spp")

    # Precision targets.
    progress(f"study comparison: 10 spp at {args.study_size}")
    study = {}
    for precision in precisions:
        path = os.path.join(tmp, f"study_{precision}.pfm")
        info = o.render(path, args.study_size, 10, 50, precision, 1)
        study[precision] = (path, info)
    floor_path = os.path.join(tmp, "study_fp32_seed2.pfm")
    o.render(floor_path, args.study_size, 10, 50, "fp32", 2)
    floor = o.compare(floor_path, study["fp32"][0])
    progress(f"converged: {args.converged_spp} spp at {args.size}")
    conv = {}
    for precision in precisions:
        path = os.path.join(tmp, f"conv_{precision}.pfm")
        info = o.render(path, args.size, args.converged_spp, 50, precision, 1)
        conv[precision] = (o.compare(path, ref), info)
    conv_floor_path = os.path.join(tmp, "conv_fp32_seed2.pfm")
    o.render(conv_floor_path, args.size, args.converged_spp, 50, "fp32", 2)
    conv_floor = o.compare(conv_floor_path, ref)

    with open(os.path.join(args.out, "precision.md"), "w") as f:
        f.write(f"Device: {device['name']} ({device['type']}).\n\n")
        f.write(f"The study's comparison: {ref_info['scene']['source']}, {args.study_size}, 10 spp, depth 50, sample seed 1 for every "
                f"precision. Noise floor: SSIM between fp32 with seed 2 and fp32 with seed 1 = "
                f"**{floor['ssim']:.4f}**.\n\n")
        f.write("| precision | SSIM vs fp32 (same seed) | noise floor SSIM | render ms | NaN/Inf samples |\n")
        f.write("|---|---:|---:|---:|---:|\n")
        for precision in precisions:
            path, info = study[precision]
            ssim = o.compare(path, study["fp32"][0])["ssim"]
            f.write(f"| {precision} | {ssim:.6f} | {floor['ssim']:.4f} | {info['times_ms']['render']:.1f} | "
                    f"{info['nonfinite_samples']} |\n")
        f.write(f"\nConverged: {args.size}, {args.converged_spp} spp, against the fp32 reference "
                f"({args.ref_spp} spp, seed 1000). Noise floor: fp32 with another seed (2), relative MSE "
                f"**{conv_floor['rel_mse']:.3g}**.\n\n")
        f.write("| precision | rel MSE vs reference | ratio to the noise floor | SSIM | NaN/Inf samples |\n")
        f.write("|---|---:|---:|---:|---:|\n")
        for precision in precisions:
            err, info = conv[precision]
            f.write(f"| {precision} | {err['rel_mse']:.3g} | {err['rel_mse'] / conv_floor['rel_mse']:.2f} | "
                    f"{err['ssim']:.4f} | {info['nonfinite_samples']} |\n")


if __name__ == "__main__":
    main()
