#!/usr/bin/python3
"""Side by side: octrace's render of a glTF file and the same view drawn by
an independent glTF viewer (pyrender, a rasteriser on trimesh's glTF loader,
off-screen through Mesa's EGL), so that one can check that materials and
textures land where they should. The camera is octrace's own (its framing
camera or the file's, from `octrace render --dump-scene`); the rasteriser's
light is an ambient term plus a light at the camera, so its shading differs
by design; colours, textures and their placement must not.

  tools/viewer_compare.py --octrace build/app/octrace --scene model.glb --out docs/images/compare.png
      [--size 600x400] [--spp 64] [--device auto]

Needs the Python packages pyrender and trimesh (pip install pyrender trimesh)
and Debian's libegl1 and libegl-mesa0 (tools/setup.sh installs them). Bad
input exits with 2 before any render; where octrace fails, with its error line.
"""
import argparse
import json
import os
import sys
import tempfile

import tool_args

# Off-screen OpenGL through Mesa's EGL without a display (llvmpipe here).
os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
os.environ.setdefault("EGL_PLATFORM", "surfaceless")


def look_at_pose(eye, target, up):
    import numpy as np
    eye, target, up = (np.asarray(v, dtype=float) for v in (eye, target, up))
    z = eye - target
    z /= np.linalg.norm(z)
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = x, y, z, eye
    return pose


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", type=tool_args.executable, default="build/app/octrace")
    ap.add_argument("--scene", required=True, type=tool_args.input_file, help=".gltf or .glb")
    ap.add_argument("--out", required=True, type=tool_args.output_file, help="the side-by-side PNG")
    ap.add_argument("--size", type=tool_args.size, default="600x400")
    ap.add_argument("--spp", type=tool_args.positive_int, default=64)
    ap.add_argument("--device", default="auto")
    args = ap.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    # The viewer's modules, checked before the render.
    try:
        import numpy as np
        import pyrender
        import trimesh
        from PIL import Image, ImageDraw
    except ImportError as e:
        tool_args.fail("viewer_compare.py", f"needs the Python module {e.name or e} (pip install pyrender trimesh)")

    with tempfile.TemporaryDirectory() as tmp:
        dump, ours = os.path.join(tmp, "scene.json"), os.path.join(tmp, "octrace.png")
        # octrace's warnings passed on; where it fails, its error line and exit status.
        tool_args.run([args.octrace, "render", "--scene", args.scene, "--size", args.size, "--spp", str(args.spp),
                       "--device", args.device, "--quiet", "--dump-scene", dump, "--out", ours], echo_stderr=True)
        camera = json.load(open(dump))["camera"]
        octrace_image = Image.open(ours).convert("RGB")

    scene = pyrender.Scene.from_trimesh_scene(trimesh.load(args.scene), ambient_light=np.full(3, 0.35),
                                              bg_color=np.array([1.0, 1.0, 1.0, 1.0]))
    pose = look_at_pose(camera["lookfrom"], camera["lookat"], camera["vup"])
    scene.add(pyrender.PerspectiveCamera(yfov=np.radians(camera["vfov"]), aspectRatio=width / height), pose=pose)
    scene.add(pyrender.DirectionalLight(color=np.ones(3), intensity=3.0), pose=pose)
    renderer = pyrender.OffscreenRenderer(width, height)
    colour, _ = renderer.render(scene)
    renderer.delete()

    pair = Image.new("RGB", (2 * width, height + 24), "white")
    pair.paste(octrace_image, (0, 24))
    pair.paste(Image.fromarray(colour[:, :, :3]), (width, 24))
    draw = ImageDraw.Draw(pair)
    draw.text((8, 6), f"octrace, {args.spp} spp, its camera", fill="black")
    draw.text((width + 8, 6), "pyrender (rasteriser, trimesh glTF loader), same camera", fill="black")
    pair.save(args.out)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
