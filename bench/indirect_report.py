"""The report's section "VSGL one-bounce indirect" (the tracer's `indirect` scene).

For each clustering (FIS, k-means) and N in CLUSTERS, `sphera-trace --scene indirect`
renders VSGL frames (RSM of the spot, pyramid, clustering, closed-form shading with one
shadow ray per VSGL) and measures ms per frame (and its parts), RMSE, relative MSE and
the ratio of the image mean to the reference's (VSGLs are biased by design, so no
unbiasedness check applies). The reference is the path-traced one-bounce image (BRDF
sample at the camera hit, the spot's direct light at the next hit), cached like the
other references; a second, smaller reference with another seed estimates its noise.
Both images hold indirect light only.
"""

import hashlib
import html
import os
import shutil
import struct

CLUSTERS = {"full": [16, 64, 256, 1024], "quick": [16, 64, 256]}
SETTINGS = {
    "full": {"width": 128, "height": 96, "rsm_size": 64, "frames": 1, "ref_spp": 2048},
    "quick": {"width": 64, "height": 48, "rsm_size": 32, "frames": 1, "ref_spp": 256},
}
NOISE_SPP_DIVISOR = 8  # the noise estimate renders ref_spp / 8 paths with another seed
EXPOSURE = "1.5"
COLUMNS = (("clustering", "clustering"), ("N", "clusters"), ("ms/frame", "ms_per_frame"),
           ("ms clustering", "ms_clustering"), ("ms shading", "ms_shading"),
           ("RMSE", "rmse"), ("relMSE", "relmse"), ("mean ratio", "mean_ratio"),
           ("empty clusters", "empty_clusters"))
EXPLANATION = (
    "The <code>indirect</code> scene: a 6 m room lit by a spot light (35&deg; cone) on a GGX "
    "floor (roughness 0.45) and a glossy red wall; images hold the first bounce only. "
    "VSGLs: an RSM of {rsm}&sup2; rays from the spot (each hit a VPL), its mip pyramid, N "
    "clusters by FIS (Hammersley points, K = 1, 8 bisection steps) or by one k-means pass "
    "(Section 5: centres drawn by importance, nearest centre in |&Delta;x|&sup2;/h<sub>i</sub>&sup2; + "
    "|&Delta;y|&sup2;/h<sub>w</sub>&sup2;, h<sub>i</sub> = 1/&radic;N, h<sub>w</sub> = 6 m/&radic;N), "
    "then per pixel and VSGL the incoming-radiance SG (Eq. 6&ndash;7), constant-cosine diffuse "
    "and ASG specular shading, and one shadow ray to the VSGL's mean. <b>ms/frame</b>: RSM + "
    "pyramid + clustering + shading on all threads, mean of {frames} frame(s); <b>ms "
    "clustering</b> includes the pyramid. <b>mean ratio</b>: image mean / reference mean "
    "(VSGLs are biased by design and lose light, most of it to the positional spread of Eq. "
    "6&ndash;7 and to the single Toksvig lobe of large clusters; the README's &ldquo;Where the "
    "VSGLs' energy goes&rdquo; decomposes it with <code>bench/vsgl_energy.py</code>). "
    "Reference: {spp} one-bounce paths per "
    "pixel; its noise (RMSE) is about {noise:.2g}. <b>VPLs, exact</b> (a diagnosis, N = the "
    "VPL count): every VPL as a point light with the exact BRDFs at both ends and a shadow "
    "ray, unclamped: the RSM's own error, without clustering and SG fits.")


