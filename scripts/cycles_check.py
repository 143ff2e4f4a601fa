#!/usr/bin/env python3
"""fovea against Blender Cycles on scenes both render (docs/benchmarks.md "... against Cycles").

Run from the repository root after a build (needs Debian's `blender`, not installed by
install-deps.sh: it is a cross-check, not a test):

    python3 scripts/cycles_check.py [--fovea build/fovea] [--out out/cycles] [--spp 1024]
                                    [--size 96] [--cases env:forest env:sunset normal alpha
                                    transform] [--no-ablate]

For each case it writes one glTF file, renders it converged with `fovea reference` and with Cycles
(`blender -b --factory-startup`, CPU, its glTF importer, which needs python3-numpy; this same
file is the Blender script; run the driver with Debian's /usr/bin/python3),
and compares the mean radiance of a 4x4 grid of regions. Cycles is set to what fovea computes:
Lambertian surfaces (each imported Principled BSDF replaced by a Diffuse BSDF of roughness 0 with
the same base colour), 8 indirect bounces (fovea's reference graph, maxBounces 8), a 1-pixel box
filter, no clamping, no light threshold, no denoiser, linear EXR output. The environment is the
same EXR, `Closest` interpolation (fovea reads texels without filtering).

Cases (the scenes are written by scripts/cycles_scenes.py, whose docstrings give the numbers):
- "env:<name>": a flat-shaded sphere (albedo 0.5) on a plane (albedo 0.8) lit only by
  /usr/share/blender/datafiles/studiolights/world/<name>.exr (blender-data, CC0);
- "normal": a normal-textured plane under a sun 20 degrees above the horizon;
- "alpha": an alphaMode MASK leaf card casting its holes' shadow on a plane;
- "transform": a box textured through KHR_texture_transform with MIRRORED_REPEAT/REPEAT, NEAREST.
For "normal" fovea runs with --set pt.bumpShadowing=true (Cycles' bump shadowing term on
diffuse closures, which Cycles always applies) and again with its defaults (plain glTF shading),
printed as a second grid. The sun cases set Blender's imported sun to fovea's reading of the glTF intensity (irradiance in
W/m2 at normal incidence, angle 0). For MASK materials the Blender side builds the cutoff itself
(alpha < cutoff selects a Transparent BSDF): the 3.4 importer only sets Eevee's alpha_threshold,
which Cycles ignores.

Unless --no-ablate, fovea also renders each non-env scene without its feature (normal texture
removed, alpha mode OPAQUE, transform removed) and the table gives that image's difference from
Cycles too: how far off a renderer that ignored the feature would be.
"""
import argparse
import glob
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_scenes  # noqa: E402
import shutil  # noqa: E402

# oiiotool (Debian's openimageio-tools) reads the images; fovea itself no longer needs it.
if shutil.which("oiiotool") is None:
    sys.exit("%s: needs oiiotool: apt-get install openimageio-tools" % os.path.basename(__file__))

HDRI_DIR = "/usr/share/blender/datafiles/studiolights/world"
GRID = 4


# --- inside Blender ---------------------------------------------------------------------------
def lambert_materials(bpy, masks):
    """Each imported Principled BSDF becomes a Diffuse BSDF (roughness 0) fed by the same base
    colour and normal (texture links kept); a MASK material mixes in a Transparent BSDF where
    alpha < cutoff (glTF 3.9.4: the texel is opaque when alpha >= cutoff)."""
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        for p in [n for n in nodes if n.type == "BSDF_PRINCIPLED"]:
            d = nodes.new("ShaderNodeBsdfDiffuse")
            d.inputs["Color"].default_value = p.inputs["Base Color"].default_value
            d.inputs["Roughness"].default_value = 0.0
            for name, target in (("Base Color", "Color"), ("Normal", "Normal")):
                for link in list(p.inputs[name].links):
                    links.new(link.from_socket, d.inputs[target])
            shader = d.outputs["BSDF"]
            alpha_links = list(p.inputs["Alpha"].links)
            if mat.name in masks and alpha_links:
                below = nodes.new("ShaderNodeMath")
                below.operation = "LESS_THAN"
                links.new(alpha_links[0].from_socket, below.inputs[0])
                below.inputs[1].default_value = masks[mat.name]
                mix = nodes.new("ShaderNodeMixShader")
                links.new(below.outputs["Value"], mix.inputs["Fac"])
                links.new(d.outputs["BSDF"], mix.inputs[1])
                links.new(nodes.new("ShaderNodeBsdfTransparent").outputs["BSDF"], mix.inputs[2])
                shader = mix.outputs["Shader"]
            for link in list(p.outputs["BSDF"].links):
                links.new(shader, link.to_socket)
            nodes.remove(p)


