#!/usr/bin/env python3
"""Where the VSGLs' energy goes (issue 20, 5): the image mean of the `indirect` scene over
the reference's, one approximation added at a time (the tracer's `--variant` switches).

    python3 bench/vsgl_energy.py [--tracer bench/build/sphera-trace]
        [--width 128 --height 96 --spp 2048] [--clusters 16,64,256,1024] [--out DIR]

Rows, each a `sphera-trace --scene indirect` run against one path-traced reference
(`--technique reference`, seed 5):

  VPLs, exact                     every VPL a point light, exact BRDFs, shadow rays
  VPLs, unshadowed                the same without shadow rays
  + SG emission (Eq. 1, 2)        each VPL emits by its normalised SG lobes
  + SG shading (Eq. 6-7, Sec. 4.2) each VPL a VSGL of its own (sigma^2 = 0), SG shading
  clusters as points              per clustering and N: the VSGL at its mean, sigma^2 = 0
                                  (Toksvig lobes, the cluster collapsed to its mean)
  + positional variance           Eq. 6-7 with the cluster's spread, the receiver's
                                  integral by quadrature (64 vMF samples, exact BRDF)
  + closed-form receiver shading  constant-cosine diffuse and ASG specular (Sec. 4.2)
  + cluster visibility            V = the visible share of the cluster's VPLs (exact)
  + one ray to the mean           the method as specified (V of the mean)

and, for k-means, the clustering step split in two (`--variant exact-lobes`): each cluster
at its mean emitting the sum of its VPLs' SG lobes, then one Toksvig lobe per component.
Prints Markdown tables of the mean ratios (`--tables` picks them).
"""

import argparse
import json
import os
import subprocess
import sys


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tracer", default=os.path.join(here, "build", "sphera-trace"))
    p.add_argument("--width", type=int, default=128)
    p.add_argument("--height", type=int, default=96)
    p.add_argument("--rsm-size", type=int, default=64)
    p.add_argument("--spp", type=int, default=2048)
    p.add_argument("--clusters", default="16,64,256,1024")
    p.add_argument("--out", default="/tmp/sphera-vsgl-energy")
    p.add_argument("--tables", default="vpl,clusters,lobes",
                   help="which tables: vpl, clusters, lobes (comma-separated)")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    size = ["--width", str(a.width), "--height", str(a.height)]
    ref = os.path.join(a.out, f"ref-{a.width}x{a.height}-{a.spp}.pfm")

    def run(args):
        out = subprocess.run([a.tracer, "--scene", "indirect", "--quiet"] + size + args,
                             check=True, capture_output=True, text=True).stdout
        return json.loads(out)

    if not os.path.isfile(ref):
        run(["--technique", "reference", "--spp", str(a.spp), "--seed", "5", "--out-pfm", ref])
    common = ["--rsm-size", str(a.rsm_size), "--seed", "1", "--reference", ref]

    def ratio(technique, variant, n=None):
        args = ["--technique", technique, "--variant", variant] + common
        if n:
            args += ["--clusters", str(n)]
        r = run(args)
        print(f"  {technique} N={n} {variant}: {r['mean_ratio']:.4f}", file=sys.stderr)
        return r["mean_ratio"]

    tables = a.tables.split(",")
    counts = [int(x) for x in a.clusters.split(",")]
    print(f"{a.width}x{a.height}, RSM {a.rsm_size}^2, reference {a.spp} paths per pixel\n")
    if "vpl" in tables:
        vpl_table(ratio)
    if "clusters" in tables:
        cluster_table(ratio, counts)
    if "lobes" in tables:
        lobe_table(ratio, counts)


def vpl_table(ratio):
    print("| VPL rows (no clustering) | mean ratio |")
    print("|---|---:|")
    for label, variant in (("VPLs, exact", "none"), ("VPLs, unshadowed", "unshadowed"),
                           ("+ SG emission lobes (Eq. 1, 2)", "sg-emission,unshadowed"),
                           ("+ SG shading, each VPL a VSGL (Eq. 6-7, Sec. 4.2)",
                            "vsgl-per-vpl,unshadowed"),
                           ("each VPL a VSGL, one ray to it", "vsgl-per-vpl")):
        print(f"| {label} | {ratio('vpl', variant):.3f} |")
    print()


def cluster_table(ratio, counts):
    steps = (("points (σ² = 0), unshadowed", "point,unshadowed"),
             ("+ positional variance (receiver by quadrature)",
              "unshadowed,receiver-quadrature"),
             ("+ closed-form receiver shading", "unshadowed"),
             ("+ cluster visibility", "cluster-visibility"),
             ("+ one ray to the mean (the method)", "none"))
    print("| clustering | N | " + " | ".join(s[0] for s in steps) + " |")
    print("|---|---:|" + "---:|" * len(steps))
    for technique, name in (("fis", "FIS"), ("kmeans", "k-means")):
        for n in counts:
            cells = [f"{ratio(technique, v, n):.3f}" for _, v in steps]
            print(f"| {name} | {n} | " + " | ".join(cells) + " |")
            sys.stdout.flush()
    print()


def lobe_table(ratio, counts):
    """k-means only (its clusters are sets of VPLs): the clustering step split into the
    cluster collapsed to its mean (its VPLs' own SG lobes summed) and the one Toksvig lobe
    per component; unshadowed."""
    rows = (("each VPL its SG lobes, at its position (exact receiver)", "vpl",
             "sg-emission,unshadowed"),
            ("each cluster at its mean, its VPLs' SG lobes summed (exact receiver)", "kmeans",
             "exact-lobes"),
            ("each cluster at its mean, one Toksvig lobe per component (closed forms)", "kmeans",
             "point,unshadowed"))
    print("| k-means, unshadowed | " + " | ".join(f"N = {n}" for n in counts) + " |")
    print("|---|" + "---:|" * len(counts))
    for label, technique, variant in rows:
        if technique == "vpl":
            cells = [f"{ratio(technique, variant):.3f}"] * len(counts)
        else:
            cells = [f"{ratio(technique, variant, n):.3f}" for n in counts]
        print(f"| {label} | " + " | ".join(cells) + " |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
