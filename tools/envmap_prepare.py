#!/usr/bin/env python3
"""Makes an HDR environment map octrace can load: reads an OpenEXR file of any
compression (Debian's blender-data HDRIs are DWAB, which tinyexr cannot read),
sets its negative channels to 0 (lossy compression rings slightly below 0 near
bright edges: octrace refuses negative radiance rather than guess), and writes
it as a ZIP-compressed float EXR. Says how many channels it changed and how far
below 0 they went; refuses NaN and infinite texels.

    tools/envmap_prepare.py IN.exr OUT.exr

An alpha channel is ignored. Bad input (a missing or unreadable EXR, one
without R, G and B, NaN or infinite texels, OUT in a folder that does not
exist) exits with 2.

Needs the Python packages OpenEXR and numpy (pip install OpenEXR numpy).
"""
import os
import sys

import tool_args


def main():
    parser = tool_args.Parser(description=__doc__.splitlines()[0])
    parser.add_argument("input", type=tool_args.input_file)
    parser.add_argument("output", type=tool_args.output_file)
    args = parser.parse_args()
    try:
        import numpy as np
        import OpenEXR
    except ImportError as e:
        tool_args.fail("envmap_prepare.py", f"needs the Python module {e.name or e} (pip install OpenEXR numpy)")
    try:
        exr = OpenEXR.File(args.input)
    except RuntimeError:
        tool_args.fail("envmap_prepare.py", f"{args.input}: not a readable OpenEXR file")
    with exr as f:
        channels = f.channels()
        # OpenEXR groups R, G, B (and A) into one "RGB" or "RGBA" entry;
        # files with other channels too may keep them apart. Alpha is ignored.
        if "RGB" in channels or "RGBA" in channels:
            rgb = np.asarray(channels["RGB" if "RGB" in channels else "RGBA"].pixels, dtype=np.float32)[..., :3]
        elif all(c in channels for c in "RGB"):
            rgb = np.stack([np.asarray(channels[c].pixels, dtype=np.float32) for c in "RGB"], axis=-1)
        else:
            tool_args.fail("envmap_prepare.py", f"{args.input}: no R, G and B channels (found {', '.join(channels)})")
    if not np.isfinite(rgb).all():
        tool_args.fail("envmap_prepare.py",
                       f"{args.input}: {int((~np.isfinite(rgb)).sum())} channels are NaN or infinite")
    negative = rgb < 0
    print(f"{args.input}: {rgb.shape[1]}x{rgb.shape[0]}, {int(negative.sum())} negative channels set to 0"
          f" (lowest {float(rgb.min()):.3g}), largest value {float(rgb.max()):.6g}")
    rgb = np.where(negative, np.float32(0), rgb)
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    existed = os.path.exists(args.output)
    try:
        with OpenEXR.File(header, {"RGB": np.ascontiguousarray(rgb)}) as out:
            out.write(args.output)
    except RuntimeError as e:
        if not existed and os.path.exists(args.output):
            os.remove(args.output)  # no half-written file
        tool_args.fail("envmap_prepare.py", f"{args.output}: cannot write it ({e})")


if __name__ == "__main__":
    main()
