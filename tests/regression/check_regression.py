#!/usr/bin/python3
"""Quality regression check: compares the key metrics of the end-to-end run (tests/e2e/e2e.py --metrics-out) with
the baseline in tests/regression/metrics.json and fails when a mesh got WORSE beyond the tolerance of a metric.
Better is fine (reported as a hint to tighten the baseline). Standard library only.

metrics.json:
  "rules":  metric -> {"better": "lower" | "true", "rel": r, "abs": a, "doc": "..."}
            lower: worse when current > baseline + max(abs, rel * |baseline|)
            true:  worse when the baseline is true and the current value is false (e.g. a manifold output)
  "meshes": mesh -> metric -> baseline value (default options of `quadcover param` / `remesh`)
  "known_issues": mesh -> [text]  defects accepted for now (e.g. a non-manifold output); tests/e2e/e2e.py reads it
  "updated": how and when the baseline was written

Usage:
  check_regression.py CURRENT.json [--baseline tests/regression/metrics.json] [--subset]
  check_regression.py CURRENT.json --update     rewrite the baseline values (rules and tolerances are kept)
  check_regression.py --self-test
To accept a deliberate change: `bash scripts/update_regression.sh` and commit tests/regression/metrics.json.
"""

import argparse
import json
import os
import sys

BASELINE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "metrics.json")
HINT = ("If the change is intended (e.g. more branch points for less distortion), update the baseline with\n"
        "  bash scripts/update_regression.sh\n"
        "and commit tests/regression/metrics.json with a message saying why.")


def allowance(rule, base):
    return max(rule.get("abs", 0.0), rule.get("rel", 0.0) * abs(base))


def compare(baseline, current, subset=False):
    """Returns (worse, better) lists of human-readable lines. subset: only the meshes present in `current`."""
    worse, better = [], []
    rules = baseline["rules"]
    for mesh, base_values in sorted(baseline["meshes"].items()):
        if subset and mesh not in current:
            continue
        if mesh not in current:
            worse.append(f"{mesh}: no current metrics (the end-to-end run failed or skipped this mesh)")
            continue
        cur_values = current[mesh]
        for metric, base in sorted(base_values.items()):
            rule = rules.get(metric)
            if rule is None:
                continue
            if metric not in cur_values:
                worse.append(f"{mesh}: metric {metric} is missing from the current run")
                continue
            cur = cur_values[metric]
            if rule["better"] == "true":
                if base is True and cur is not True:
                    worse.append(f"{mesh}: {metric} was true, now {cur}")
                elif base is not True and cur is True:
                    better.append(f"{mesh}: {metric} is now true (baseline {base})")
                continue
            slack = allowance(rule, base)
            if cur > base + slack:
                worse.append(f"{mesh}: {metric} {cur:.6g} is worse than the baseline {base:.6g} "
                             f"(tolerance +{slack:.3g})")
            elif cur < base - slack:
                better.append(f"{mesh}: {metric} {cur:.6g} improved on the baseline {base:.6g}")
    return worse, better


def update(baseline, current, note):
    for mesh, values in current.items():
        baseline["meshes"][mesh] = {k: v for k, v in sorted(values.items()) if k in baseline["rules"]}
    baseline["updated"] = note
    return baseline


def self_test():
    base = {"rules": {"rsd": {"better": "lower", "rel": 0.1, "abs": 1.0}, "manifold": {"better": "true"}},
            "meshes": {"m": {"rsd": 10.0, "manifold": True}, "gone": {"rsd": 5.0}}}
    worse, better = compare(base, {"m": {"rsd": 10.9, "manifold": True}, "gone": {"rsd": 0.0}})
    assert not worse and better == ["gone: rsd 0 improved on the baseline 5"], (worse, better)
    worse, _ = compare(base, {"m": {"rsd": 11.1, "manifold": False}})
    assert len(worse) == 3 and "gone: no current metrics" in worse[0], worse
    assert len(compare(base, {"m": {"rsd": 11.1, "manifold": True}}, subset=True)[0]) == 1
    up = update(json.loads(json.dumps(base)), {"m": {"rsd": 5.0, "manifold": True, "other": 1}}, "test")
    assert up["meshes"]["m"] == {"manifold": True, "rsd": 5.0}, up
    print("regression self-test: worse beyond tolerance fails, better and within tolerance pass: ok")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("current", nargs="?")
    ap.add_argument("--baseline", default=BASELINE)
    ap.add_argument("--update", action="store_true")
    ap.add_argument("--note", default="scripts/update_regression.sh")
    ap.add_argument("--subset", action="store_true", help="check only the meshes present in CURRENT.json")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    if args.self_test:
        self_test()
        return 0
    if not args.current:
        ap.error("CURRENT.json is required")
    with open(args.baseline) as f:
        baseline = json.load(f)
    with open(args.current) as f:
        current = json.load(f)
    if args.update:
        update(baseline, current, args.note)
        tmp = args.baseline + ".tmp"
        with open(tmp, "w") as f:
            json.dump(baseline, f, indent=1, sort_keys=False)
            f.write("\n")
        os.replace(tmp, args.baseline)
        print(f"regression: baseline {args.baseline} updated for {len(current)} meshes")
        return 0
    worse, better = compare(baseline, current, args.subset)
    for line in better:
        print("better: " + line)
    for line in worse:
        print("WORSE:  " + line)
    checked = sum(len(v) for m, v in baseline["meshes"].items() if not args.subset or m in current)
    print(f"regression: {checked} baseline values, {len(worse)} worse, {len(better)} better")
    if worse:
        print(HINT)
        return 1
    if better:
        print("Quality improved: tighten the baseline with `bash scripts/update_regression.sh` when convenient.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
