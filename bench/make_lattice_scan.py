#!/usr/bin/env python3
"""Writes a scan-like perforated plate as OBJ (bench/hard_cases.py lattice_plate): HOLES x HOLES through-holes
(genus HOLES²), voxel faces split CELLS x CELLS, rounded by Taubin smoothing, with TINY scan holes of one triangle or
one vertex's fan. A stand-in for the scans of high genus with hundreds of small holes that issue 14 and 16 name:
bench/make_lattice_scan.py lattice.obj 7 7 250 gives 325k triangles, genus 49, 250 boundary loops.
Usage: bench/make_lattice_scan.py OUT.obj HOLES CELLS TINY"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hard_cases import check, lattice_plate, write_obj  # noqa: E402


def main():
    args = sys.argv[1:]
    if len(args) != 4 or args[0].startswith("-") or not all(a.isdigit() for a in args[1:]):
        sys.exit(__doc__)
    holes, cells, tiny = (int(a) for a in args[1:])
    V, F = lattice_plate(holes, cells, 10, tiny)
    write_obj(args[0], V, F)
    info, problems = check(V, F)
    problems = [p for p in problems if "not 500-20000" not in p]
    print("%s: %d vertices, %d triangles, %d boundary loops, genus %g" % (args[0], info["V"], info["F"], info["loops"],
                                                                         info["genus"]))
    if problems or (info["loops"], info["genus"]) != (tiny, holes * holes):
        sys.exit("not the intended surface: " + "; ".join(problems[:5]))


if __name__ == "__main__":
    main()
