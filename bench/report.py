#!/usr/bin/env python3
"""Speed-versus-error report of sphera's light-sampling techniques, driven by sphera-trace.

For each scene the tracer renders a reference image with many passes of its `reference`
technique (cached under OUT/cache, keyed by the tracer's version and binary, the scene,
the size and the pass count), then renders every other technique twice: with an equal
number of passes (EQ_SPP) and with an equal time budget (BUDGET_MS of sampling passes).
Each run reports its error against the reference: RMSE and relMSE, and for the
equal-time run a curve of RMSE against time.

The reference is noisy too: with independent noise, the expected squared difference to
it is the technique's own MSE plus the reference's per-pixel variance of the mean, so
the report subtracts that (MSE_corrected = max(RMSE^2 - ref variance_of_mean, 0)).
Efficiency is 1 / (MSE_corrected * seconds of sampling); for an unbiased technique MSE
falls like 1/time, so efficiency does not depend on the budget, and its ratio to that
of area sampling is the speed-up: how many times sooner the technique reaches the same
error. A check (always in --quick mode) compares the image mean of every unbiased
technique with the reference's, within 5 standard errors.

A scene given as `name@K` renders with K light samples per light per pass (the
many-samples mode: one prepare per light and pixel, then K samples), against the
reference of `name`; the default list has `polygons@8` beside `polygons`, so that the
cost of prepare is visible.

Output: OUT/index.html (tables, RMSE plots as SVG, images), OUT/report.md, and the
tables on stdout. Techniques run one after another, never in parallel, for fair timing.
"""
import argparse
import csv
import datetime
import hashlib
import html
import json
import math
import os
import platform
import shlex
import shutil
import subprocess
import sys
import time

import indirect_report

SCENES = ("cornell", "polygons", "polygons@8", "hard", "glossy", "spheres", "slab",
          "occlusion", "overlap")  # name@K: K per light
# The techniques that combine two samples by MIS (BRDF or LTC sampling with projected
# solid angle sampling) matter on glossy surfaces: they run on the `glossy` scene, with
# the light samplers they are built from; the other scenes compare the light samplers.
MIS_TECHNIQUES = ("brdf_balance", "brdf_power", "ltc_weighted", "ltc_clamped", "ltc_optimal")
GLOSSY_TECHNIQUES = ("turk", "solid_angle", "projected") + MIS_TECHNIQUES
# Sphere lights have their own samplers; they run on the `spheres` scene only.
SPHERE_TECHNIQUES = ("sphere_cap", "sphere_cap_brdf", "sphere_sptd", "sphere_projected",
                     "sphere_realtime")
# In-scattering in a medium: the `slab` scene, the pivot phase function restricted to
# the light's cap (Dupuy et al. 2017, Sec. 6.2) beside its baseline, Henyey-Greenstein
# sampling with uniform cap sampling by MIS, against uniform cap sampling.
MEDIUM_TECHNIQUES = ("medium_pivot", "medium_hg_cap")
SLAB_TECHNIQUES = ("sphere_cap",) + MEDIUM_TECHNIQUES
# The baseline of the speed-up column: area sampling, or on `spheres` and `slab` uniform
# cap sampling.
# Specular occlusion (Dupuy et al. 2017, Sec. 5.4): the `occlusion` scene, the SPTD's
# triple product in a traced bent cone (Eq. 23) against the separable approximation
# (Eq. 21-22), beside the ray-traced estimators.
OCCLUSION_TECHNIQUES = ("sphere_cap", "sphere_cap_brdf", "sphere_realtime",
                        "sphere_occlusion", "sphere_occlusion_separable")
# Sets of caps (Dupuy et al. 2017, Sec. 4; issue 20, 1): the `overlap` scene, two
# intersecting sphere lights of equal radiance sampled as one light, uniformly in the
# union of their caps (sphere_union) against picking one light with probability 1/2
# (sphere_mixture, the baseline of its speed-up), beside a cap sample per light.
OVERLAP_TECHNIQUES = ("sphere_cap", "sphere_mixture", "sphere_union")
SCENE_BASELINE = {"spheres": "sphere_cap", "slab": "sphere_cap", "occlusion": "sphere_cap",
                  "overlap": "sphere_mixture"}


