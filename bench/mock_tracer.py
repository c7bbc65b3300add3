#!/usr/bin/env python3
"""Stand-in for `sphera-trace` with the same command line, for testing report.py.

Nothing is traced. Each scene has a smooth analytic "true" image T; a run of a technique
returns T + bias + noise, the noise being a fixed Gaussian field (seeded by scene,
technique and --seed) scaled by sigma_technique * (0.2 + T) / sqrt(passes * K). Times
are simulated from a per-technique cost per light sample, so --time-ms returns at once.
The JSON line, PFM, PNG and curve CSV follow the tracer's interface exactly.

Test hooks: MOCK_BIAS=1 (or =NAME) shifts the mean of solid_angle (or NAME) by 5%;
MOCK_FAIL=NAME makes a run of technique NAME fail with exit status 3.
"""
import argparse
import hashlib
import json
import math
import os
import random
import struct
import sys
import zlib

SCENES = {  # name: (lights, description)
    "cornell": (1, "Cornell box with one quad light"),
    "polygons": (4, "four polygonal lights of 3 to 7 vertices over a plane"),
    "hard": (3, "grazing lights crossing the horizon, thin occluders"),
    "floor": (1, "one large quad over a diffuse floor"),
}
TECHNIQUES = {  # name: (biased, noise sigma, ns per sample with shadow ray, description)
    "reference": (False, 0.4, 400.0, "projected solid angle, many samples"),
    "turk": (False, 2.0, 330.0, "Turk area sampling"),
    "solid_angle": (False, 1.2, 345.0, "solid angle sampling (Alg. 5)"),
    "clipped_solid_angle": (False, 0.9, 350.0, "solid angle sampling of the clipped polygon"),
    "hart_bilinear": (False, 0.7, 360.0, "bilinear cosine warp (Hart et al. 2020)"),
    "projected": (False, 0.4, 380.0, "projected solid angle sampling (Peters 2021)"),
    "projected_biased": (True, 0.4, 365.0, "projected solid angle, no iteration"),
}


