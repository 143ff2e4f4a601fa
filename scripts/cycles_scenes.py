"""The glTF scenes of scripts/cycles_check.py: each written once and rendered by fovea and Cycles.

Every scene is a glTF 2.0 file with its buffers in one .bin and its textures as PNG files next to
it, one perspective camera (yfov 0.7, square) and, where it is lit by a sun, one
KHR_lights_punctual directional light. Each writer takes `ablate`: the same scene without the
feature under test (normal texture removed, alpha mode OPAQUE, texture transform removed), which
fovea renders too, so the table shows how far a renderer that ignored the feature would be off.
Only the standard library (the PNGs are written with zlib).
"""
import json
import math
import os
import struct
import zlib

YFOV = 0.7


def write_png(path, width, height, texels):
    """RGBA8 PNG from a list of (r, g, b, a) byte tuples, rows top first."""
    raw = b"".join(b"\0" + bytes(c for t in texels[y * width:(y + 1) * width] for c in t)
                   for y in range(height))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
                + chunk(b"IEND", b""))


def look_at_rotation(eye, target):
    """Quaternion (x, y, z, w) turning the glTF camera (looking down -Z, +Y up) towards target."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    yaw = math.atan2(-f[0], -f[2])
    pitch = math.asin(max(-1.0, min(1.0, f[1])))
    qy = (0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2))
    qx = (math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2))
    return quat_mul(qy, qx)


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


class Gltf:
    """A small glTF writer: meshes of triangles with per-vertex attributes, materials, textures."""

    def __init__(self):
        self.blob = b""
        self.doc = {"asset": {"version": "2.0", "generator": "fovea scripts/cycles_scenes.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": []}

    def _accessor(self, values, kind, width):
        data = struct.pack("<%df" % len(values), *values)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.blob),
                                        "byteLength": len(data)})
        self.blob += data
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": 5126,
               "count": len(values) // width, "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, positions, material, normals=None, uvs=None):
        """Non-indexed triangles: positions (and normals, uvs) one tuple per vertex."""
        attributes = {"POSITION": self._accessor([c for p in positions for c in p], "VEC3", 3)}
        if normals:
            attributes["NORMAL"] = self._accessor([c for n in normals for c in n], "VEC3", 3)
        if uvs:
            attributes["TEXCOORD_0"] = self._accessor([c for t in uvs for c in t], "VEC2", 2)
        self.doc["meshes"].append({"primitives": [{"attributes": attributes,
                                                   "material": material}]})
        self.doc["nodes"].append({"mesh": len(self.doc["meshes"]) - 1})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def material(self, name, color, **extra):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1.0],
                                                    "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        m.update(extra)
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def texture(self, uri, mag, min_filter, wrap_s, wrap_t):
        d = self.doc
        d.setdefault("images", []).append({"uri": uri})
        d.setdefault("samplers", []).append({"magFilter": mag, "minFilter": min_filter,
                                             "wrapS": wrap_s, "wrapT": wrap_t})
        d.setdefault("textures", []).append({"source": len(d["images"]) - 1,
                                             "sampler": len(d["samplers"]) - 1})
        return len(d["textures"]) - 1

    def camera(self, eye, target):
        self.doc["cameras"] = [{"type": "perspective",
                                "perspective": {"yfov": YFOV, "znear": 0.01, "aspectRatio": 1.0}}]
        self.doc["nodes"].append({"camera": 0, "translation": list(eye),
                                  "rotation": list(look_at_rotation(eye, target))})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def sun(self, towards, irradiance):
        """A directional light travelling along `towards` (glTF lights shine down their -Z)."""
        d = self.doc
        d.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
        d.setdefault("extensions", {})["KHR_lights_punctual"] = {
            "lights": [{"type": "directional", "intensity": irradiance, "name": "sun"}]}
        # The rotation that turns -Z into `towards` is a camera look-at from 0 to `towards`.
        d["nodes"].append({"rotation": list(look_at_rotation((0, 0, 0), towards)),
                           "extensions": {"KHR_lights_punctual": {"light": 0}}})
        d["scenes"][0]["nodes"].append(len(d["nodes"]) - 1)

    def save(self, path):
        if "KHR_texture_transform" in json.dumps(self.doc["materials"]):
            self.doc.setdefault("extensionsUsed", []).append("KHR_texture_transform")
        self.doc["buffers"] = [{"uri": os.path.basename(path) + ".bin",
                                "byteLength": len(self.blob)}]
        with open(path + ".bin", "wb") as f:
            f.write(self.blob)
        with open(path, "w") as f:
            json.dump(self.doc, f, indent=1)


def quad(g, corners, material, uv=((0, 0), (0, 1), (1, 1), (1, 0)), normal=None):
    """Two triangles a b c, a c d; corners counter-clockwise seen from the front."""
    a, b, c, d = corners
    ua, ub, uc, ud = uv
    g.mesh([a, b, c, a, c, d], material, [normal] * 6 if normal else None,
           [ua, ub, uc, ua, uc, ud])


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


# --- the cases --------------------------------------------------------------------------------
def env_scene(path, ablate=False):
    """A flat-shaded sphere (albedo 0.5) on a plane (0.8); the light is the driver's --env map."""
    g = Gltf()
    sphere = g.material("sphere", (0.5, 0.5, 0.5))
    ground = g.material("ground", (0.8, 0.8, 0.8))
    g.mesh([v for t in sphere_triangles() for v in t], sphere)
    k = 6.0
    quad(g, [(-k, -1, -k), (-k, -1, k), (k, -1, k), (k, -1, -k)], ground)
    g.camera((0, 0.8, 5.5), (0, -0.2, 0))
    g.save(path)


