"""Remesh or parameterize a folder of meshes on a Dask cluster (Debian python3-distributed).

One task per mesh; each task runs the quadcover CLI in a process of its own, so a crash, an out-of-memory kill or a
timeout costs that one file. Outputs are atomic (written in a private temporary folder, then renamed into OUT_DIR),
and the run is resumable: a mesh whose outputs are complete (the mesh, then its JSON report, renamed last) is
skipped. OUT_DIR/summary.csv and OUT_DIR/summary.json list every file: status, seconds, peak memory (of the whole
process, and of its largest stage from the report's "memory") and the quality metrics of the CLI's --report JSON.

    python3 -m quadcover.distributed [--scheduler ADDRESS] IN_DIR OUT_DIR [-- CLI OPTIONS...]

Without --scheduler a LocalCluster of --workers processes runs on this machine. In Python::

    from quadcover.distributed import run_folder
    rows = run_folder("meshes/", "out/", client=None, workers=2, cli_args=["--faces", "2000"])
"""
import argparse
import csv
import io
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

from ._cli import cli_path

MESH_EXTENSIONS = (".obj", ".off", ".ply", ".stl")
COMMANDS = {"remesh": (".quad.obj", ".remesh.json"), "param": (".param.obj", ".param.json")}
# The columns of summary.csv: the run, then metrics from the CLI's report (blank when it has none).
RUN_COLUMNS = ["file", "status", "exit_code", "seconds", "peak_memory_mb", "peak_stage", "peak_stage_mb", "output",
               "error", "worker"]
METRIC_PATHS = {
    "faces": [("quad_mesh", "faces")], "quads": [("quad_mesh", "quads")], "non_quads": [("quad_mesh", "non_quads")],
    "rsd_edge_length": [("quad_mesh", "rsd_edge_length")], "rsd_corner_angle": [("quad_mesh", "rsd_corner_angle")],
    "irregular_vertices": [("quad_mesh", "irregular_vertices")],
    "arap": [("parameterization", "arap"), ("arap",)],
    "flipped_triangles": [("parameterization", "flipped_triangles"), ("flipped_triangles",)],
    "branch_points": [("parameterization", "branch_points"), ("branch_points",)],  # a list in param's: its length
    "E_D": [("parameterization", "energy_curl"), ("E_D",)],
    "E_H": [("parameterization", "energy_harmonic"), ("E_H",)],
    "distance_max": [("surface_distance", "max")],
    "warnings": [("warnings",)],  # the report's list of degraded-result warnings: how many
}
COLUMNS = RUN_COLUMNS + list(METRIC_PATHS)


def find_inputs(in_dir):
    """Mesh files under in_dir (recursively, sorted), as paths relative to it."""
    found = []
    for root, dirs, files in os.walk(in_dir):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        found += [os.path.relpath(os.path.join(root, f), in_dir) for f in sorted(files)
                  if f.lower().endswith(MESH_EXTENSIONS)]
    return found


def output_paths(rel, out_dir, command):
    """(mesh output, report) for the input at relative path rel: OUT_DIR/<rel without extension><suffixes>."""
    stem = os.path.splitext(rel)[0]
    mesh_suffix, report_suffix = COMMANDS[command]
    return os.path.join(out_dir, stem + mesh_suffix), os.path.join(out_dir, stem + report_suffix)


def metrics_of(report):
    """The summary metrics of a CLI report dict (None where it has none)."""
    out = {}
    for name, paths in METRIC_PATHS.items():
        out[name] = None
        for path in paths:
            v = report
            for key in path:
                v = v.get(key) if isinstance(v, dict) else None
            if v is not None:
                out[name] = len(v) if isinstance(v, list) else v
                break
    return out


def largest_stage(report):
    """{peak_stage, peak_stage_mb}: the stage of the report's "memory" section with the largest peak resident memory
    (None, None for a report without one)."""
    stages = (report.get("memory") or {}).get("stages") or []
    if not stages:
        return dict(peak_stage=None, peak_stage_mb=None)
    top = max(stages, key=lambda s: s["peak_bytes"])
    return dict(peak_stage=top["stage"], peak_stage_mb=round(top["peak_bytes"] / 2**20, 1))


def process_peak_mb(sampled_kib, report):
    """The process's peak resident MB: the larger of the sampled VmHWM (the process resets it at each stage, so a
    sample can miss a short stage's peak) and the process peak the report says (None if neither is known)."""
    reported = (report.get("memory") or {}).get("peak_bytes") or 0
    peak = max(sampled_kib * 1024, reported)
    return round(peak / 2**20, 1) if peak else None


