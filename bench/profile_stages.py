#!/usr/bin/env python3
"""Stage profile of `quadcover remesh` (issue 16): one table of stages x mesh sizes with wall time and peak resident
memory per stage, and the growth exponent k of time ~ F^k fitted over the sizes (least squares on log t, log F).

Each mesh is remeshed once with the default options (`remesh MESH -o OUT --report R.json -v`, under `nice`):
- top-level stage times come from the report's "seconds" (read, field, optimize, param, extract, smooth, metrics,
  write) and the optimize report (set-up, exact confirmations, estimates summed over threads);
- sub-stages of `param` (both parameterizations of --keep-better summed) from the time stamps of the -v progress
  lines: each line ends a sub-stage, the time since the previous line is charged to it;
- peak memory per stage: /proc/PID/status VmRSS sampled every 20 ms, maximum over the stage's time window
  (windows from the cumulative report seconds); the process peak is the larger of the maximum resident size at exit
  and the report's memory.peak_bytes (the CLI resets VmHWM at each stage, which lowers the kernel's maximum).

Usage: bench/profile_stages.py [--build DIR] [--torus F1,F2,...] [--extra "ARGS"] MESH...
  --torus 1000000 generates the bumpy torus of bench/make_torus.py with about that many faces (in a temp dir).
Prints a Markdown table (and the raw numbers as JSON with --json FILE).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP_STAGES = ["read", "field", "optimize", "param", "extract", "smooth", "metrics", "write"]
PARAM_SUB = ["cut", "curl_removal", "integrate", "harmonic_factor", "period_rounding", "round", "harmonic",
             "relaxation", "stiffening", "assemble"]


def count_faces(path):
    n = 0
    with open(path, "rb") as f:
        for line in f:
            if line.startswith(b"f "):
                n += len(line.split()) - 3  # fan triangles of a polygon
    return n


def rss_kb(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def run_one(binary, mesh, extra, work):
    out = os.path.join(work, "out.obj")
    report = os.path.join(work, "report.json")
    cmd = ["nice", "/usr/bin/time", "-f", "%e %M", "-o", os.path.join(work, "time.txt"), binary, "remesh", mesh,
           "-o", out, "--report", report, "-v"] + extra
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, bufsize=1)
    lines = []

    def reader():
        for line in proc.stderr:
            lines.append((time.monotonic() - t0, line.rstrip("\n")))

    th = threading.Thread(target=reader)
    th.start()
    samples = []
    child = None
    while proc.poll() is None:
        if child is None:  # the quadcover process under nice + time
            try:
                kids = open("/proc/%d/task/%d/children" % (proc.pid, proc.pid)).read().split()
                while kids:
                    child = int(kids[0])
                    kids = open("/proc/%d/task/%d/children" % (child, child)).read().split()
            except OSError:
                child = None
        if child is not None:
            kb = rss_kb(child)
            if kb is not None:
                samples.append((time.monotonic() - t0, kb))
        time.sleep(0.02)
    th.join()
    wall = time.monotonic() - t0
    if proc.returncode != 0:
        sys.exit("remesh failed on %s (exit %d):\n%s" % (mesh, proc.returncode, "\n".join(l for _, l in lines[-5:])))
    secs, peak_kb = open(os.path.join(work, "time.txt")).read().split()[-2:]
    rep = json.load(open(report))
    return rep, lines, samples, float(secs), int(peak_kb), wall


def stage_rows(rep, lines, samples, secs, peak_kb):
    """{stage: (seconds, peak MB or None)} for one run."""
    rows = {}
    s = rep["seconds"]
    # windows: cumulative report seconds from the first RSS sample (the process start; CLI parsing takes ms).
    t = samples[0][0] if samples else 0.0
    for k in TOP_STAGES:
        d = s.get(k, 0.0)
        window = [kb for (ts, kb) in samples if t - 0.02 <= ts <= t + d + 0.02]
        rows[k] = (d, max(window) / 1024 if window else None)
        t += d
    o = rep.get("optimize", {}).get("seconds", {})
    if o:
        ex = o.get("exact", {})
        rows["optimize: set-up"] = (o.get("setup", float("nan")), None)
        rows["optimize: exact evaluations"] = (sum(v for v in ex.values()), None)
        es = o.get("estimates", {})
        rows["optimize: estimates (Σ threads)"] = (sum(v for k, v in es.items() if k != "count"), None)
    sub = {k: 0.0 for k in PARAM_SUB}
    prev = None
    for ts, line in lines:
        m = re.match(r"param\s+([a-z_]+)", line)
        if m and prev is not None and m.group(1) in sub:
            sub[m.group(1)] += ts - prev
        prev = ts
    sub["period_rounding"] += sub.pop("round")
    for k, v in sub.items():
        rows["param: " + k] = (v, None)
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
            rep, lines, samples, secs, peak_kb, _ = run_one(binary, m, a.extra.split(), work)
            runs.append((os.path.basename(m), F, stage_rows(rep, lines, samples, secs, peak_kb)))
    runs.sort(key=lambda r: r[1])
    names = list(runs[0][2].keys())
    print("| stage | " + " | ".join("%s (%.0fk F)" % (n, F / 1000) for n, F, _ in runs) + " | k |")
    print("|---|" + "---:|" * (len(runs) + 1))
    for st in names:
        cells = []
        for _, F, rows in runs:
            t, mb = rows.get(st, (float("nan"), None))
            cells.append(("%.2f s" % t if not math.isnan(t) else "–") + (" / %.0f MB" % mb if mb else ""))
        k = fit_k([(F, rows.get(st, (None,))[0]) for _, F, rows in runs])
        print("| %s | %s | %s |" % (st, " | ".join(cells), "%.2f" % k if k is not None else "–"))
    per_face = [(n, rows["whole process"][1] * 1024 * 1024 / F) for n, F, rows in runs]
    print("\nWhole-process peak per face: " + ", ".join("%s %.1f KB" % (n, b / 1024) for n, b in per_face))
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{"mesh": n, "faces": F, "stages": rows} for n, F, rows in runs], f, indent=1)


if __name__ == "__main__":
    main()