def techniques_for(scene, techs):
    """The (name, biased) pairs of `techs` that the report runs on `scene` (a spec)."""
    name = scene.partition("@")[0]
    if name == "glossy":
        return [t for t in techs if t[0] in GLOSSY_TECHNIQUES]
    if name == "spheres":
        return [t for t in techs if t[0] in SPHERE_TECHNIQUES]
    if name == "slab":
        return [t for t in techs if t[0] in SLAB_TECHNIQUES]
    if name == "occlusion":
        return [t for t in techs if t[0] in OCCLUSION_TECHNIQUES]
    if name == "overlap":
        return [t for t in techs if t[0] in OVERLAP_TECHNIQUES]
    return [t for t in techs
            if t[0] not in MIS_TECHNIQUES + SPHERE_TECHNIQUES + MEDIUM_TECHNIQUES
            + OCCLUSION_TECHNIQUES + OVERLAP_TECHNIQUES]
FULL = {"width": 256, "height": 192, "ref_spp": 512, "spp": 16, "budget_ms": 1500.0}
QUICK = {"width": 64, "height": 48, "ref_spp": 128, "spp": 4, "budget_ms": 150.0}
# Full mode without --ref-spp: scenes whose reference technique is efficient enough for
# fewer passes (spheres: sphere_sptd's estimator, whose reference noise at 256 passes is
# about half of sphere_cap_brdf's at 512; overlap: the same reference), which keeps the
# full report near 4.5 minutes.
FULL_REF_SPP = {"spheres": 256, "overlap": 256}
REF_SEED = 1          # seed of reference renders
RUN_SEED = 2          # seed of technique renders (independent of the reference's noise)
BASELINE = "turk"     # technique the speed-up is relative to
CHECK_SIGMAS = 5.0
# Unbiased techniques whose f32 implementation is known to miss the reference in a
# scene, and why. The check expects them to fail (and fails if one starts to agree, so
# that this list stays true); the report prints the reason under the scene's table.
KNOWN_FAILURES = {
    ("hard", "arvo"): "Arvo 1995 is unbiased in exact arithmetic, but in f32 Girard's "
                      "formula (alpha + beta + gamma - pi) cancels for the 1e-7 sr distant "
                      "light: its solid angle, hence its pdf, is off by tens of percent "
                      "(docs/polygon-lights.md: accuracy per decade of solid angle).",
    ("hard", "arvo_projected"): "Arvo's projected sampling in f32 puts most draws for the "
                                "1e-7 sr distant light outside it; since issue 16 such "
                                "draws are no sample (the baseline no longer claims a "
                                "density there), so its estimate misses their energy "
                                "(header: unreliable below about 2e-3 rad across).",
}
COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
           "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
# (header, key in a row, shown on stdout)
COLUMNS = (("technique", "tech", True), ("biased", "biased", True),
           ("ms/frame", "ms_frame", True), ("ns/sample", "ns_sample", True),
           ("RMSE@spp", "rmse_spp", True), ("RMSE@time", "rmse_time", True),
           ("relMSE@time", "relmse_time", True), ("MSE corrected", "mse_corr", False),
           ("efficiency", "eff", True), ("speed-up", "speedup", True))
EXPLANATION = (
    "All columns but RMSE@spp come from the equal-time run. <b>ms/frame</b>: sampling "
    "time per pass (one camera sample per pixel, one light sample per light). "
    "<b>ns/sample</b>: time per light sample including its shadow ray. <b>RMSE@spp</b>: "
    "RMSE against the reference after {spp} passes. <b>RMSE@time</b>, <b>relMSE@time</b>: "
    "after {budget:g} ms of sampling (relMSE = mean of (x&minus;ref)&sup2;/(ref&sup2;+0.01)). "
    "<b>MSE corrected</b> = max(RMSE&sup2; &minus; v<sub>ref</sub>, 0), where v<sub>ref</sub>, the "
    "reference's variance of the mean averaged over pixels and channels, is the part of "
    "the squared error due to the reference's own noise. <b>efficiency</b> = "
    "1&nbsp;/&nbsp;(MSE corrected &times; sampling time in seconds): higher is better, "
    "and for unbiased techniques it does not depend on the budget. <b>speed-up</b> = "
    "efficiency / efficiency of {base}: how many times sooner the technique reaches the "
    "same error. <b>biased</b> techniques converge to a slightly wrong image; their "
    "efficiency holds only at this budget and they are left out of the mean check.")