def complete_row(rel, out_dir, command):
    """The summary row of an input whose outputs are complete (report renamed last and readable), else None."""
    mesh, report = output_paths(rel, out_dir, command)
    if not (os.path.isfile(mesh) and os.path.isfile(report)):
        return None
    try:
        with open(report) as f:
            r = json.load(f)
    except (OSError, ValueError):
        return None
    run = r.get("distributed", {})
    return dict(file=rel, status="skipped", exit_code=0, seconds=run.get("seconds"),
                peak_memory_mb=run.get("peak_memory_mb"), output=os.path.relpath(mesh, out_dir), error="",
                **largest_stage(r), **metrics_of(r))


def _peak_kib(pid):
    """VmHWM (peak resident set) of a running process in KiB, 0 if it has none (exited) or is gone."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0


def _wait(proc, deadline):
    """Waits for proc, killing it at the deadline (0: none). Returns (peak KiB, timed out). The peak is the
    process's own VmHWM sampled every 20 ms (rusage would count the forking worker's memory too)."""
    peak = 0
    while True:
        peak = max(peak, _peak_kib(proc.pid))
        pid, status, _ = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            proc.returncode = os.waitstatus_to_exitcode(status)
            return peak, False
        if deadline and time.monotonic() > deadline:
            proc.kill()
            _, status, _ = os.wait4(proc.pid, 0)
            proc.returncode = os.waitstatus_to_exitcode(status)
            return peak, True
        time.sleep(0.02)


def run_one(in_dir, rel, out_dir, command="remesh", cli=None, cli_args=(), timeout=None):
    """Runs `quadcover COMMAND` on one input in a child process and moves its outputs into out_dir atomically.
    Returns the summary row. Never raises for a failing file: its row says why (status bad input / failed /
    killed by SIGNAL / timeout)."""
    cli = cli or cli_path()
    mesh_out, report_out = output_paths(rel, out_dir, command)
    os.makedirs(os.path.dirname(mesh_out) or ".", exist_ok=True)
    tmp = tempfile.mkdtemp(prefix=".quadcover-" + os.path.basename(rel) + ".", dir=os.path.dirname(mesh_out))
    row = dict(file=rel, output="", error="", worker=f"{socket.gethostname()}:{os.getpid()}",
               **{k: None for k in METRIC_PATHS})
    try:
        tmp_mesh, tmp_report = os.path.join(tmp, "out.obj"), os.path.join(tmp, "report.json")
        args = [cli, command, os.path.join(in_dir, rel), "-o", tmp_mesh, "--report", tmp_report, "-q", *cli_args]
        t0 = time.monotonic()
        with open(os.path.join(tmp, "stderr.txt"), "w+") as err:
            proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err)
            peak, timed_out = _wait(proc, t0 + timeout if timeout else 0)
            err.seek(0)
            stderr = err.read().strip()
        row["seconds"] = round(time.monotonic() - t0, 3)
        row["peak_memory_mb"] = round(peak / 1024.0, 1) if peak else None
        code = proc.returncode
        row["exit_code"] = code
        lines = [line for line in stderr.splitlines() if line.strip()]
        if timed_out:
            row["status"], row["error"] = "timeout", f"killed after {timeout} s"
        elif code < 0:
            row["status"] = "killed by " + signal.Signals(-code).name
            row["error"] = lines[-1] if lines else "no message (the process was killed)"
        elif code not in (0, 3):  # 3: partial result written (a --time-limit skipped improving stages)
            row["status"] = "bad input" if code == 2 else "failed"
            row["error"] = next((line for line in lines if line.startswith("error")), lines[-1] if lines else "")
        elif not (os.path.isfile(tmp_mesh) and os.path.isfile(tmp_report)):
            row["status"], row["error"] = "failed", f"the CLI exited {code} without writing its outputs"
        else:
            with open(tmp_report) as f:
                report = json.load(f)
            row.update(metrics_of(report))
            row.update(largest_stage(report))
            row["peak_memory_mb"] = process_peak_mb(peak, report)
            row["status"] = "partial" if code == 3 else "ok"
            report["distributed"] = {"seconds": row["seconds"], "peak_memory_mb": row["peak_memory_mb"]}
            with open(tmp_report, "w") as f:
                json.dump(report, f, indent=1)
            os.replace(tmp_mesh, mesh_out)  # the mesh first: the report's presence marks the pair complete
            os.replace(tmp_report, report_out)
            row["output"] = os.path.relpath(mesh_out, out_dir)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return row


def _atomic_write_text(path, text):
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", dir=os.path.dirname(path) or ".")
    try:
        with os.fdopen(fd, "w", newline="") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def write_summary(rows, out_dir):
    """OUT_DIR/summary.csv and summary.json (atomic), one row per input in input order."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS, extrasaction="ignore")
    w.writeheader()
    for r in rows:
        w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in COLUMNS})
    _atomic_write_text(os.path.join(out_dir, "summary.csv"), buf.getvalue())
    counts = {}
    for r in rows:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    _atomic_write_text(os.path.join(out_dir, "summary.json"),
                       json.dumps({"counts": counts, "files": rows}, indent=1) + "\n")
    return counts