def _cached(call_json, key_base, out, log, s, spp, seed, name):
    """The reference image (PFM path) and JSON, rendered once per tracer binary."""
    key = hashlib.sha256("\n".join([key_base, "indirect", str(s["width"]), str(s["height"]),
                                    str(spp), str(seed)]).encode()).hexdigest()[:16]
    stem = os.path.join(out, "cache", f"ref-indirect-{s['width']}x{s['height']}-{spp}-{key}")
    if os.path.isfile(stem + ".pfm") and os.path.isfile(stem + ".png"):
        log(f"[indirect] {name}: cached {stem}.pfm")
    else:
        log(f"[indirect] {name}: rendering {spp} paths per pixel (not cached) ...")
        call_json(["--scene", "indirect", "--technique", "reference", "--spp", spp,
                   "--seed", seed, "--width", s["width"], "--height", s["height"],
                   "--out-pfm", stem + ".pfm", "--out-png", stem + ".png",
                   "--exposure", EXPOSURE])
    return stem


def run(call_json, key_base, out, quick, threads, log):
    """Renders the section; returns a dict with its rows, settings and figures."""
    mode = "quick" if quick else "full"
    s, clusters = SETTINGS[mode], CLUSTERS[mode]
    common = ["--width", s["width"], "--height", s["height"], "--quiet"]
    if threads:
        common += ["--threads", threads]
    ref = _cached(call_json, key_base, out, log, s, s["ref_spp"], 5, "reference")
    shutil.copyfile(ref + ".png", os.path.join(out, "indirect-reference.png"))
    noise_spp = max(1, s["ref_spp"] // NOISE_SPP_DIVISOR)
    other = _cached(call_json, key_base, out, log, s, noise_spp, 6, "noise estimate")
    noise = _noise(ref, other, s["ref_spp"] / noise_spp)
    rows = []
    for clustering in ("fis", "kmeans"):
        for n in clusters:
            png = f"indirect-{clustering}-{n}.png"
            r = call_json(["--scene", "indirect", "--technique", clustering, "--clusters", n,
                           "--rsm-size", s["rsm_size"], "--frames", s["frames"], "--seed", 1,
                           "--reference", ref + ".pfm", "--out-png", os.path.join(out, png),
                           "--exposure", EXPOSURE] + common)
            r["clustering"], r["png"] = clustering, png
            log(f"[indirect] {clustering} N={n}: {r['ms_per_frame']:.1f} ms/frame, "
                f"RMSE {r['rmse']:.3g}, mean ratio {r['mean_ratio']:.3f}")
            rows.append(r)
    # Diagnosis: every VPL shaded exactly as a point light (no clustering, no SG fits).
    png = "indirect-vpl.png"
    r = call_json(["--scene", "indirect", "--technique", "vpl", "--rsm-size", s["rsm_size"],
                   "--seed", 1, "--reference", ref + ".pfm", "--out-png", os.path.join(out, png),
                   "--exposure", EXPOSURE] + common)
    r["clustering"], r["png"], r["clusters"], r["empty_clusters"] = "vpl", png, r["vpls"], 0
    log(f"[indirect] exact VPLs: {r['ms_per_frame']:.1f} ms/frame, RMSE {r['rmse']:.3g}, "
        f"mean ratio {r['mean_ratio']:.3f}")
    rows.append(r)
    return {"rows": rows, "settings": s, "noise": noise, "mode": mode}


def _noise(ref, other, ratio):
    """The reference's noise RMSE from a second, independent reference with `ratio` times
    fewer paths: their mean squared difference is σ_ref² (1 + ratio), as σ² ∝ 1/paths."""

    def read(path):
        with open(path, "rb") as f:
            assert f.readline().strip() == b"PF"
            w, h = map(int, f.readline().split())
            scale = float(f.readline())
            fmt = "<" if scale < 0 else ">"
            return struct.unpack(f"{fmt}{3 * w * h}f", f.read(12 * w * h))
    a, b = read(ref + ".pfm"), read(other + ".pfm")
    mse = sum((x - y) ** 2 for x, y in zip(a, b)) / len(a)
    return (mse / (1.0 + ratio)) ** 0.5


def _cell(key, r):
    v = r[key]
    if key in ("ms_per_frame", "ms_clustering", "ms_shading"):
        return f"{v:.1f}" if v >= 1 else f"{v:.2f}"
    if key in ("rmse", "relmse"):
        return f"{v:.3g}"
    if key == "mean_ratio":
        return f"{v:.3f}"
    if key == "clustering":
        return {"fis": "FIS", "kmeans": "k-means", "vpl": "VPLs, exact"}[v]
    return str(v)


def text_table(section):
    """The table for stdout."""
    rows = [[h for h, _ in COLUMNS]] + [[_cell(k, r) for _, k in COLUMNS]
                                        for r in section["rows"]]
    widths = [max(len(row[i]) for row in rows) for i in range(len(COLUMNS))]
    return "\n".join("  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in rows)


def markdown(section):
    """The section in Markdown."""
    s = section["settings"]
    lines = ["## VSGL one-bounce indirect", "",
             f"{s['width']}x{s['height']}, RSM {s['rsm_size']}², reference {s['ref_spp']} "
             f"paths per pixel (noise RMSE about {section['noise']:.2g}); biased by design, "
             "no mean check.", "",
             "| " + " | ".join(h for h, _ in COLUMNS) + " |",
             "|---|" + "---:|" * (len(COLUMNS) - 1)]
    lines += ["| " + " | ".join(_cell(k, r) for _, k in COLUMNS) + " |" for r in section["rows"]]
    return "\n".join(lines) + "\n"


def html_section(section):
    """The section in HTML, with the images."""
    s = section["settings"]
    width = s["width"] * max(1, round(192 / s["width"]))
    head = "".join(f"<th>{html.escape(h)}</th>" for h, _ in COLUMNS)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_cell(k, r))}</td>" for _, k in COLUMNS)
                   + "</tr>" for r in section["rows"])
    figs = [f'<figure><img src="indirect-reference.png" width="{width}" alt="reference">'
            f"<figcaption>reference ({s['ref_spp']} paths)</figcaption></figure>"]
    figs += [f'<figure><img src="{html.escape(r["png"])}" width="{width}" alt="{r["png"]}">'
             f"<figcaption>{html.escape(_cell('clustering', r))} N={r['clusters']}: RMSE "
             f"{r['rmse']:.3g}</figcaption></figure>" for r in section["rows"]]
    columns = 1 + len(section["rows"]) // 2
    return ("<h2>VSGL one-bounce indirect</h2>\n<p>"
            + EXPLANATION.format(rsm=s["rsm_size"], frames=s["frames"], spp=s["ref_spp"],
                                 noise=section["noise"])
            + f"</p>\n<table><tr>{head}</tr>{body}</table>\n"
            + f'<div class="grid" style="grid-template-columns: repeat({columns}, {width}px)">'
            + "".join(figs) + "</div>\n")


def check(section):
    """Failure messages: every image finite and the clusters carrying the RSM's power
    (VSGLs are biased, so no mean check)."""
    failures = []
    for r in section["rows"]:
        name = f"indirect/{r['clustering']} N={r['clusters']}"
        if r["clustering"] == "vpl":
            continue
        if not all(m == m and abs(m) != float("inf") for m in r["mean"]):
            failures.append(f"check FAILED: {name}: image mean not finite")
        if abs(r["cluster_luminance"] - r["rsm_luminance"]) > 1e-3 * r["rsm_luminance"]:
            failures.append(f"check FAILED: {name}: clusters carry {r['cluster_luminance']:.6g}"
                            f" of the RSM's {r['rsm_luminance']:.6g}")
    return failures


def append(index_html, report_md, section):
    """Adds the section to the written HTML and Markdown reports."""
    with open(index_html) as f:
        page = f.read()
    page = page.replace("\n</body></html>", "\n" + html_section(section) + "</body></html>", 1)
    with open(index_html, "w") as f:
        f.write(page)
    with open(report_md, "a") as f:
        f.write("\n" + markdown(section))
