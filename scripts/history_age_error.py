#!/usr/bin/env python3
"""Error by history age: RMSE % of a denoiser's display image over the pixels that hold k frames
of history (k = 0: disoccluded this frame), against per-frame references (issue 13, "error in the
first frames after a disocclusion").

The age of a pixel is read from one run's BMFR `accumulated` alpha (samples = age + 1; BMFR's
position/normal disocclusion test, P2 §3.2), so every graph is measured on the same pixels.
Images are read through `oiiotool --dumpdata`; RGB only, the bench's RMSE (plain RMS of
the channel differences, x100) over the pixels with a surface and a non-black reference.

usage: history_age_error.py --ref DIR --age RUN_DIR --frames 4,5,6,7 LABEL=RUN_DIR:OUTPUT ...
  DIR holds frameNNNN.exr (fovea bench's cached per-frame references); RUN_DIR is a
  `fovea run --save-frames ...` folder; OUTPUT the compared output (tm.ldr).
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import shutil  # noqa: E402

# oiiotool (Debian's openimageio-tools) reads the images; fovea itself no longer needs it.
if shutil.which("oiiotool") is None:
    sys.exit("%s: needs oiiotool: apt-get install openimageio-tools" % os.path.basename(__file__))


def read_pixels(path):
    """Returns (w, h, rows of channel values) in row-major order, top row first, through
    `oiiotool --dumpdata` (no Python image library needed)."""
    text = subprocess.run(["oiiotool", "--dumpdata", path], check=True, capture_output=True,
                          text=True).stdout.splitlines()
    w, h = (int(v) for v in text[0].split(":", 1)[1].split(",")[0].split("x"))
    pixels = [None] * (w * h)
    for line in text[1:]:
        if "Pixel (" not in line:
            continue
        where, values = line.split(":", 1)
        x, y = (int(v) for v in where.split("(", 1)[1].rstrip(")").split(","))
        pixels[y * w + x] = [float(v) for v in values.split()]
    if any(p is None for p in pixels):
        sys.exit(f"history_age_error: could not read every pixel of {path}")
    return w, h, pixels


def read_rgb(path):
    return [p[:3] for p in read_pixels(path)[2]]


def read_alpha(path):
    return [p[3] for p in read_pixels(path)[2]]


def frame_file(folder, stem, frame):
    name = f"{stem}.frame{frame:04d}.exr"
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        sys.exit(f"history_age_error: missing {path}")
    return path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ref", required=True)
    ap.add_argument("--age", required=True, help="run folder with bmfr.accumulated frames")
    ap.add_argument("--frames", required=True)
    ap.add_argument("--max-age", type=int, default=3)
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    frames = [int(f) for f in a.frames.split(",")]
    # samples 0 = no surface (sky): not counted; else age = samples - 1, capped at max_age.
    ages = {f: [min(int(round(s)) - 1, a.max_age) if s >= 0.5 else -1
                for s in read_alpha(frame_file(a.age, "bmfr.accumulated", f))] for f in frames}
    refs = {f: read_rgb(os.path.join(a.ref, f"frame{f:04d}.exr")) for f in frames}
    # BMFR counts a sky pixel as a fresh sample every frame (samples 1): pixels whose reference is
    # black (sky, the unlit outside of a box) are left out as well.
    for f in frames:
        ages[f] = [k if any(v > 0.0 for v in refs[f][i]) else -1 for i, k in enumerate(ages[f])]
    counts = [0] * (a.max_age + 1)
    for f in frames:
        for k in ages[f]:
            if k >= 0:
                counts[k] += 1
    total = sum(counts)
    head = " | ".join(f"age {k}" if k < a.max_age else f"age >= {k}" for k in range(a.max_age + 1))
    print(f"| Graph | {head} | all |")
    print("|---|" + "---:|" * (a.max_age + 2))
    print("| pixels (share) | " + " | ".join(f"{c} ({100.0 * c / total:.1f} %)" for c in counts)
          + f" | {total} |")
    for run in a.runs:
        label, rest = run.split("=", 1)
        folder, output = rest.rsplit(":", 1)
        sums = [0.0] * (a.max_age + 1)
        for f in frames:
            img = read_rgb(frame_file(folder, output, f))
            ref = refs[f]
            for i, k in enumerate(ages[f]):
                if k < 0:
                    continue
                d = sum((img[i][c] - ref[i][c]) ** 2 for c in range(3))
                sums[k] += d
        cells = [f"{100.0 * math.sqrt(s / (3 * c)):.2f}" if c else "—" for s, c in zip(sums, counts)]
        allv = 100.0 * math.sqrt(sum(sums) / (3 * total))
        print(f"| {label} | " + " | ".join(cells) + f" | {allv:.2f} |")


if __name__ == "__main__":
    main()
