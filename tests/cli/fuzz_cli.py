#!/usr/bin/env python3
"""Fuzz-style test of the quadcover command line (issue 18): random commands and options on corrupted inputs.

Inputs are the files of tests/data/bad, a small valid mesh (tests/data/eight_genus2.obj) and mutated copies of it
(flipped bytes, truncation, deleted / repeated / shuffled lines, garbage lines, out-of-range and negative indices,
NaN coordinates, random bytes, an empty file, OBJ text under .off/.ply/.stl names). Each run is one command on one
input (a file or "-" on standard input) with random options (valid, invalid and contradictory values). Asserted
after every run:
  - no crash: the process exits by itself (not by a signal), within the per-run timeout;
  - the exit code is one of 0, 1, 2, 3;
  - on a non-zero exit no output file was left (the output folder holds nothing new);
  - no temporary file (".NAME.tmpPID.N") anywhere in the work folder;
  - every input file is byte-identical afterwards.
The seed is fixed (FUZZ_CLI_SEED, default 18) and the time bounded (FUZZ_CLI_SECONDS, default 40 s), so a failure
repeats; the failing command line is printed. Usage: fuzz_cli.py [QUADCOVER_BINARY]
"""
import hashlib
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.environ.get("QUADCOVER_BIN", "build/quadcover"))
SEED = int(os.environ.get("FUZZ_CLI_SEED", "18"))
BUDGET = float(os.environ.get("FUZZ_CLI_SECONDS", "40"))
RUN_TIMEOUT = 30  # seconds for one run: a hang fails (huge densities are left out: issue 18 item 2, memory estimate)

rng = random.Random(SEED)