def true_image(scene, w, h):
    """The noise-free image of a scene: a lit blob, a shadow band, coloured walls."""
    rng = random.Random(scene)
    cx, cy, r = rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), rng.uniform(0.03, 0.1)
    tint = [rng.uniform(0.5, 1.0) for _ in range(3)]
    px = []
    for y in range(h):
        for x in range(w):
            u, v = (x + 0.5) / w, (y + 0.5) / h
            e = 0.1 + 0.9 * math.exp(-((u - cx) ** 2 + (v - cy) ** 2) / r)
            if abs(u + v - 1.0) < 0.05:
                e *= 0.1
            px.append([e * tint[c] * (1.3 if c == (x * 3) // w else 1.0) for c in range(3)])
    return px


def write_pfm(path, w, h, px):
    """Colour PFM, little-endian (scale -1), rows bottom to top; px is top-first."""
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        for y in reversed(range(h)):
            row = [c for p in px[y * w:(y + 1) * w] for c in p]
            f.write(struct.pack("<%df" % len(row), *row))


def read_pfm(path):
    """Returns (w, h, pixels top-first) of a colour PFM."""
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    if parts[0].strip() != b"PF":
        raise ValueError(f"{path}: not a colour PFM")
    w, h = map(int, parts[1].split())
    end = "<" if float(parts[2]) < 0 else ">"
    vals = struct.unpack(end + "%df" % (w * h * 3), parts[3][:w * h * 12])
    rows = [[list(vals[i:i + 3]) for i in range((h - 1 - y) * w * 3, (h - y) * w * 3, 3)]
            for y in range(h)]
    return w, h, [p for row in rows for p in row]


def write_png(path, w, h, px, exposure):
    """8-bit sRGB PNG of px scaled by 2^exposure."""
    def srgb(v):
        v = min(max(v * 2.0 ** exposure, 0.0), 1.0)
        v = 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
        return int(v * 255 + 0.5)

    raw = b"".join(b"\0" + bytes(srgb(c) for p in px[y * w:(y + 1) * w] for c in p)
                   for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(
            ">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def errors(img, ref):
    """(rmse, relmse) of img against ref over pixels and channels."""
    se = rel = 0.0
    for p, q in zip(img, ref):
        for a, b in zip(p, q):
            d = (a - b) ** 2
            se += d
            rel += d / (b * b + 0.01)
    n = 3 * len(img)
    return math.sqrt(se / n), rel / n


def main():
    ap = argparse.ArgumentParser(prog="sphera-trace")
    ap.add_argument("--scene", default="cornell")
    ap.add_argument("--technique", default="projected")
    ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--height", type=int, default=192)
    ap.add_argument("--spp", type=int)
    ap.add_argument("--time-ms", type=float)
    ap.add_argument("--light-samples", type=int, default=1)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--reference")
    ap.add_argument("--curve")
    ap.add_argument("--out-pfm")
    ap.add_argument("--out-png")
    ap.add_argument("--out-error-png")
    ap.add_argument("--exposure", type=float, default=0.0)
    ap.add_argument("--list-scenes", action="store_true")
    ap.add_argument("--list-techniques", action="store_true")
    ap.add_argument("--version", action="store_true")
    a = ap.parse_args()
    if a.version:
        print("sphera-trace 0.1.0 libsphera 0.1.0")
        return 0
    if a.list_scenes:
        print("\n".join(f"{n}\t{d}" for n, (_, d) in SCENES.items()))
        return 0
    if a.list_techniques:
        print("\n".join(f"{n}\t{'biased' if t[0] else 'unbiased'}\t{t[3]}"
                        for n, t in TECHNIQUES.items()))
        return 0
    if a.scene not in SCENES or a.technique not in TECHNIQUES:
        print("sphera-trace: unknown scene or technique", file=sys.stderr)
        return 2
    if os.environ.get("MOCK_FAIL") == a.technique:
        print(f"sphera-trace: simulated failure of {a.technique}", file=sys.stderr)
        return 3
    w, h, k = a.width, a.height, a.light_samples
    lights = SCENES[a.scene][0]
    biased, sigma, ns, _ = TECHNIQUES[a.technique]
    ms_per_frame = w * h * (300.0 + lights * k * ns) * 1e-6 / max(a.threads, 1)
    if a.time_ms is not None:
        passes = max(1, math.ceil(a.time_ms / ms_per_frame))
    else:
        passes = a.spp or 1
    truth = true_image(a.scene, w, h)
    bias_name = os.environ.get("MOCK_BIAS", "")
    bias = 0.05 if a.technique == ("solid_angle" if bias_name == "1" else bias_name) else 0.0
    bias = 2e-3 if biased else bias
    rng = random.Random(hashlib.sha256(f"{a.scene} {a.technique} {a.seed}".encode()).digest())
    sig = [[sigma * (0.2 + c) / math.sqrt(k) for c in p] for p in truth]
    z = [[rng.gauss(0.0, 1.0) for _ in range(3)] for _ in truth]

    def image(n):
        return [[t * (1 + bias) + s * g / math.sqrt(n) for t, s, g in zip(tp, sp, zp)]
                for tp, sp, zp in zip(truth, sig, z)]

    img = image(passes)
    npx = w * h
    mean = [sum(p[c] for p in img) / npx for c in range(3)]
    var = [sum(s[c] ** 2 for s in sig) / passes if passes > 1 else 0.0 for c in range(3)]
    out = {"scene": a.scene, "technique": a.technique, "biased": biased, "width": w,
           "height": h, "passes": passes, "light_samples": k, "lights": lights,
           "time_ms": passes * ms_per_frame, "ms_per_frame": ms_per_frame,
           "ns_per_sample": ns, "samples": passes * npx * lights * k, "mean": mean,
           "mean_stderr": [math.sqrt(v) / npx for v in var],
           "variance_of_mean": sum(var) / (3 * npx)}
    if a.reference:
        rw, rh, ref = read_pfm(a.reference)
        if (rw, rh) != (w, h):
            print(f"sphera-trace: reference is {rw}x{rh}, image is {w}x{h}", file=sys.stderr)
            return 2
        out["rmse"], out["relmse"] = errors(img, ref)
        if a.curve:
            with open(a.curve, "w") as f:
                f.write("passes,time_ms,rmse,relmse\n")
                n = 1
                while True:
                    m = min(n, passes)
                    f.write("%d,%.6g,%.6g,%.6g\n" % (m, m * ms_per_frame, *errors(image(m), ref)))
                    if m == passes:
                        break
                    n *= 2
    if a.out_pfm:
        write_pfm(a.out_pfm, w, h, img)
    if a.out_png:
        write_png(a.out_png, w, h, img, a.exposure)
    if a.out_error_png:
        if not a.reference:
            print("sphera-trace: --out-error-png needs --reference", file=sys.stderr)
            return 2
        # As sphera-trace: the mean error over the channels, x 4, red brighter, blue darker.
        err = [sum(p) - sum(q) for p, q in zip(img, ref)]
        write_png(a.out_error_png, w, h, [(4 * e / 3, 0.0, -4 * e / 3) for e in err],
                  a.exposure)
    print(f"{a.technique}: {passes} passes", file=sys.stderr)
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
