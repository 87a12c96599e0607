"""quadcover.distributed's summary memory columns without a cluster (run_one is what each Dask task runs): the process
peak and the report's largest stage."""
import json
import os
import shutil

from quadcover import distributed

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data")


def test_summary_row_has_the_process_peak_and_the_largest_stage(tmp_path):
    src, out = tmp_path / "in", tmp_path / "out"
    src.mkdir()
    shutil.copy(os.path.join(DATA, "bunny_3k.obj"), src / "bunny.obj")
    row = distributed.run_one(str(src), "bunny.obj", str(out), "remesh", cli_args=["--faces", "400"])
    assert row["status"] == "ok", row
    with open(out / "bunny.remesh.json") as f:
        report = json.load(f)
    stages = report["memory"]["stages"]
    top = max(stages, key=lambda s: s["peak_bytes"])
    assert row["peak_stage"] == top["stage"]
    assert row["peak_stage_mb"] == round(top["peak_bytes"] / 2**20, 1) > 0
    # The whole process's peak covers every stage's, and the report records what the summary says.
    assert row["peak_memory_mb"] >= row["peak_stage_mb"]
    assert row["peak_memory_mb"] >= round(report["memory"]["peak_bytes"] / 2**20, 1)
    assert report["distributed"]["peak_memory_mb"] == row["peak_memory_mb"]
    # A resumed run reads the same columns back from the report.
    skipped = distributed.complete_row("bunny.obj", str(out), "remesh")
    assert skipped["status"] == "skipped"
    assert (skipped["peak_stage"], skipped["peak_stage_mb"]) == (row["peak_stage"], row["peak_stage_mb"])


def test_reports_without_memory_give_empty_columns():
    assert distributed.largest_stage({}) == {"peak_stage": None, "peak_stage_mb": None}
    assert distributed.process_peak_mb(0, {}) is None
    assert distributed.process_peak_mb(2048, {"memory": {"peak_bytes": 3 * 2**20}}) == 3.0  # the larger one
    assert distributed.process_peak_mb(4096, {"memory": {"peak_bytes": 3 * 2**20}}) == 4.0
