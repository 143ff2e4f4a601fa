#!/usr/bin/env python3
"""fovea against Blender Cycles on scenes both render (docs/benchmarks.md "... against Cycles").

Run from the repository root after a build (needs Debian's `blender`, not installed by
install-deps.sh: it is a cross-check, not a test):

    python3 scripts/cycles_check.py [--fovea build/fovea] [--out out/cycles] [--spp 1024]
                                    [--size 96] [--hdri forest sunset]

For each case it writes one glTF file, renders it converged with `fovea reference` and with Cycles
(`blender -b --factory-startup`, CPU, its glTF importer, which needs python3-numpy; this same
file is the Blender script; run the driver with Debian's /usr/bin/python3),
and compares the mean radiance of a 4x4 grid of regions. Cycles is set to what fovea computes:
Lambertian surfaces (each imported Principled BSDF replaced by a Diffuse BSDF of roughness 0 with
the same base colour), 8 indirect bounces (fovea's reference graph, maxBounces 8), a 1-pixel box
filter, no clamping, no light threshold, no denoiser, linear EXR output. The environment is the
same EXR, `Closest` interpolation (fovea reads texels without filtering).

Cases: "env:<name>": a flat-shaded sphere (albedo 0.5) on a plane (albedo 0.8) lit only by
/usr/share/blender/datafiles/studiolights/world/<name>.exr (blender-data, CC0).
"""
import argparse
import glob
import json
import math
import os
import struct
import subprocess
import sys

HDRI_DIR = "/usr/share/blender/datafiles/studiolights/world"
GRID = 4


# --- the scene ------------------------------------------------------------------------------
def sphere_triangles(rings=16, segments=32):
    def point(r, s):
        t, p = math.pi * r / rings, 2 * math.pi * s / segments
        return (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))

    tris = []
    for r in range(rings):
        for s in range(segments):
            a, b, c, d = point(r, s), point(r, s + 1), point(r + 1, s + 1), point(r + 1, s)
            # Counter-clockwise seen from outside (glTF front faces).
            if r > 0:
                tris.append((a, c, b))
            if r < rings - 1:
                tris.append((a, d, c))
    return tris