class TracerError(Exception):
    """A tracer run that failed: the message holds its command line and stderr."""


# The largest value of each setting: a larger (or infinite) budget would never finish.
SETTING_LIMITS = {"width": 16384, "height": 16384, "ref_spp": 1 << 20, "spp": 1 << 20,
                  "budget_ms": 86400e3}


def setting_type(name):
    """The argparse type of a setting: a finite number in (0, SETTING_LIMITS[name]], an
    int where the default is one; anything else is an error with a message (not a
    traceback, not a run without end)."""
    kind = type(FULL[name])

    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a {kind.__name__}: {text!r}")
        if not (math.isfinite(value) and 0 < value <= SETTING_LIMITS[name]):
            raise argparse.ArgumentTypeError(
                f"must be finite, positive and at most {SETTING_LIMITS[name]:g}: {text!r}")
        return value
    return parse


def parse_args(argv):
    """Command-line options; settings default to FULL or QUICK."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="small and fast; implies --check")
    ap.add_argument("--tracer", default=os.path.join(root, "bench", "build", "sphera-trace"),
                    help="path or command line of sphera-trace")
    ap.add_argument("--out", default="report", help="output directory")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--techniques", help="comma-separated subset (default: all)")
    ap.add_argument("--check", action="store_true", help="check the unbiased means")
    ap.add_argument("--no-indirect", action="store_true",
                    help="leave out the VSGL one-bounce indirect section")
    ap.add_argument("--threads", type=int, help="passed to the tracer")
    for name in FULL:
        ap.add_argument("--" + name.replace("_", "-"), type=setting_type(name))
    args = ap.parse_args(argv)
    base = QUICK if args.quick else FULL
    args.settings = {k: base[k] if getattr(args, k) is None else getattr(args, k) for k in FULL}
    args.scenes = [s for s in args.scenes.split(",") if s]
    if not args.scenes:
        ap.error("--scenes names no scene (a comma-separated list of --list-scenes names)")
    args.ref_spp_by_scene = {} if args.quick or args.ref_spp is not None else FULL_REF_SPP
    return args


def scene_settings(args, spec):
    """The settings of one scene spec: args.settings with its reference pass count."""
    name = spec.partition("@")[0]
    return dict(args.settings, ref_spp=args.ref_spp_by_scene.get(name, args.settings["ref_spp"]))


def tracer_binary(words):
    """The file identifying the tracer: the last word that is an existing file."""
    for w in reversed(words):
        if os.path.isfile(w):
            return w
    return shutil.which(words[0]) if words else None


def sha256_file(path):
    """Hex sha256 of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def call(tracer, args):
    """Runs the tracer with args; returns its stdout, raises TracerError on failure."""
    cmd = tracer + [str(a) for a in args]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        raise TracerError(f"cannot run {shlex.join(cmd)}: {e}") from e
    if p.returncode != 0:
        raise TracerError(f"{shlex.join(cmd)} exited with status {p.returncode}:\n{p.stderr}")
    return p.stdout


def run_json(tracer, args):
    """Runs the tracer and parses the JSON object on the last line of its stdout."""
    out = call(tracer, args)
    lines = out.strip().splitlines()
    try:
        return json.loads(lines[-1])
    except (IndexError, ValueError) as e:
        raise TracerError(f"{shlex.join(tracer + [str(a) for a in args])}: no JSON line "
                          f"at the end of stdout:\n{out}") from e