def run_folder(in_dir, out_dir, client=None, workers=2, command="remesh", cli=None, cli_args=(), timeout=None,
               force=False, log=None):
    """Runs every mesh of in_dir on the Dask client's workers (a LocalCluster of `workers` processes if client is
    None); returns the summary rows (also written to OUT_DIR/summary.csv/.json). force: redo complete outputs."""
    if command not in COMMANDS:
        raise ValueError(f"command must be one of {', '.join(COMMANDS)}, got {command!r}")
    if not os.path.isdir(in_dir):
        raise ValueError(f"{in_dir}: not a folder")
    os.makedirs(out_dir, exist_ok=True)
    cli = os.path.abspath(cli or cli_path())
    inputs = find_inputs(in_dir)
    rows = {rel: (None if force else complete_row(rel, out_dir, command)) for rel in inputs}
    todo = [rel for rel in inputs if rows[rel] is None]
    log = log or (lambda s: None)
    log(f"{len(inputs)} meshes in {in_dir}: {len(inputs) - len(todo)} already complete, {len(todo)} to run")
    own_cluster = None
    if todo:
        from dask.distributed import Client, LocalCluster, as_completed

        if client is None:
            own_cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
            client = Client(own_cluster)
        try:
            futures = {client.submit(run_one, os.path.abspath(in_dir), rel, os.path.abspath(out_dir), command, cli,
                                     list(cli_args), timeout, key=f"quadcover-{command}-{rel}", pure=False): rel
                       for rel in todo}
            for fut in as_completed(futures):
                rel = futures[fut]
                try:
                    rows[rel] = fut.result()
                except Exception as e:  # the worker itself died (run_one never raises for a bad file)
                    rows[rel] = dict(file=rel, status="failed", exit_code=None, error=f"task failed: {e}")
                r = rows[rel]
                log(f"  {r['status']:>9}  {r.get('seconds') or 0:7.2f} s  {rel}" + (f"  {r['error']}"
                                                                                   if r.get("error") else ""))
        finally:
            if own_cluster is not None:
                client.close()
                own_cluster.close()
    ordered = [rows[rel] for rel in inputs]
    counts = write_summary(ordered, out_dir)
    log("summary: " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items())) + f"  ({out_dir}/summary.csv)")
    return ordered


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    cli_args = []
    if "--" in argv:
        k = argv.index("--")
        argv, cli_args = argv[:k], argv[k + 1:]
    p = argparse.ArgumentParser(prog="python3 -m quadcover.distributed",
                                description="Remesh or parameterize every mesh of IN_DIR on a Dask cluster; "
                                "options after -- go to the quadcover CLI (e.g. -- --faces 2000)")
    p.add_argument("in_dir")
    p.add_argument("out_dir")
    p.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster here)")
    p.add_argument("--workers", type=int, default=max(1, os.cpu_count() or 1),
                   help="LocalCluster worker processes (default: the cores)")
    p.add_argument("--command", choices=sorted(COMMANDS), default="remesh")
    p.add_argument("--timeout", type=float, help="seconds per mesh before its process is killed")
    p.add_argument("--cli", help="the quadcover executable (default: the package's, see quadcover.cli_path)")
    p.add_argument("--force", action="store_true", help="redo meshes whose outputs are complete")
    a = p.parse_args(argv)
    client = None
    if a.scheduler:
        from dask.distributed import Client

        client = Client(a.scheduler)
    try:
        rows = run_folder(a.in_dir, a.out_dir, client=client, workers=a.workers, command=a.command, cli=a.cli,
                          cli_args=cli_args, timeout=a.timeout, force=a.force,
                          log=lambda s: print(s, flush=True))
    except (ValueError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    finally:
        if client is not None:
            client.close()
    if not all(r["status"] in ("ok", "skipped", "partial") for r in rows):
        return 1
    return 3 if any(r["status"] == "partial" for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
