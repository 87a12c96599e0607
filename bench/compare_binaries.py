#!/usr/bin/env python3
"""Whole-process wall time of two quadcover binaries on the same job, alternating run by run (shared machines are
noisy: the ratio of one run is what counts), median of N, and whether their outputs are byte-identical.

Usage: bench/compare_binaries.py OLD NEW [--runs N] [--command param|remesh] [--args "ARGS"] MESH...
"""
import argparse
import filecmp
import os
import statistics
import subprocess
import tempfile
import time


def run(binary, command, mesh, out, args):
    start = time.perf_counter()
    subprocess.run([binary, command, mesh, "-o", out, "-q"] + args.split(), stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("meshes", nargs="+")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--command", default="param", choices=["param", "remesh"])
    parser.add_argument("--args", default="")
    a = parser.parse_args()
    print("| mesh | old s | new s | ratio new/old | outputs |")
    print("|---|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.meshes:
            times = {"old": [], "new": []}
            same = True
            for _ in range(a.runs):
                for name, binary in (("old", a.old), ("new", a.new)):
                    times[name].append(run(binary, a.command, mesh, os.path.join(tmp, name + ".obj"), a.args))
                same = same and filecmp.cmp(os.path.join(tmp, "old.obj"), os.path.join(tmp, "new.obj"), shallow=False)
            old, new = statistics.median(times["old"]), statistics.median(times["new"])
            name = os.path.splitext(os.path.basename(mesh))[0]
            print(f"| {name} | {old:.2f} | {new:.2f} | {new / old:.2f} | {'identical' if same else 'differ'} |",
                  flush=True)


if __name__ == "__main__":
    main()
