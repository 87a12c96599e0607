"""quadcover.distributed on a 2-worker Dask LocalCluster (separate processes): shipped meshes, a broken file and a
file whose process is killed mid-run; summary CSV/JSON, atomic outputs, and a resumed run that skips what is done.
Run by scripts/tests.d/34_dask.sh (needs Debian's python3-distributed)."""
import csv
import json
import os
import shutil
import stat
import subprocess
import sys

import pytest

import quadcover
from quadcover import distributed

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "tests", "data")


def killing_wrapper(path, real_cli):
    """A stand-in CLI that starts the real one and, for inputs named *killme*, SIGKILLs it (and itself) after 0.5 s:
    what the OOM killer does to a run."""
    path.write_text(f"""#!/bin/bash
case "$*" in
  *killme*) "{real_cli}" "$@" & pid=$!; sleep 0.5; kill -9 $pid; wait $pid; kill -9 $$ ;;
  *) exec "{real_cli}" "$@" ;;
esac
""")
    path.chmod(path.stat().st_mode | stat.S_IEXEC)
    return str(path)


def run_cli(args):
    r = subprocess.run([sys.executable, "-m", "quadcover.distributed", *args], capture_output=True, text=True,
                       timeout=300)
    print(r.stdout, r.stderr)
    return r


def read_summary(out):
    with open(os.path.join(out, "summary.csv")) as f:
        rows = {r["file"]: r for r in csv.DictReader(f)}
    with open(os.path.join(out, "summary.json")) as f:
        doc = json.load(f)
    assert [r["file"] for r in doc["files"]] == list(rows)  # the same files, in the same order
    return rows, doc


@pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")  # tornado, under Dask 2022.12
def test_folder_on_two_workers_survives_a_broken_and_a_killed_file_and_resumes(tmp_path):
    src = tmp_path / "in"
    (src / "sub").mkdir(parents=True)
    shutil.copy(os.path.join(DATA, "bunny_3k.obj"), src / "bunny_3k.obj")
    shutil.copy(os.path.join(DATA, "torus_5k.obj"), src / "sub" / "torus_5k.obj")
    shutil.copy(os.path.join(DATA, "spot.obj"), src / "killme.obj")
    (src / "broken.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")  # index out of range
    (src / "notes.txt").write_text("not a mesh\n")
    out = tmp_path / "out"
    wrapper = killing_wrapper(tmp_path / "qc.sh", quadcover.cli_path())

    r = run_cli(["--workers", "2", "--cli", wrapper, str(src), str(out), "--", "--vertices", "600"])
    assert r.returncode == 1  # some files failed
    rows, doc = read_summary(out)
    assert sorted(rows) == ["broken.obj", "bunny_3k.obj", "killme.obj", os.path.join("sub", "torus_5k.obj")]
    for name in ("bunny_3k", os.path.join("sub", "torus_5k")):
        row = rows[name + ".obj"]
        assert row["status"] == "ok" and row["exit_code"] == "0", row
        assert int(row["faces"]) > 300 and int(row["non_quads"]) == 0 and float(row["rsd_edge_length"]) > 0
        assert float(row["seconds"]) > 0 and float(row["peak_memory_mb"]) > 5
        assert row["peak_stage"] != "" and 0 < float(row["peak_stage_mb"]) <= float(row["peak_memory_mb"])
        assert quadcover.read(out / (name + ".quad.obj")).vertices.shape[0] > 300
        with open(out / (name + ".remesh.json")) as f:
            report = json.load(f)
        assert report["quad_mesh"]["faces"] == int(row["faces"])
        assert row["peak_stage"] in [s["stage"] for s in report["memory"]["stages"]]
    assert rows["broken.obj"]["status"] == "bad input" and "broken.obj" in rows["broken.obj"]["error"]
    assert rows["killme.obj"]["status"] == "killed by SIGKILL", rows["killme.obj"]
    assert doc["counts"] == {"ok": 2, "bad input": 1, "killed by SIGKILL": 1}
    # Two worker processes took part, and nothing partial or temporary is left.
    assert len({row["worker"] for row in doc["files"]}) == 2
    left = sorted(os.path.relpath(os.path.join(d, f), out) for d, _, fs in os.walk(out) for f in fs)
    assert left == sorted(["bunny_3k.quad.obj", "bunny_3k.remesh.json", "summary.csv", "summary.json",
                           os.path.join("sub", "torus_5k.quad.obj"), os.path.join("sub", "torus_5k.remesh.json")])
    assert not [d for _, ds, _ in os.walk(out) for d in ds if d.startswith(".quadcover")]

    # Resume with the real CLI, on a running cluster given by its scheduler address: complete outputs are skipped
    # (untouched), the killed file now runs.
    from dask.distributed import LocalCluster

    before = os.stat(out / "bunny_3k.quad.obj").st_mtime_ns
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        r = run_cli(["--scheduler", cluster.scheduler_address, str(src), str(out), "--", "--vertices", "600"])
    rows, doc = read_summary(out)
    assert rows["bunny_3k.obj"]["status"] == "skipped" and rows["bunny_3k.obj"]["faces"] != ""
    assert rows[os.path.join("sub", "torus_5k.obj")]["status"] == "skipped"
    assert os.stat(out / "bunny_3k.quad.obj").st_mtime_ns == before
    assert rows["killme.obj"]["status"] == "ok" and (out / "killme.quad.obj").exists()
    assert rows["broken.obj"]["status"] == "bad input"
    assert r.returncode == 1


def test_incomplete_outputs_are_redone_and_param_runs(tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    shutil.copy(os.path.join(DATA, "torus_5k.obj"), src / "torus.obj")
    out = tmp_path / "out"
    out.mkdir()
    (out / "torus.param.obj").write_text("v 0 0 0\n")  # left by a run that died before its report
    (out / "torus.param.json").write_text('{"truncated": ')
    assert distributed.complete_row("torus.obj", str(out), "param") is None
    # run_one in this process (no cluster): the same code the workers run.
    row = distributed.run_one(str(src), "torus.obj", str(out), "param", cli_args=["--quads", "400"])
    assert row["status"] == "ok", row
    assert row["flipped_triangles"] is not None and row["branch_points"] == 0  # a torus needs no branch point
    m = quadcover.read(out / "torus.param.obj")
    assert m.uv is not None and len(m.faces) == 4608  # the input triangles, with per-corner vt
    assert distributed.complete_row("torus.obj", str(out), "param")["status"] == "skipped"


def test_bad_arguments_exit_2(tmp_path):
    r = run_cli([str(tmp_path / "missing"), str(tmp_path / "out")])
    assert r.returncode == 2 and "not a folder" in r.stderr