def mutations(text: bytes):
    """Named corrupted variants of a small OBJ file."""
    lines = text.split(b"\n")
    out = {}
    b = bytearray(text)
    for i in range(20):
        b[rng.randrange(len(b))] = rng.randrange(256)
    out["flipped.obj"] = bytes(b)
    out["truncated.obj"] = text[: rng.randrange(len(text) // 4, len(text))]
    out["deleted_lines.obj"] = b"\n".join(l for l in lines if rng.random() > 0.05)
    out["repeated_lines.obj"] = b"\n".join(l for l in lines for _ in range(2 if rng.random() < 0.05 else 1))
    shuffled = lines[:]
    rng.shuffle(shuffled)
    out["shuffled.obj"] = b"\n".join(shuffled)
    out["garbage_lines.obj"] = b"\n".join(l if rng.random() > 0.03 else bytes(rng.randrange(256) for _ in range(12))
                                          for l in lines)
    out["far_index.obj"] = text + b"\nf 1 2 99999\n"
    out["negative_index.obj"] = text + b"\nf 1 2 -100000\n"
    out["nan.obj"] = text.replace(b"v ", b"v nan ", 1)
    out["polygon.obj"] = text + b"\nf 1 2 3 4 5\n"
    out["isolated.obj"] = text + b"\nv 9 9 9\n"
    out["random.obj"] = bytes(rng.randrange(256) for _ in range(3000))
    out["empty.obj"] = b""
    out["obj_as.off"] = text
    out["obj_as.ply"] = text
    out["obj_as.stl"] = text
    out["random.stl"] = bytes(rng.randrange(256) for _ in range(84 + 50 * 3))  # a binary STL of 3 random facets
    return out


def option_pools(command, out_dir):
    """(valid, invalid) options for `command`; outputs go to out_dir."""
    o = lambda name: os.path.join(out_dir, name)
    common = [["--json"], ["-q"], ["-v"], ["--time-limit", "1"], ["-j", "1"], ["--skip-existing"],
              ["--overwrite-input"], ["--format", "off"]]
    common_bad = [["--time-limit", "-1"], ["--format", "xyz"], ["--bogus"], ["-j", "x"]]
    valid = {
        "info": [["--triangulate"], ["--fix-orientation"]],
        "repair": [["-o", o("r.obj")], ["-o", o("r.off")], ["-o", o("r.ply")], ["-o", o("r.stl")],
                   ["-o", o("new/r.obj")], ["-o", "-"]],
        "field": [["-o", o("f.json")], ["--method", "csm"], ["--rounds", "0"], ["--features", "off"],
                  ["--fill", "propagate"], ["-o", "-"]],
        "metrics": [["--report", o("m.json")], ["--no-extract"],
                    ["--ref", os.path.join(ROOT, "tests/data/eight_genus2.obj")]],
        "render": [["-o", o("p.png")], ["--size", "64x64"], ["--view", "iso"], ["--uv-layout"], ["--wireframe"],
                   ["--texture", "grid"]],
        "param": [["-o", o("p.obj")], ["--quads", "50"], ["--lattice", "coarse"], ["--optimize", "none"],
                  ["--report", o("p.json")]],
        "remesh": [["-o", o("q.obj")], ["-o", o("q.ply")], ["-o", o("q.stl")], ["--vertices", "60"],
                   ["--optimize", "none"], ["--smooth-quads", "0"], ["--report", o("q.json")]],
    }
    invalid = {
        "info": [],
        "repair": [["-o", o("r.xyz")], ["-o", "/proc/forbidden/r.obj"], ["-o", out_dir]],
        "field": [["--method", "nope"], ["--trusted", "2"], ["--lambda", "0"], ["--features", "abc"],
                  ["--report", o("f.report.json")]],
        "metrics": [["--ref", "/nonexistent.obj"]],
        "render": [["--size", "1x1"], ["--view", "up"], ["--supersample", "0"]],
        "param": [["--quads", "-3"], ["--edge-length", "1e9"], ["--quads", "5", "--edge-length", "1"]],
        "remesh": [["--vertices", "0"], ["--edge-length", "-1"], ["-o", "/proc/forbidden/q.obj"]],
    }
    return valid[command] + common, invalid[command] + common_bad


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def temporaries(folder):
    return [os.path.join(d, f) for d, _, files in os.walk(folder) for f in files if ".tmp" in f]


def main():
    if not os.access(BIN, os.X_OK):
        print(f"fuzz_cli: {BIN} is not an executable (build the quadcover target)")
        return 1
    work = tempfile.mkdtemp(prefix="quadcover_fuzz_cli_")
    try:
        return fuzz(work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def fuzz(work):
    inputs_dir = os.path.join(work, "in")
    os.makedirs(inputs_dir)
    small = open(os.path.join(ROOT, "tests/data/eight_genus2.obj"), "rb").read()
    files = {"eight_genus2.obj": small, **mutations(small)}
    bad_dir = os.path.join(ROOT, "tests/data/bad")
    for name in sorted(os.listdir(bad_dir)):
        files["bad_" + name] = open(os.path.join(bad_dir, name), "rb").read()
    for name, data in files.items():
        with open(os.path.join(inputs_dir, name), "wb") as f:
            f.write(data)
    inputs = sorted(os.path.join(inputs_dir, n) for n in files)
    hashes = {p: digest(p) for p in inputs}
    # The slow commands run on the small meshes only; the others on anything.
    small_inputs = [p for p in inputs if os.path.getsize(p) <= 40000]
    commands = ["info", "repair", "field", "metrics", "render", "param", "remesh"]
    weights = [3, 3, 2, 2, 2, 1, 1]

    start = time.monotonic()
    runs = 0
    failures = []
    codes = {}
    while time.monotonic() - start < BUDGET and len(failures) < 5:
        runs += 1
        command = rng.choices(commands, weights)[0]
        out_dir = os.path.join(work, f"out{runs}")
        os.makedirs(out_dir)
        valid, invalid = option_pools(command, out_dir)
        chosen = rng.sample(valid, rng.randint(0, min(3, len(valid))))
        if rng.random() < 0.2:  # now and then one invalid or contradictory option
            chosen.append(rng.choice(invalid))
        options = [x for opt in chosen for x in opt]
        target = rng.choice(small_inputs if command in ("param", "remesh", "field") else inputs)
        stdin = None
        args = [BIN, command]
        if rng.random() < 0.1:
            args.append("-")
            stdin = open(target, "rb")
        else:
            args.append(target)
        if command in ("param", "remesh", "field", "metrics") and "--time-limit" not in options:
            options += ["--time-limit", "5"]  # keep runs short; the stop path is exercised too
        args += options
        shown = " ".join(args) + (f" < {target}" if stdin else "")
        before = set(os.listdir(out_dir))
        before_inputs = set(os.listdir(inputs_dir))  # outputs without -o go next to the input
        try:
            r = subprocess.run(args, stdin=stdin or subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, timeout=RUN_TIMEOUT, cwd=out_dir)
        except subprocess.TimeoutExpired:
            failures.append(f"hang (> {RUN_TIMEOUT} s): {shown}")
            continue
        finally:
            if stdin:
                stdin.close()
        codes[r.returncode] = codes.get(r.returncode, 0) + 1
        problems = []
        if r.returncode < 0:
            problems.append(f"killed by signal {-r.returncode}")
        elif r.returncode not in (0, 1, 2, 3):
            problems.append(f"exit code {r.returncode}")
        if r.returncode == 3 and "partial" not in r.stderr.decode(errors="replace") + r.stdout.decode(errors="replace") \
                and "cut short" not in r.stderr.decode(errors="replace"):
            problems.append("exit 3 (partial result) without saying what was cut short")
        if r.returncode not in (0, 3):  # 3 = partial result written: its outputs are complete
            left = sorted(set(os.listdir(out_dir)) - before - {"new"})
            left += [os.path.join("new", f) for f in os.listdir(os.path.join(out_dir, "new"))] \
                if os.path.isdir(os.path.join(out_dir, "new")) else []
            left += sorted(set(os.listdir(inputs_dir)) - before_inputs)
            if left:
                problems.append(f"exit {r.returncode} but outputs left: {left}")
            if not r.stderr.strip():
                problems.append(f"exit {r.returncode} without a message")
        for name in set(os.listdir(inputs_dir)) - before_inputs:  # keep the input folder as it was
            if not name.startswith("."):
                os.remove(os.path.join(inputs_dir, name))
        tmp = temporaries(work)
        if tmp:
            problems.append(f"temporary files left: {tmp}")
            for t in tmp:
                os.remove(t)
        changed = [p for p in inputs if digest(p) != hashes[p]]
        if changed:
            problems.append(f"inputs modified: {changed}")
            for p in changed:
                hashes[p] = digest(p)
        if problems:
            err = r.stderr.decode(errors="replace").strip().splitlines()[-3:]
            failures.append(f"{'; '.join(problems)}\n    command: {shown}\n    stderr: {' | '.join(err)}")
        shutil.rmtree(out_dir, ignore_errors=True)

    seconds = time.monotonic() - start
    print(f"fuzz_cli: {runs} runs in {seconds:.0f} s (seed {SEED}), exit codes {dict(sorted(codes.items()))}")
    for f in failures:
        print("FAILED: " + f)
    print(f"{runs - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