def cpu_name():
    """CPU model from /proc/cpuinfo where there is one, else platform's names."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def log(msg):
    """Progress on stderr."""
    print(msg, file=sys.stderr, flush=True)


def reference(tracer, key_base, scene, s, out, common):
    """Renders or reuses the cached reference; returns its JSON (with 'pfm' added)."""
    w, h, spp = s["width"], s["height"], s["ref_spp"]
    key = hashlib.sha256("\n".join([key_base, scene, str(w), str(h), str(spp)]).encode())
    stem = os.path.join(out, "cache", f"ref-{scene}-{w}x{h}-{spp}-{key.hexdigest()[:16]}")
    png = os.path.join(out, f"{scene}-reference.png")
    if all(os.path.isfile(stem + e) for e in (".pfm", ".json", ".png")):
        log(f"[{scene}] reference: cached {stem}.pfm")
        shutil.copyfile(stem + ".png", png)
        with open(stem + ".json") as f:
            ref = json.load(f)
    else:
        log(f"[{scene}] reference: rendering {spp} passes (not cached) ...")
        t = time.monotonic()
        ref = run_json(tracer, ["--scene", scene, "--technique", "reference", "--spp", spp,
                                "--seed", REF_SEED, "--out-pfm", stem + ".pfm",
                                "--out-png", png] + common)
        shutil.copyfile(png, stem + ".png")
        with open(stem + ".json", "w") as f:
            json.dump(ref, f)
        log(f"[{scene}] reference: done in {time.monotonic() - t:.1f} s, saved to cache")
    ref["pfm"] = stem + ".pfm"
    return ref


def file_name(spec):
    """A scene spec (`name` or `name@K`) as part of a file name."""
    return spec.replace("@", "-k")


def read_curve(path):
    """(time_ms, rmse) pairs of a curve CSV."""
    with open(path, newline="") as f:
        return [(float(r["time_ms"]), float(r["rmse"])) for r in csv.DictReader(f)]


def render_scene(tracer, key_base, spec, techs, s, out, common):
    """Reference, equal-sample and equal-time runs of one scene; returns its results.

    `spec` is a scene name, or `name@K` for K light samples per light per pass (the
    many-samples mode: one prepare, K samples), which shares the reference of `name`."""
    scene, _, k = spec.partition("@")
    ref = reference(tracer, key_base, scene, s, out, common)
    base = ["--scene", scene, "--seed", RUN_SEED, "--reference", ref["pfm"]] + common
    if k:
        base += ["--light-samples", k]
    if spec != scene:
        shutil.copyfile(os.path.join(out, f"{scene}-reference.png"),
                        os.path.join(out, f"{file_name(spec)}-reference.png"))
    rows = []
    for tech, biased in techs:
        stem = os.path.join(out, f"{file_name(spec)}-{tech}")
        eq = run_json(tracer, base + ["--technique", tech, "--spp", s["spp"],
                                      "--out-png", stem + "-spp.png",
                                      "--out-error-png", stem + "-spp-error.png"])
        budget = s["budget_ms"]  # an integer where it is one: the tracer may parse it so
        budget = int(budget) if budget == int(budget) else budget
        tm = run_json(tracer, base + ["--technique", tech, "--time-ms", budget,
                                      "--curve", stem + "-time.csv",
                                      "--out-png", stem + "-time.png"])
        log(f"[{scene}] {tech}: RMSE {eq['rmse']:.3g} at {eq['passes']} passes, "
            f"{tm['rmse']:.3g} at {tm['passes']} passes in {tm['time_ms']:.0f} ms")
        mse = max(tm["rmse"] ** 2 - ref["variance_of_mean"], 0.0)
        seconds = tm["time_ms"] / 1000.0
        eff = 1.0 / (mse * seconds) if mse * seconds > 0 else math.inf
        rows.append({"tech": tech, "biased": bool(tm.get("biased", biased)), "spp": eq,
                     "time": tm, "ms_frame": tm["ms_per_frame"],
                     "ns_sample": tm["ns_per_sample"], "rmse_spp": eq["rmse"],
                     "rmse_time": tm["rmse"], "relmse_time": tm["relmse"],
                     "mse_corr": mse, "eff": eff, "curve": read_curve(stem + "-time.csv")})
    baseline = SCENE_BASELINE.get(scene, BASELINE)
    base_eff = next((r["eff"] for r in rows if r["tech"] == baseline), None)
    for r in rows:
        ok = base_eff is not None and 0 < base_eff < math.inf and r["eff"] < math.inf
        r["speedup"] = r["eff"] / base_eff if ok else None
    return {"scene": spec, "name": scene, "ref": ref, "rows": rows, "ref_spp": s["ref_spp"]}


def cell(key, value):
    """A table cell as text."""
    if key == "tech":
        return value
    if key == "biased":
        return "biased" if value else ""
    if value is None:
        return "-"
    if key == "speedup":
        return f"{value:.2f}x" if value < 1000 else f"{value:.3g}x"
    if key in ("ms_frame", "ns_sample"):
        return f"{value:.3g}" if value < 100 else f"{value:.0f}"
    return "inf" if value == math.inf else f"{value:.3g}"


def table(rows, stdout_only=False):
    """Headers and text cells of a scene's table."""
    cols = [(h, k) for h, k, shown in COLUMNS if shown or not stdout_only]
    return [h for h, _ in cols], [[cell(k, r[k]) for _, k in cols] for r in rows]