def normal_map_scene(path, ablate=False):
    """A 12 x 12 m plane (albedo 0.8) whose normal texture tilts the normal by up to 20 degrees
    about the v axis in stripes (4 periods per texture, the texture repeated 6 times: 0.5 m
    stripes), under a sun 20 degrees above the horizon travelling along -x: across the stripes,
    so n.L swings between about 0 and 0.64 (flat: 0.34)."""
    width, tilt = 256, math.radians(20.0)
    texels = []
    for _ in range(4):
        for i in range(width):
            t = tilt * math.sin(2 * math.pi * 4 * (i + 0.5) / width)
            n = (math.sin(t), 0.0, math.cos(t))  # tangent space: x along +u, z out of the surface
            texels.append(tuple(int(round((c * 0.5 + 0.5) * 255)) for c in n) + (255,))
    write_png(os.path.join(os.path.dirname(path), "normal_stripes.png"), width, 4, texels)
    g = Gltf()
    extra = {}
    if not ablate:
        tex = g.texture("normal_stripes.png", 9729, 9729, 10497, 10497)  # LINEAR, REPEAT
        extra["normalTexture"] = {"index": tex, "scale": 1.0}
    plane = g.material("plane", (0.8, 0.8, 0.8), **extra)
    k = 6.0
    # u runs along +x (the tangent), v along +z; 6 repeats over the 12 m.
    quad(g, [(-k, 0, -k), (-k, 0, k), (k, 0, k), (k, 0, -k)], plane,
         uv=((0, 0), (0, 6), (6, 6), (6, 0)), normal=(0, 1, 0))
    g.camera((0, 4, 2.5), (0, 0, 0))
    e = math.radians(20.0)
    g.sun((-math.cos(e), -math.sin(e), 0.0), 3.0)
    g.save(path)


