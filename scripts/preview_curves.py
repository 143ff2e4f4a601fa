#!/usr/bin/env python3
"""Seed 003 P4's preview result as curves (issue 27, docs/preview.md).

For each scene: a converged equirect reference (`fovea reference`), then the three preview graphs
(OD, VP, FV) with the same per-frame sample budget and `run --reference`, which reports the RMSE
of the accumulated equirect image as displayed (tm.ldr, ACES-tone-mapped like the reference's
tm.ldr; display-space errors as seed 000 Table 4, so that a rare firefly does not dominate a band)
per eccentricity band around the gaze on the sphere (0-5, 5-10, 10-20, 20-80, 80+ degrees). From the per-frame errors it writes:

  OUT/preview_curves.md   the time (samples) each method needs to reach two error thresholds per
                          band - stand-ins for P4's "visible outline" and "visible material"
                          splits - and the ratio to OD's (P4: FV ~10 %, VP ~30 % of OD's time)
  OUT/preview_curves.svg  RMSE against samples per texel, per band and scene (log-log)
  OUT/preview_curves.json everything measured

Thresholds: OD's error in the band after 2 and after 16 samples per texel (so OD's times are 2 and
16 samples per texel by construction and the others are read against them). A method that does
not reach a threshold within the run is reported as "> N".

Usage: scripts/preview_curves.py OUT [--fovea build/fovea] [--frames 96] [--budget 25000]
                                     [--size 512x256] [--spp 512] [--scenes cornell,forest]
Only Python's standard library; the fovea runs are the cost (about 10 minutes on 2 CPU cores).
"""
import argparse
import json
import math
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {
    "cornell": ("builtin:cornell", "graphs/cameras/preview_cornell.json"),
    "forest": ("builtin:forest", "graphs/cameras/preview_forest.json"),
}
METHODS = [("od", "OD"), ("vp", "VP"), ("fv", "FV")]
BANDS = ["0-5°", "5-10°", "10-20°", "20-80°"]
COLOURS = {"od": "#1f77b4", "vp": "#2ca02c", "fv": "#d62728"}