def text_table(rows):
    """The table as aligned plain text: text left, numbers right."""
    head, body = table(rows, stdout_only=True)
    widths = [max(len(x) for x in col) for col in zip(head, *body)]

    def line(cells):
        return "  ".join(c.ljust(w) if i < 2 else c.rjust(w)
                         for i, (c, w) in enumerate(zip(cells, widths))).rstrip()
    return "\n".join([line(head), line(["-" * w for w in widths])] + [line(b) for b in body])


def md_table(rows):
    """The table in Markdown."""
    head, body = table(rows)
    sep = ["---" if i < 2 else "---:" for i in range(len(head))]
    return "\n".join("| " + " | ".join(r) + " |" for r in [head, sep] + body)


def html_table(rows):
    """The table in HTML."""
    head, body = table(rows)
    th = "".join(f"<th>{html.escape(h)}</th>" for h in head)
    trs = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in b) + "</tr>"
                  for b in body)
    return f"<table><tr>{th}</tr>{trs}</table>"


def decades(values):
    """Enclosing range of powers of ten (lo, hi), at least one decade wide."""
    lo = math.floor(math.log10(min(values)))
    hi = math.ceil(math.log10(max(values)))
    return lo, max(hi, lo + 1)


def svg_plot(title, curves, floor=None):
    """Log-log SVG of RMSE against time: curves is [(name, [(time_ms, rmse)])]."""
    W, H, L, R, T, B = 720, 420, 70, 190, 40, 50
    pts = [(t, e) for _, c in curves for t, e in c if t > 0 and e > 0]
    if not pts:
        pts = [(1.0, 1.0)]
    ys = [e for _, e in pts] + ([floor] if floor else [])
    (x0, x1), (y0, y1) = decades([t for t, _ in pts]), decades(ys)

    def px(t):
        return L + (math.log10(t) - x0) / (x1 - x0) * (W - L - R)

    def py(e):
        return H - B - (math.log10(e) - y0) / (y1 - y0) * (H - T - B)
    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
         f'viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/>',
         f'<text x="{(L + W - R) / 2}" y="22" text-anchor="middle" font-size="15">'
         f'{html.escape(title)}</text>']
    for k in range(x0, x1 + 1):
        for m in range(1, 10 if k < x1 else 2):
            x = px(m * 10.0 ** k)
            o.append(f'<line x1="{x:.1f}" y1="{T}" x2="{x:.1f}" y2="{H - B}" '
                     f'stroke="{"#ccc" if m == 1 else "#eee"}"/>')
        o.append(f'<text x="{px(10.0 ** k):.1f}" y="{H - B + 16}" '
                 f'text-anchor="middle">{10.0 ** k:g}</text>')
    for k in range(y0, y1 + 1):
        for m in range(1, 10 if k < y1 else 2):
            y = py(m * 10.0 ** k)
            o.append(f'<line x1="{L}" y1="{y:.1f}" x2="{W - R}" y2="{y:.1f}" '
                     f'stroke="{"#ccc" if m == 1 else "#eee"}"/>')
        o.append(f'<text x="{L - 6}" y="{py(10.0 ** k) + 4:.1f}" '
                 f'text-anchor="end">{10.0 ** k:g}</text>')
    o.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" '
             f'fill="none" stroke="black"/>')
    o.append(f'<text x="{(L + W - R) / 2}" y="{H - 12}" text-anchor="middle">'
             f'time of sampling passes (ms)</text>')
    o.append(f'<text transform="translate(18 {(T + H - B) / 2}) rotate(-90)" '
             f'text-anchor="middle">RMSE</text>')
    legend = list(curves) + ([("reference noise", None)] if floor else [])
    for i, (name, c) in enumerate(legend):
        colour, ly = COLOURS[i % len(COLOURS)], T + 10 + 18 * i
        if c is None:
            o.append(f'<line x1="{L}" y1="{py(floor):.1f}" x2="{W - R}" y2="{py(floor):.1f}" '
                     f'stroke="black" stroke-dasharray="5 4"/>')
            o.append(f'<line x1="{W - R + 12}" y1="{ly}" x2="{W - R + 36}" y2="{ly}" '
                     f'stroke="black" stroke-dasharray="5 4"/>')
        else:
            xy = [(px(t), py(e)) for t, e in c if t > 0 and e > 0]
            o.append(f'<polyline fill="none" stroke="{colour}" stroke-width="2" points="'
                     + " ".join(f"{x:.1f},{y:.1f}" for x, y in xy) + '"/>')
            o.extend(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="2.5" fill="{colour}"/>'
                     for x, y in xy)
            o.append(f'<line x1="{W - R + 12}" y1="{ly}" x2="{W - R + 36}" y2="{ly}" '
                     f'stroke="{colour}" stroke-width="2"/>')
        o.append(f'<text x="{W - R + 42}" y="{ly + 4}">{html.escape(name)}</text>')
    return "\n".join(o + ["</svg>\n"])


