#!/usr/bin/env python3
"""Default-choice benchmark (issue 15 item 4): `quadcover remesh` of every given mesh under each option variant, one
row per mesh and variant with what the report says about validity (non-positive triangles and wrong windings of the
map, non-quad faces, same topology as the input) and quality (ARAP, RSD edge / angle, feature samples covered), and
the wall time. A variant is a string of CLI options ("" = the defaults). The meshes of a row run back to back, the
variants alternating, so that the machine's noise hits them alike.

Usage: bench/compare_options.py [--build DIR] [--variant "ARGS"]... MESH...
Prints a Markdown table, then per variant the sums, the meshes where its ARAP is the lowest or equal, and the mean RSD.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time


def run(binary, mesh, args, work):
    out, rep = os.path.join(work, "q.obj"), os.path.join(work, "r.json")
    start = time.monotonic()
    p = subprocess.run([binary, "remesh", mesh, "-o", out, "-q", "--report", rep] + args.split(),
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seconds = time.monotonic() - start
    if p.returncode != 0:
        return {"exit": p.returncode, "seconds": seconds, "error": p.stderr.strip().splitlines()[-1:]}
    with open(rep) as f:
        r = json.load(f)
    par, quads, fid = r["parameterization"], r["quad_mesh"], r["feature_fidelity"]["total"]
    return {"exit": 0, "seconds": seconds, "non_positive": par["non_positive_triangles"],
            "wrong_windings": par["wrong_windings"], "non_quads": quads["non_quads"],
            "same_topology": r["surface_check"].get("same_topology"), "arap": par["arap"],
            "rsd_edge": quads["rsd_edge_length"], "rsd_angle": quads["rsd_corner_angle"], "quads": quads["faces"],
            "covered": fid["covered_percent"]}


def cell(x, fmt):
    return "–" if x is None else fmt % x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--variant", action="append", default=None)
    ap.add_argument("meshes", nargs="+")
    a = ap.parse_args()
    variants = a.variant or [""]
    binary = os.path.join(a.build, "quadcover")
    rows = []
    print("| mesh | options | non-positive / wrong windings | non-quads | same topology | ARAP | RSD edge / angle % "
          "| features covered % | quads | s |")
    print("|---|---|---|---:|---|---:|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as work:
        for mesh in a.meshes:
            name = os.path.splitext(os.path.basename(mesh))[0]
            for v in variants:
                m = run(binary, mesh, v, work)
                rows.append((name, v, m))
                label = v or "(defaults)"
                if m["exit"] != 0:
                    print(f"| {name} | {label} | exit {m['exit']}: {m['error']} | | | | | | | {m['seconds']:.1f} |")
                else:
                    print(f"| {name} | {label} | {m['non_positive']} / {m['wrong_windings']} | {m['non_quads']} | "
                          f"{'yes' if m['same_topology'] else 'no'} | {m['arap']:.4f} | {m['rsd_edge']:.1f} / "
                          f"{m['rsd_angle']:.1f} | {cell(m['covered'], '%.0f')} | {m['quads']} | {m['seconds']:.1f} |")
                sys.stdout.flush()
    print()
    for v in variants:
        ms = [m for (_, w, m) in rows if w == v and m["exit"] == 0]
        best = 0
        for name in {n for (n, _, _) in rows}:
            mine = [m for (n, w, m) in rows if n == name and w == v and m["exit"] == 0]
            others = [m for (n, w, m) in rows if n == name and w != v and m["exit"] == 0]
            if mine and all(mine[0]["arap"] <= o["arap"] for o in others):
                best += 1
        print(f"- `{v or '(defaults)'}`: {len(ms)} runs, non-positive {sum(m['non_positive'] for m in ms)}, wrong "
              f"windings {sum(m['wrong_windings'] for m in ms)}, non-quads {sum(m['non_quads'] for m in ms)}, "
              f"topology changed {sum(1 for m in ms if not m['same_topology'])}, lowest or equal ARAP on {best} meshes, "
              f"mean RSD edge {sum(m['rsd_edge'] for m in ms) / max(1, len(ms)):.2f} %, "
              f"angle {sum(m['rsd_angle'] for m in ms) / max(1, len(ms)):.2f} %, "
              f"{sum(m['seconds'] for m in ms):.1f} s")


if __name__ == "__main__":
    main()
