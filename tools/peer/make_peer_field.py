#!/usr/bin/env python3
"""Writes the peer's scene recipe as an octrace JSON scene.

The peer (karimsayedre/CUDA-Ray-Tracing-In-One-Weekend, see
tools/peer/README.md) renders a fixed 488-sphere field. This writes the same
recipe with octrace's own random draws: the same counts, radii, positions'
distribution, material mix and camera, not the same individual spheres
(which come from the peer's RNG).

  ground   radius 1000 at (0, -1000, -1), lambertian 0.5
  grid     for a, b in -11..10: radius 0.2 at (a + U, 0.2, b + U), all 484
           kept (no exclusion zone); 80 % lambertian with albedo U^2 per
           channel, 15 % metal with albedo 0.5 (1 + U) and fuzz 0.5 U,
           5 % glass ior 1.5
  big      glass 1.5 at (0, 1, 0); lambertian (0.4, 0.2, 0.1) at (-4, 1, 0);
           metal (0.7, 0.6, 0.5) fuzz 0 at (4, 1, 0); all radius 1
  camera   pinhole at (13, 2, 3) looking at (0, 0, 0), up +y, vfov 20
  sky      RTIOW's gradient, white to (0.5, 0.7, 1.0)

Usage: make_peer_field.py OUT.json [--seed N]
"""
import argparse
import json
import random


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=134537)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    u = rng.random
    materials = [
        {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
        {"type": "dielectric", "ior": 1.5},
        {"type": "lambertian", "albedo": [0.4, 0.2, 0.1]},
        {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0.0},
    ]
    spheres = [
        {"center": [0, -1000, -1], "radius": 1000, "material": 0},
        {"center": [0, 1, 0], "radius": 1, "material": 1},
        {"center": [-4, 1, 0], "radius": 1, "material": 2},
        {"center": [4, 1, 0], "radius": 1, "material": 3},
    ]
    for a in range(-11, 11):
        for b in range(-11, 11):
            choose = u()
            center = [round(a + u(), 6), 0.2, round(b + u(), 6)]
            if choose < 0.8:
                m = {"type": "lambertian", "albedo": [round(u() ** 2, 6) for _ in range(3)]}
            elif choose < 0.95:
                m = {"type": "metal", "albedo": [round(0.5 * (1 + u()), 6) for _ in range(3)],
                     "fuzz": round(0.5 * u(), 6)}
            else:
                m = None
            if m is None:
                index = 1  # the shared glass
            else:
                materials.append(m)
                index = len(materials) - 1
            spheres.append({"center": center, "radius": 0.2, "material": index})
    scene = {
        "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 20,
                   "aperture": 0, "focus_dist": 10},
        "sky": {"type": "gradient", "down": [1, 1, 1], "up": [0.5, 0.7, 1]},
        "materials": materials,
        "spheres": spheres,
    }
    with open(args.out, "w") as f:
        json.dump(scene, f, indent=None, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