def figure(src, caption, width):
    """An image with a caption, for the HTML grid."""
    return (f'<figure><img src="{html.escape(src)}" width="{width}" alt="{html.escape(caption)}">'
            f"<figcaption>{html.escape(caption)}</figcaption></figure>")


def write_html(path, info, results, s):
    """The self-contained HTML report."""
    width = s["width"] * max(1, round(192 / s["width"]))
    parts = [f"<p>{html.escape(k)}: {html.escape(v)}</p>" for k, v in info]
    parts.append("<p>" + EXPLANATION.format(spp=s["spp"], budget=s["budget_ms"],
                                            base=BASELINE + " (sphere_cap on the sphere-light scenes, sphere_mixture on overlap)") + "</p>")
    for res in results:
        sc, rows = file_name(res["scene"]), res["rows"]
        top = [figure(f"{sc}-reference.png", f"reference ({res['ref_spp']} passes)", width)]
        top += [figure(f"{sc}-{r['tech']}-time.png",
                       f"{r['tech']}: RMSE {r['rmse_time']:.3g}", width) for r in rows]
        low = [f'<div class="label">equal samples<br>({s["spp"]} passes)</div>']
        low += [figure(f"{sc}-{r['tech']}-spp.png",
                       f"{r['tech']}: RMSE {r['rmse_spp']:.3g}", width) for r in rows]
        low += [f'<div class="label">error &times;4<br>({s["spp"]} passes)</div>']
        low += [figure(f"{sc}-{r['tech']}-spp-error.png",
                       f"{r['tech']}: image − reference", width) for r in rows]
        parts += [f"<h2>{html.escape(sc)}</h2>", html_table(rows)]
        parts += [f"<p><b>{html.escape(t)}</b>: {html.escape(why)}</p>"
                  for (scene, t), why in KNOWN_FAILURES.items() if scene == res["name"]]
        parts += [
                  f'<p><img src="rmse-{html.escape(sc)}.svg" alt="RMSE against time"></p>',
                  f"<p>Top: reference, then each technique after {s['budget_ms']:g} ms; "
                  f"middle: each technique after {s['spp']} passes; bottom: the error of "
                  f"the middle row, (image &minus; reference) &times; 4 averaged over the "
                  f"channels, red where brighter, blue where darker.</p>",
                  f'<div class="grid" style="grid-template-columns: repeat({len(top)}, '
                  f'{width}px)">' + "".join(top + low) + "</div>"]
    style = ("body{font-family:sans-serif;margin:2em;max-width:100%}"
             "table{border-collapse:collapse;margin:1em 0}"
             "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
             "td:nth-child(-n+2),th{text-align:left}"
             ".grid{display:grid;gap:8px;overflow-x:auto}"
             "figure{margin:0}img{image-rendering:pixelated}"
             "figcaption{font-size:12px}.label{align-self:center;font-size:13px}")
    with open(path, "w") as f:
        f.write(f"<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>sphera "
                f"report</title><style>{style}</style></head><body>\n<h1>sphera: speed "
                f"versus error of light sampling</h1>\n" + "\n".join(parts) + "\n</body></html>\n")


