#!/usr/bin/env python3
"""Session 55's measurement of llvmpipe's loop limit under brute force
(docs/reliability.md, the brute-force warning): render_test's light trap
(test::light_trap_scene: a fuzz-0.6 mirror sphere r = 5 around small white
spheres r = 0.04 and an emitter r = 0.15, the camera inside) with 1,000
small spheres instead of 20,000, written as a JSON scene, rendered with
`--accel brute` on the CPU device at several depths, with and without
next-event estimation and the tail levels; prints each render's
`cut_paths` and rays (render --json) and whether octrace warned before it.

  python3 loop_limit.py OCTRACE [OUT_DIR]
"""
import json
import os
import subprocess
import sys


def trap_scene(count):
    state = 3

    def nxt():
        nonlocal state
        state = (state * 1664525 + 1013904223) & 0xFFFFFFFF
        return (state >> 8) / float(1 << 24) * 6.8 - 3.4

    spheres = [{"center": [0, 0, 0], "radius": 5.0, "material": 0},
               {"center": [3, 3, 0], "radius": 0.15, "material": 2}]
    while len(spheres) < count + 2:
        c = (nxt(), nxt(), nxt())
        if sum(x * x for x in c) > 3.4 ** 2 or (c[0] ** 2 + c[1] ** 2 < 0.3 and c[2] > 0):
            continue
        spheres.append({"center": list(c), "radius": 0.04, "material": 1})
    return {"camera": {"lookfrom": [0, 0, 4.5], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 60,
                       "aperture": 0, "focus_dist": 4.5},
            "sky": {"type": "gradient", "down": [0, 0, 0], "up": [0, 0, 0]},
            "materials": [{"type": "metal", "albedo": [1, 1, 1], "fuzz": 0.6},
                          {"type": "lambertian", "albedo": [1, 1, 1]},
                          {"type": "emissive", "radiance": [4, 4, 4]}],
            "spheres": spheres}


def main():
    octrace = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else "/tmp"
    scene = os.path.join(out, "trap1000.json")
    with open(scene, "w") as f:
        json.dump(trap_scene(1000), f)
    env = dict(os.environ, XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp"))
    runs = [("160x120", d, nee, "") for nee in ("on", "off") for d in (40, 60, 64)]
    runs += [("320x240", 200, "on", "--tail-depth off"), ("320x240", 200, "on", ""),
             ("320x240", 128, "off", "--tail-depth off"), ("320x240", 128, "off", "")]
    print("| size | depth | nee | flags | warned before | cut_paths | rays |")
    print("|---|---:|---|---|---|---:|---:|")
    for size, depth, nee, flags in runs:
        cmd = [octrace, "render", "--device", "cpu", "--scene", scene, "--size", size, "--spp", "1",
               "--depth", str(depth), "--accel", "brute", "--nee", nee, "--json", "-q",
               "-o", os.path.join(out, "trap.pfm")] + flags.split()
        p = subprocess.run(cmd, capture_output=True, text=True, env=env, check=True)
        r = json.loads(p.stdout)
        warned = "yes" if "ends a shader loop" in p.stderr else "no"
        print(f"| {size} | {depth} | {nee} | {flags or '(auto)'} | {warned} | {r['cut_paths']} | {r['rays']} |",
              flush=True)


if __name__ == "__main__":
    main()