def blender_main(argv):
    import bpy  # noqa: F401 (only inside Blender)

    import numpy

    # Debian 12's Blender 3.4 glTF importer still says np.bool, which numpy 1.24 removed.
    if not hasattr(numpy, "bool"):
        numpy.bool = bool
    args = json.loads(argv[0])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=args["gltf"])
    with open(args["gltf"]) as f:
        doc = json.load(f)
    masks = {m["name"]: m.get("alphaCutoff", 0.5) for m in doc["materials"]
             if m.get("alphaMode") == "MASK"}
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    scene = bpy.context.scene
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    scene.camera = cams[0]
    cams[0].data.sensor_fit = "VERTICAL"
    cams[0].data.angle_y = cycles_scenes.YFOV
    for o in scene.objects:
        if o.type == "LIGHT" and o.data.type == "SUN":
            # fovea reads a directional intensity as irradiance at normal incidence; a Cycles
            # sun's strength is the same quantity. Angle 0: a delta light, as fovea's.
            o.data.energy = lights[0]["intensity"]
            o.data.angle = 0.0
    lambert_materials(bpy, masks)
    world = bpy.data.worlds.new("env")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    if args["hdri"]:
        tex = nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(args["hdri"])
        tex.interpolation = "Closest"
        tex.projection = "EQUIRECTANGULAR"
        links.new(tex.outputs["Color"], nodes["Background"].inputs["Color"])
        nodes["Background"].inputs["Strength"].default_value = 1.0
    else:
        nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args["spp"]
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = c.diffuse_bounces = 8
    c.glossy_bounces = c.transmission_bounces = c.volume_bounces = 8
    c.transparent_max_bounces = 64  # fovea's any-hit test has no limit on skipped surfaces
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = args.get("seed", 1)
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


# Cycles multiplies diffuse closures by Chiang et al.'s bump shadowing term wherever a normal map
# bends the normal; fovea does so with pt.bumpShadowing (default off: plain glTF shading).
CYCLES_SETTINGS = {"normal": ["pt.bumpShadowing=true"]}


def fovea_render(o, gltf, hdri, out_dir, settings=()):
    cmd = [o.fovea, "reference", "--scene", gltf, "--camera", "gltf:0", "--spp", str(o.spp),
           "--size", "%dx%d" % (o.size, o.size), "--out", out_dir, "--overwrite", "--quiet"]
    if hdri:
        cmd += ["--env", hdri]
    for setting in settings:
        cmd += ["--set", setting]
    subprocess.run(cmd, check=True)
    return sorted(glob.glob(os.path.join(out_dir, "acc.mean*.exr")))[-1]


def relative(fr, cr):
    return [[fr[y][x] / cr[y][x] - 1.0 if cr[y][x] > 0 else float("nan") for x in range(GRID)]
            for y in range(GRID)]


def print_grid(title, diffs):
    print(title)
    for row in diffs:
        print("   " + "  ".join("%+6.2f %%" % (100 * d) for d in row))


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
    ap.add_argument("--cases", nargs="+",
                    default=["env:forest", "env:sunset", "normal", "alpha", "transform"])
    ap.add_argument("--no-ablate", action="store_true")
    o = ap.parse_args()
    o.out = os.path.abspath(o.out)
    results = []
    for case in o.cases:
        name = case.replace(":", "_")
        case_dir = os.path.join(o.out, name)
        os.makedirs(case_dir, exist_ok=True)
        gltf = os.path.join(case_dir, name + ".gltf")
        hdri = None
        if case.startswith("env:"):
            hdri = os.path.join(HDRI_DIR, case[4:] + ".exr")
            cycles_scenes.env_scene(gltf)
        elif case in cycles_scenes.CASES:
            cycles_scenes.CASES[case](gltf)
        else:
            sys.exit("cycles_check.py: unknown case '%s'" % case)
        settings = CYCLES_SETTINGS.get(case, [])
        fimg = fovea_render(o, gltf, hdri, os.path.join(case_dir, "fovea"), settings)
        cimg = os.path.join(case_dir, "cycles.exr")
        args = json.dumps({"gltf": gltf, "hdri": hdri, "spp": o.spp, "size": o.size, "out": cimg})
        env = dict(os.environ, FOVEA_IN_BLENDER="1")
        subprocess.run([o.blender, "-b", "--factory-startup", "--python", os.path.abspath(__file__),
                        "--", args], check=True, env=env, stdout=subprocess.DEVNULL)
        fr, fmean = read_exr(fimg)
        cr, cmean = read_exr(cimg)
        result = {"case": case, "fovea_mean": fmean, "cycles_mean": cmean, "regions_fovea": fr,
                  "regions_cycles": cr, "relative_difference": relative(fr, cr)}
        print_grid("%s  mean fovea %.5f  cycles %.5f  (%+.2f %%)" %
                   (case, fmean, cmean, 100 * (fmean / cmean - 1)), result["relative_difference"])
        result["fovea_settings"] = settings
        if settings:
            dr, dmean = read_exr(fovea_render(o, gltf, hdri, os.path.join(case_dir, "default")))
            result.update({"default_mean": dmean, "regions_default": dr,
                           "default_relative_difference": relative(dr, cr)})
            print_grid("%s with fovea's defaults (without %s): mean %.5f (%+.2f %%)" %
                       (case, " ".join(settings), dmean, 100 * (dmean / cmean - 1)),
                       relative(dr, cr))
        if not hdri and not o.no_ablate:
            ablated = os.path.join(case_dir, name + "_without.gltf")
            cycles_scenes.CASES[case](ablated, ablate=True)
            ar, amean = read_exr(fovea_render(o, ablated, None, os.path.join(case_dir, "without"),
                                              settings))
            result.update({"without_mean": amean, "regions_without": ar,
                           "without_relative_difference": relative(ar, cr)})
            print_grid("%s without the feature: mean %.5f (%+.2f %%)" %
                       (case, amean, 100 * (amean / cmean - 1)), relative(ar, cr))
        results.append(result)
    with open(os.path.join(o.out, "cycles_check.json"), "w") as f:
        json.dump({"spp": o.spp, "size": o.size, "grid": GRID, "results": results}, f, indent=1)


if __name__ == "__main__":
    main()