def write_markdown(path, info, results):
    """The tables in Markdown."""
    lines = ["# sphera: speed versus error of light sampling", ""]
    lines += [f"- {k}: {v}" for k, v in info]
    lines += ["", f"MSE corrected = max(RMSE^2 - reference variance of the mean, 0); "
              f"efficiency = 1 / (MSE corrected x seconds); speed-up relative to {BASELINE} (sphere_cap on the sphere-light scenes, sphere_mixture on overlap).",
              ""]
    for res in results:
        lines += [f"## {res['scene']}", "", md_table(res["rows"]), ""]
        lines += [f"**{t}**: {why}\n" for (scene, t), why in KNOWN_FAILURES.items()
                  if scene == res["name"]]
        lines += [
                  f"![RMSE against time](rmse-{file_name(res['scene'])}.svg)", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def check_means(results):
    """Failure messages and the number of unbiased techniques whose mean agrees."""
    failures, agreed = [], 0
    for res in results:
        ref = res["ref"]
        for r in res["rows"]:
            if r["biased"]:
                continue
            run = r["time"]
            if run["passes"] < 2:
                log(f"check: {res['scene']}/{r['tech']} skipped: 1 pass, no standard error")
                continue
            bad = []
            for c, (m, se, mr, ser) in enumerate(zip(run["mean"], run["mean_stderr"],
                                                     ref["mean"], ref["mean_stderr"])):
                tol = CHECK_SIGMAS * math.hypot(se, ser) + 1e-4 * abs(mr) + 1e-6
                if abs(m - mr) > tol:
                    bad.append(f"channel {'rgb'[c]}: {m:.6g} vs reference {mr:.6g} "
                               f"(|diff| {abs(m - mr):.3g} > {tol:.3g})")
            known = KNOWN_FAILURES.get((res["name"], r["tech"]))
            if known and bad:
                log(f"check: {res['scene']}/{r['tech']} disagrees, as expected: {known}")
            elif known:
                failures.append(f"check FAILED: {res['scene']}/{r['tech']} agrees with the "
                                f"reference but is listed in KNOWN_FAILURES: update the list")
            elif bad:
                failures += [f"check FAILED: {res['scene']}/{r['tech']} mean {b}" for b in bad]
            else:
                agreed += 1
    return failures, agreed


def main(argv=None):
    """Runs the report; returns the exit status."""
    start = time.monotonic()
    args = parse_args(argv)
    s, out = args.settings, args.out
    tracer = shlex.split(args.tracer)
    binary = tracer_binary(tracer)
    if binary is None:
        print(f"report: tracer not found: {args.tracer} (build it first)", file=sys.stderr)
        return 1
    common = ["--width", s["width"], "--height", s["height"]]
    if args.threads:
        common += ["--threads", args.threads]
    os.makedirs(os.path.join(out, "cache"), exist_ok=True)
    try:
        version = call(tracer, ["--version"]).strip().splitlines()[-1]
        listed = [line.split("\t") for line in call(tracer, ["--list-techniques"]).splitlines()
                  if line.strip()]
        techs = [(f[0], f[1:2] == ["biased"]) for f in listed if f[0] != "reference"]
        if args.techniques:
            wanted = [t for t in args.techniques.split(",") if t]
            unknown = set(wanted) - {t for t, _ in techs}
            if unknown:
                print(f"report: unknown techniques: {', '.join(sorted(unknown))}",
                      file=sys.stderr)
                return 2
            techs = [t for t in techs if t[0] in wanted]
        key_base = version + "\n" + sha256_file(binary)
        results = [render_scene(tracer, key_base, sc, techniques_for(sc, techs),
                                scene_settings(args, sc), out, common) for sc in args.scenes]
        indirect = None if args.no_indirect else indirect_report.run(
            lambda a: run_json(tracer, a), key_base, out, args.quick, args.threads, log)
    except TracerError as e:
        print(f"report: tracer failed: {e}", file=sys.stderr)
        return 1
    except KeyError as e:
        print(f"report: a JSON line of the tracer lacks the field {e}", file=sys.stderr)
        return 1
    for res in results:
        curves = [(r["tech"], r["curve"]) for r in res["rows"]]
        floor = math.sqrt(res["ref"]["variance_of_mean"]) or None
        title = f"{res['scene']}: RMSE against time, {s['width']}x{s['height']}"
        with open(os.path.join(out, f"rmse-{file_name(res['scene'])}.svg"), "w") as f:
            f.write(svg_plot(title, curves, floor))
    for res in results:
        print(f"\n{res['scene']} ({s['width']}x{s['height']}, {s['spp']} passes / "
              f"{s['budget_ms']:g} ms, reference {res['ref_spp']} passes)\n")
        print(text_table(res["rows"]))
    if indirect:
        print("\nVSGL one-bounce indirect (biased by design; no mean check)\n")
        print(indirect_report.text_table(indirect))
    wall = time.monotonic() - start
    info = [("date", datetime.datetime.now().astimezone().isoformat(timespec="seconds")),
            ("tracer", f"{version} ({args.tracer})"),
            ("machine", f"{os.cpu_count()} logical CPUs, {cpu_name()}, "
                        f"{platform.machine()}, {platform.system()}"),
            ("settings", f"{'quick' if args.quick else 'full'}: {s['width']}x{s['height']}, "
                         f"reference {s['ref_spp']} passes"
                         + "".join(f" ({k}: {v})" for k, v in args.ref_spp_by_scene.items()
                                   if k in {sc.partition('@')[0] for sc in args.scenes})
                         + f", equal samples {s['spp']} passes, "
                         f"equal time {s['budget_ms']:g} ms, threads "
                         f"{args.threads or 'all'}, seeds {REF_SEED} (reference) / {RUN_SEED}"),
            ("total wall time of the report", f"{wall:.1f} s")]
    index = os.path.join(out, "index.html")
    write_html(index, info, results, s)
    write_markdown(os.path.join(out, "report.md"), info, results)
    if indirect:
        indirect_report.append(index, os.path.join(out, "report.md"), indirect)
    print(f"\nreport: {index}, total wall time {wall:.1f} s")
    if not os.path.isfile(index) or os.path.getsize(index) == 0:
        print(f"report: {index} was not written", file=sys.stderr)
        return 1
    if args.check or args.quick:
        failures, agreed = check_means(results)
        if indirect:
            failures += indirect_report.check(indirect)
        for f in failures:
            print(f)
        if failures:
            return 1
        print(f"check: {agreed} unbiased technique means agree with the references "
              f"({CHECK_SIGMAS:g} sigma)")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except OSError as error:
        # An unwritable --out (or a full disk): a message, not a traceback.
        print(f"report: {error.strerror or error}: {error.filename or ''}", file=sys.stderr)
        sys.exit(1)
