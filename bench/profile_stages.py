#!/usr/bin/env python3
"""Stage profile of `quadcover remesh` (issue 16): one table of stages x mesh sizes with wall time and peak resident
memory per stage, and the growth exponent k of time ~ F^k fitted over the sizes (least squares on log t, log F).

Each mesh is remeshed once with the default options (`remesh MESH -o OUT --report R.json -q`, under `nice`). The
stages are the report's own, in the order they ran (`memory.stages`: every stage the job timed, e.g. field, optimize,
param_curl_removal, ..., param_untangling, cone_merging, fold_refinement, extract, smooth, metrics, write), each with
its `seconds` and its peak resident bytes; Algorithm 6.1's set-up, exact evaluations and estimates come from the
optimize report. The whole-process row is the wall time of the command and the larger of /usr/bin/time's maximum
resident size and the report's `memory.peak_bytes` (the CLI resets VmHWM at each stage, which lowers the kernel's).

Usage: bench/profile_stages.py [--build DIR] [--torus F1,F2,...] [--extra "ARGS"] MESH...
  --torus 1000000 generates the bumpy torus of bench/make_torus.py with about that many faces (in a temp dir).
Prints a Markdown table (and the raw numbers as JSON with --json FILE).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def count_faces(path):
    n = 0
    with open(path, "rb") as f:
        for line in f:
            if line.startswith(b"f "):
                n += len(line.split()) - 3  # fan triangles of a polygon
    return n


def run_one(binary, mesh, extra, work):
    out = os.path.join(work, "out.obj")
    report = os.path.join(work, "report.json")
    cmd = ["nice", "/usr/bin/time", "-f", "%e %M", "-o", os.path.join(work, "time.txt"), binary, "remesh", mesh,
           "-o", out, "--report", report, "-q"] + extra
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.exit("remesh failed on %s (exit %d):\n%s" % (mesh, proc.returncode, proc.stderr[-2000:]))
    secs, peak_kb = open(os.path.join(work, "time.txt")).read().split()[-2:]
    return json.load(open(report)), float(secs), int(peak_kb)


def stage_rows(rep, secs, peak_kb):
    """{stage: (seconds, peak MB or None)} for one run, stages in the order the job ran them."""
    rows = {}
    seconds = rep["seconds"]
    for st in rep.get("memory", {}).get("stages", []):
        name = st["stage"]
        rows[name] = (seconds.get(name, float("nan")), st["peak_bytes"] / 2**20)
    o = rep.get("optimize", {}).get("seconds", {})
    if o:
        ex = o.get("exact", {})
        rows["optimize: set-up"] = (o.get("setup", float("nan")), None)
        rows["optimize: exact evaluations"] = (sum(v for v in ex.values()), None)
        es = o.get("estimates", {})
        rows["optimize: estimates (Σ threads)"] = (sum(v for k, v in es.items() if k != "count"), None)
    reported_kb = rep.get("memory", {}).get("peak_bytes", 0) / 1024
    rows["whole process"] = (secs, max(peak_kb, reported_kb) / 1024)
    return rows


def fit_k(points):
    pts = [(math.log(f), math.log(t)) for f, t in points if t and t > 0.02 and not math.isnan(t)]
    if len(pts) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx if sxx > 0 else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--build", default="build")
    ap.add_argument("--torus", default="")
    ap.add_argument("--extra", default="", help="extra remesh arguments, e.g. '--vertices 6500'")
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    binary = os.path.join(a.build, "quadcover")
    if not os.access(binary, os.X_OK):
        sys.exit("missing %s: cmake --build %s --target quadcover" % (binary, a.build))
    with tempfile.TemporaryDirectory() as work:
        meshes = list(a.meshes)
        for f in [int(x) for x in a.torus.split(",") if x]:
            path = os.path.join(work, "torus_%d.obj" % f)
            subprocess.check_call([sys.executable, os.path.join(HERE, "make_torus.py"), path, str(f)])
            meshes.append(path)
        runs = []
        for m in meshes:
            F = count_faces(m)
            print("running %s (%d faces)" % (os.path.basename(m), F), file=sys.stderr, flush=True)
            rep, secs, peak_kb = run_one(binary, m, a.extra.split(), work)
            runs.append((os.path.basename(m), F, stage_rows(rep, secs, peak_kb),
                         len(rep.get("validity_retries", {}).get("attempts", [None]))))
    runs.sort(key=lambda r: r[1])
    tail = ["optimize: set-up", "optimize: exact evaluations", "optimize: estimates (Σ threads)", "whole process"]
    names = []  # the stages of every run, in the order of the first run that has them; the summary rows last
    for _, _, rows, _ in runs:
        names += [st for st in rows if st not in names and st not in tail]
    names += tail
    print("| stage | " + " | ".join("%s (%.0fk F)" % (n, F / 1000) for n, F, _, _ in runs) + " | k |")
    print("|---|" + "---:|" * (len(runs) + 1))
    for st in names:
        cells = []
        for _, F, rows, _ in runs:
            t, mb = rows.get(st, (float("nan"), None))
            cells.append(("%.2f s" % t if not math.isnan(t) else "–") + (" / %.0f MB" % mb if mb else ""))
        k = fit_k([(F, rows.get(st, (None,))[0]) for _, F, rows, _ in runs])
        print("| %s | %s | %s |" % (st, " | ".join(cells), "%.2f" % k if k is not None else "–"))
    per_face = [(n, rows["whole process"][1] * 1024 * 1024 / F) for n, F, rows, _ in runs]
    print("\nWhole-process peak per face: " + ", ".join("%s %.1f KB" % (n, b / 1024) for n, b in per_face))
    # The stage rows are the kept attempt's; the whole process ran every attempt (pipeline/validity_retries.h).
    print("Whole jobs run (validity attempts): " + ", ".join("%s %d" % (n, k) for n, _, _, k in runs))
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{"mesh": n, "faces": F, "stages": rows, "attempts": k} for n, F, rows, k in runs], f, indent=1)


if __name__ == "__main__":
    main()