def run(cmd):
    print("+ " + " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True)


def reference(args, out, scene, camera):
    folder = os.path.join(out, "reference")
    key = os.path.join(folder, "key.json")
    want = {"scene": scene, "camera": camera, "size": args.size, "spp": args.spp}
    if os.path.exists(key) and json.load(open(key)) == want:
        pass
    else:
        run([args.fovea, "reference", "--scene", scene, "--camera", os.path.join(REPO, camera),
             "--size", args.size, "--spp", str(args.spp), "--out", folder, "--overwrite",
             "--quiet"])
        json.dump(want, open(key, "w"))
    exrs = [f for f in os.listdir(folder) if f.startswith("tm.ldr") and f.endswith(".exr")]
    return os.path.join(folder, sorted(exrs)[-1])


def measure(args, out, scene, camera, ref, method):
    folder = os.path.join(out, method)
    run([args.fovea, "run", os.path.join(REPO, "graphs", "preview_%s.json" % method), "--scene",
         scene, "--camera", os.path.join(REPO, camera), "--size", args.size, "--frames",
         str(args.frames), "--set", "samples.budget=%d" % args.budget, "--reference", ref,
         "--reference-output", "tm.ldr", "--out", folder, "--overwrite", "--quiet"])
    report = json.load(open(os.path.join(folder, "report.json")))
    errors = [[b["rmse"] for b in f["bands"]] for f in report["reference"]["frames"]]
    passes = {p["name"]: p["gpu_ms"]["median"] for p in report["passes"] if "gpu_ms" in p}
    return {"errors": errors, "frame_ms": report["frame_ms"]["median"], "pass_gpu_ms": passes}


def samples_to_reach(errors, band, threshold, per_frame):
    """Samples per texel at which the band's error first drops to `threshold` (log-log
    interpolation between frames); None when it never does."""
    prev = None
    for f, e in enumerate(errors):
        s = (f + 1) * per_frame
        if e[band] <= threshold:
            if prev is None or prev[1] <= 0 or e[band] <= 0:
                return s
            (s0, e0) = prev
            t = (math.log(threshold) - math.log(e0)) / (math.log(e[band]) - math.log(e0))
            return math.exp(math.log(s0) + t * (math.log(s) - math.log(s0)))
        prev = (s, e[band])
    return None


def plot(results, per_frame, path):
    width, height, pad = 300, 220, 46
    scenes = list(results)
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'font-family="sans-serif" font-size="11">' %
           (width * len(BANDS[:3]) + 20, height * len(scenes) + 30)]
    for si, scene in enumerate(scenes):
        for b in range(3):
            x0, y0 = 10 + b * width, 20 + si * height
            curves = {m: [e[b] for e in results[scene][m]["errors"]] for m, _ in METHODS}
            values = [v for c in curves.values() for v in c if v > 0]
            lo, hi = math.log10(min(values)), math.log10(max(values))
            n = len(next(iter(curves.values())))
            smin, smax = math.log10(per_frame), math.log10(n * per_frame)

            def px(s, e):
                return (x0 + pad + (math.log10(s) - smin) / max(smax - smin, 1e-9) *
                        (width - pad - 10),
                        y0 + height - pad - (math.log10(e) - lo) / max(hi - lo, 1e-9) *
                        (height - pad - 20))
            svg.append('<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="#ccc"/>' %
                       (x0 + pad, y0 + 20, width - pad - 10, height - pad - 20))
            svg.append('<text x="%d" y="%d">%s, %s band</text>' % (x0 + pad, y0 + 14, scene,
                                                                   BANDS[b]))
            svg.append('<text x="%d" y="%d">samples per texel (log)</text>' %
                       (x0 + pad, y0 + height - pad + 28))
            svg.append('<text x="%d" y="%d" transform="rotate(-90 %d %d)">RMSE (log)</text>' %
                       (x0 + 14, y0 + height - pad, x0 + 14, y0 + height - pad))
            for m, label in METHODS:
                pts = [px((f + 1) * per_frame, e) for f, e in enumerate(curves[m]) if e > 0]
                svg.append('<polyline fill="none" stroke="%s" stroke-width="1.5" points="%s"/>' %
                           (COLOURS[m], " ".join("%.1f,%.1f" % p for p in pts)))
            for k, (m, label) in enumerate(METHODS):
                svg.append('<text x="%d" y="%d" fill="%s">%s</text>' %
                           (x0 + width - 40, y0 + 36 + 13 * k, COLOURS[m], label))
    svg.append("</svg>")
    open(path, "w").write("\n".join(svg) + "\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out")
    p.add_argument("--fovea", default=os.path.join(REPO, "build", "fovea"))
    p.add_argument("--frames", type=int, default=96)
    p.add_argument("--budget", type=int, default=25000)
    p.add_argument("--size", default="512x256")
    p.add_argument("--spp", type=int, default=512)
    p.add_argument("--scenes", default="cornell,forest")
    args = p.parse_args()
    w, h = (int(v) for v in args.size.split("x"))
    per_frame = args.budget / float(w * h)  # samples per texel per frame, every method
    results, rows = {}, []
    for name in args.scenes.split(","):
        scene, camera = SCENES[name]
        out = os.path.join(args.out, name)
        os.makedirs(out, exist_ok=True)
        ref = reference(args, out, scene, camera)
        results[name] = {m: measure(args, out, scene, camera, ref, m) for m, _ in METHODS}
        for b in range(len(BANDS)):
            od = results[name]["od"]["errors"]
            for split, spt in (("outline", 2.0), ("material", 16.0)):
                frame = int(round(spt / per_frame)) - 1
                if frame >= len(od):
                    continue
                threshold = od[frame][b]
                reach = {m: samples_to_reach(results[name][m]["errors"], b, threshold, per_frame)
                         for m, _ in METHODS}
                rows.append((name, BANDS[b], split, threshold, reach))
    md = ["| scene | band | split (OD at) | threshold RMSE | OD | VP | FV | VP / OD | FV / OD |",
          "|---|---|---|---|---|---|---|---|---|"]
    for name, band, split, threshold, reach in rows:
        def fmt(v):
            return "> %.0f" % (args.frames * per_frame) if v is None else "%.2f" % v

        def ratio(v):
            return "—" if v is None or reach["od"] is None else "%.0f %%" % (100 * v / reach["od"])
        md.append("| %s | %s | %s (%s spt) | %.4g | %s | %s | %s | %s | %s |" %
                  (name, band, split, "2" if split == "outline" else "16", threshold,
                   fmt(reach["od"]), fmt(reach["vp"]), fmt(reach["fv"]), ratio(reach["vp"]),
                   ratio(reach["fv"])))
    md.append("")
    md.append("Times in samples per texel of the whole equirect image (the same for every method "
              "per frame: %d samples per frame at %s = %.3f per texel)." %
              (args.budget, args.size, per_frame))
    md.append("")
    md.append("| scene | method | frame ms (median) | PreviewSamples GPU ms | PathTrace GPU ms | "
              "Accumulate GPU ms | HmdPreview GPU ms |")
    md.append("|---|---|---|---|---|---|---|")
    for name in results:
        for m, label in METHODS:
            r = results[name][m]
            g = r["pass_gpu_ms"]
            md.append("| %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f |" %
                      (name, label, r["frame_ms"], g.get("samples", 0), g.get("pt", 0),
                       g.get("acc", 0), g.get("preview", 0)))
    open(os.path.join(args.out, "preview_curves.md"), "w").write("\n".join(md) + "\n")
    json.dump({"args": vars(args), "per_frame_samples_per_texel": per_frame, "results": results},
              open(os.path.join(args.out, "preview_curves.json"), "w"), indent=1)
    plot(results, per_frame, os.path.join(args.out, "preview_curves.svg"))
    print("\n".join(md))


if __name__ == "__main__":
    main()