def write_gltf(path):
    """Sphere + ground plane + camera; no NORMAL attribute: both renderers shade flat."""
    sphere = sphere_triangles()
    k = 6.0
    plane = [((-k, -1, -k), (-k, -1, k), (k, -1, k)), ((-k, -1, -k), (k, -1, k), (k, -1, -k))]
    meshes_data = []
    blob = b""
    accessors, views, meshes = [], [], []
    for index, tris in enumerate([sphere, plane]):
        floats = [c for t in tris for v in t for c in v]
        data = struct.pack("<%df" % len(floats), *floats)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        xs, ys, zs = floats[0::3], floats[1::3], floats[2::3]
        accessors.append({"bufferView": index, "componentType": 5126, "count": len(tris) * 3,
                          "type": "VEC3", "min": [min(xs), min(ys), min(zs)],
                          "max": [max(xs), max(ys), max(zs)]})
        meshes.append({"primitives": [{"attributes": {"POSITION": index}, "material": index}]})
        blob += data
    a = math.atan2(1.0, 5.5)  # pitch down towards (0, -0.2, 0) from (0, 0.8, 5.5)
    gltf = {
        "asset": {"version": "2.0", "generator": "fovea scripts/cycles_check.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0}, {"mesh": 1},
                  {"camera": 0, "translation": [0, 0.8, 5.5],
                   "rotation": [math.sin(-a / 2), 0, 0, math.cos(-a / 2)]}],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.7, "znear": 0.01, "aspectRatio": 1.0}}],
        "meshes": meshes,
        "materials": [
            {"name": "sphere", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                                        "metallicFactor": 0, "roughnessFactor": 1}},
            {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                                                        "metallicFactor": 0, "roughnessFactor": 1}}],
        "buffers": [{"uri": os.path.basename(path) + ".bin", "byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(path + ".bin", "wb") as f:
        f.write(blob)
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)


# --- inside Blender ---------------------------------------------------------------------------
def blender_main(argv):
    import bpy  # noqa: F401 (only inside Blender)

    import numpy

    # Debian 12's Blender 3.4 glTF importer still says np.bool, which numpy 1.24 removed.
    if not hasattr(numpy, "bool"):
        numpy.bool = bool
    args = json.loads(argv[0])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=args["gltf"])
    scene = bpy.context.scene
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    scene.camera = cams[0]
    cams[0].data.sensor_fit = "VERTICAL"
    cams[0].data.angle_y = 0.7
    # Lambert: Diffuse BSDF (roughness 0) with the Principled BSDF's base colour.
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        for p in [n for n in nodes if n.type == "BSDF_PRINCIPLED"]:
            d = nodes.new("ShaderNodeBsdfDiffuse")
            d.inputs["Color"].default_value = p.inputs["Base Color"].default_value
            d.inputs["Roughness"].default_value = 0.0
            for link in list(links):
                if link.from_node == p:
                    links.new(d.outputs["BSDF"], link.to_socket)
            nodes.remove(p)
    world = bpy.data.worlds.new("env")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    tex = nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(args["hdri"])
    tex.interpolation = "Closest"
    tex.projection = "EQUIRECTANGULAR"
    links.new(tex.outputs["Color"], nodes["Background"].inputs["Color"])
    nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args["spp"]
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = c.diffuse_bounces = 8
    c.glossy_bounces = c.transmission_bounces = c.volume_bounces = c.transparent_max_bounces = 8
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = 1
    scene.render.resolution_x = scene.render.resolution_y = args["size"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = args["out"]
    bpy.ops.render.render(write_still=True)


# --- the driver ---------------------------------------------------------------------------------
def read_exr(path):
    """Mean-of-RGB per region via oiiotool (rows top first), as a GRID x GRID list."""
    out = subprocess.run(["oiiotool", "--info", "-v", "--dumpdata", path],
                         capture_output=True, text=True, check=True).stdout
    pixels = {}
    width = height = 0
    for line in out.splitlines():
        line = line.strip()
        if not line.startswith("Pixel ("):
            continue
        coords, values = line[7:].split("):")
        x, y = (int(v) for v in coords.split(","))
        rgb = [float(v) for v in values.split()[:3]]  # R, G, B (then A)
        pixels[(x, y)] = sum(rgb) / 3.0
        width, height = max(width, x + 1), max(height, y + 1)
    regions = []
    for gy in range(GRID):
        row = []
        for gx in range(GRID):
            xs = range(gx * width // GRID, (gx + 1) * width // GRID)
            ys = range(gy * height // GRID, (gy + 1) * height // GRID)
            row.append(sum(pixels[(x, y)] for x in xs for y in ys) / (len(xs) * len(ys)))
        regions.append(row)
    return regions, sum(pixels.values()) / len(pixels)


def main():
    if os.environ.get("FOVEA_IN_BLENDER"):
        blender_main(sys.argv[sys.argv.index("--") + 1:])
        return
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fovea", default="build/fovea")
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--out", default="out/cycles")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--hdri", nargs="+", default=["forest", "sunset"])
    o = ap.parse_args()
    os.makedirs(o.out, exist_ok=True)
    gltf = os.path.abspath(os.path.join(o.out, "sphere_plane.gltf"))
    write_gltf(gltf)
    results = []
    for name in o.hdri:
        hdri = os.path.join(HDRI_DIR, name + ".exr")
        fdir = os.path.abspath(os.path.join(o.out, "fovea_" + name))
        subprocess.run([o.fovea, "reference", "--scene", gltf, "--camera", "gltf:0", "--env", hdri,
                        "--spp", str(o.spp), "--size", "%dx%d" % (o.size, o.size), "--out", fdir,
                        "--overwrite", "--quiet"], check=True)
        fimg = sorted(glob.glob(os.path.join(fdir, "acc.mean*.exr")))[-1]
        cimg = os.path.abspath(os.path.join(o.out, "cycles_" + name + ".exr"))
        args = json.dumps({"gltf": gltf, "hdri": hdri, "spp": o.spp, "size": o.size, "out": cimg})
        env = dict(os.environ, FOVEA_IN_BLENDER="1")
        subprocess.run([o.blender, "-b", "--factory-startup", "--python", os.path.abspath(__file__),
                        "--", args], check=True, env=env, stdout=subprocess.DEVNULL)
        fr, fmean = read_exr(fimg)
        cr, cmean = read_exr(cimg)
        diffs = [[fr[y][x] / cr[y][x] - 1.0 if cr[y][x] > 0 else float("nan")
                  for x in range(GRID)] for y in range(GRID)]
        results.append({"case": "env:" + name, "fovea_mean": fmean, "cycles_mean": cmean,
                        "regions_fovea": fr, "regions_cycles": cr, "relative_difference": diffs})
        print("env:%s  mean fovea %.5f  cycles %.5f  (%+.2f %%)" %
              (name, fmean, cmean, 100 * (fmean / cmean - 1)))
        for row in diffs:
            print("   " + "  ".join("%+6.2f %%" % (100 * d) for d in row))
    with open(os.path.join(o.out, "cycles_check.json"), "w") as f:
        json.dump({"spp": o.spp, "size": o.size, "grid": GRID, "results": results}, f, indent=1)


if __name__ == "__main__":
    main()
