#!/usr/bin/env python3
"""Makes an HDR environment map octrace can load: reads an OpenEXR file of any
compression (Debian's blender-data HDRIs are DWAB, which tinyexr cannot read),
sets its negative channels to 0 (lossy compression rings slightly below 0 near
bright edges: octrace refuses negative radiance rather than guess), and writes
it as a ZIP-compressed float EXR. Says how many channels it changed and how far
below 0 they went; refuses NaN and infinite texels.

    tools/envmap_prepare.py IN.exr OUT.exr

Needs the Python packages OpenEXR and numpy (pip install OpenEXR numpy).
"""
import argparse
import sys

import numpy as np
import OpenEXR


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input")
    parser.add_argument("output")
    args = parser.parse_args()
    with OpenEXR.File(args.input) as f:
        channels = f.channels()
        if "RGB" in channels:
            rgb = np.asarray(channels["RGB"].pixels, dtype=np.float32)
        elif all(c in channels for c in "RGB"):
            rgb = np.stack([np.asarray(channels[c].pixels, dtype=np.float32) for c in "RGB"], axis=-1)
        else:
            sys.exit(f"{args.input}: no R, G and B channels (found {', '.join(channels)})")
    if not np.isfinite(rgb).all():
        sys.exit(f"{args.input}: {int((~np.isfinite(rgb)).sum())} channels are NaN or infinite")
    negative = rgb < 0
    print(f"{args.input}: {rgb.shape[1]}x{rgb.shape[0]}, {int(negative.sum())} negative channels set to 0"
          f" (lowest {float(rgb.min()):.3g}), largest value {float(rgb.max()):.6g}")
    rgb = np.where(negative, np.float32(0), rgb)
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with OpenEXR.File(header, {"RGB": np.ascontiguousarray(rgb)}) as out:
        out.write(args.output)


if __name__ == "__main__":
    main()