def alpha_scene(path, ablate=False):
    """A horizontal leaf card 1 m above a ground plane (0.8), double-sided, green, alphaMode MASK
    with the default cutoff 0.5 over an 8 x 8 NEAREST texture whose alpha is 0.3 or 0.8 in a
    checker with a round hole: the card shows the ground through its holes and casts their
    pattern as a shadow. The alpha values are not 0 and 1, so a renderer that treated alpha as
    coverage (BLEND) would be off too."""
    texels = []
    for y in range(8):
        for x in range(8):
            hole = (x + y) % 2 == 0 or (x - 3.5) ** 2 + (y - 3.5) ** 2 < 3.0
            texels.append((90, 170, 60, int(round((0.3 if hole else 0.8) * 255))))
    write_png(os.path.join(os.path.dirname(path), "leaf_checker.png"), 8, 8, texels)
    g = Gltf()
    tex = g.texture("leaf_checker.png", 9728, 9728, 33071, 33071)  # NEAREST, CLAMP_TO_EDGE
    extra = {"doubleSided": True}
    if not ablate:
        extra.update({"alphaMode": "MASK", "alphaCutoff": 0.5})
    card = g.material("card", (1.0, 1.0, 1.0), **extra)
    g.doc["materials"][card]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": tex}
    ground = g.material("ground", (0.8, 0.8, 0.8))
    k = 6.0
    quad(g, [(-k, 0, -k), (-k, 0, k), (k, 0, k), (k, 0, -k)], ground, normal=(0, 1, 0))
    s = 0.8
    quad(g, [(-s, 1, -s), (-s, 1, s), (s, 1, s), (s, 1, -s)], card, normal=(0, 1, 0))
    g.camera((0.2, 3.2, 2.6), (0.35, 0.3, 0))
    g.sun((0.45, -1.0, 0.15), 3.0)
    g.save(path)


def transform_scene(path, ablate=False):
    """A 1.2 m box on a ground plane (0.5), its six faces carrying one 8 x 8 texture of saturated
    colours (NEAREST) through KHR_texture_transform (offset, rotation, scale) with wrapS
    MIRRORED_REPEAT and wrapT REPEAT, under a sun from the upper left so three visible faces
    differ."""
    palette = [(230, 40, 40), (40, 200, 60), (40, 80, 230), (240, 220, 40), (230, 60, 220),
               (40, 220, 220), (250, 250, 250), (20, 20, 20)]
    texels = [palette[(3 * x + 5 * y + x * y) % 8] + (255,) for y in range(8) for x in range(8)]
    write_png(os.path.join(os.path.dirname(path), "box_palette.png"), 8, 8, texels)
    g = Gltf()
    tex = g.texture("box_palette.png", 9728, 9728, 33648, 10497)  # NEAREST, MIRRORED / REPEAT
    info = {"index": tex}
    if not ablate:
        info["extensions"] = {"KHR_texture_transform": {"offset": [0.2, 0.1], "rotation": 0.5,
                                                        "scale": [2.5, 1.5]}}
    box = g.material("box", (1.0, 1.0, 1.0))
    g.doc["materials"][box]["pbrMetallicRoughness"]["baseColorTexture"] = info
    ground = g.material("ground", (0.5, 0.5, 0.5))
    k = 6.0
    quad(g, [(-k, 0, -k), (-k, 0, k), (k, 0, k), (k, 0, -k)], ground, normal=(0, 1, 0))
    h = 0.6
    faces = [  # (normal, four corners counter-clockwise seen from outside)
        ((0, 0, 1), [(-h, 2 * h, h), (-h, 0, h), (h, 0, h), (h, 2 * h, h)]),
        ((0, 0, -1), [(h, 2 * h, -h), (h, 0, -h), (-h, 0, -h), (-h, 2 * h, -h)]),
        ((1, 0, 0), [(h, 2 * h, h), (h, 0, h), (h, 0, -h), (h, 2 * h, -h)]),
        ((-1, 0, 0), [(-h, 2 * h, -h), (-h, 0, -h), (-h, 0, h), (-h, 2 * h, h)]),
        ((0, 1, 0), [(-h, 2 * h, -h), (-h, 2 * h, h), (h, 2 * h, h), (h, 2 * h, -h)]),
    ]  # no bottom face: it would lie in the ground plane
    for normal, corners in faces:
        quad(g, corners, box, normal=normal)
    g.camera((2.0, 2.4, 2.6), (0, 0.5, 0))
    g.sun((0.6, -1.0, -0.35), 3.0)
    g.save(path)


CASES = {"normal": normal_map_scene, "alpha": alpha_scene, "transform": transform_scene}
