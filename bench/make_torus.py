#!/usr/bin/env python3
"""Writes a bumpy torus with about FACES triangles (2·n·m, n = 2m) as OBJ: curvature varies everywhere, so the
field, the cut graph (genus 1) and the branch points are those of a real surface, not of a flat grid.
Usage: bench/make_torus.py OUT.obj FACES"""
import math
import sys


def main():
    if len(sys.argv) != 3 or not sys.argv[2].isdigit() or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    path, faces = sys.argv[1], int(sys.argv[2])
    m = max(4, int(round(math.sqrt(faces / 4))))
    n = 2 * m
    R, r = 2.0, 0.7
    out = []
    for i in range(n):
        u = 2 * math.pi * i / n
        for j in range(m):
            v = 2 * math.pi * j / m
            rr = r * (1 + 0.08 * math.sin(5 * u) * math.cos(3 * v))
            out.append("v %.9g %.9g %.9g\n" % ((R + rr * math.cos(v)) * math.cos(u),
                                              (R + rr * math.cos(v)) * math.sin(u), rr * math.sin(v)))

    def vid(i, j):
        return (i % n) * m + (j % m) + 1

    for i in range(n):
        for j in range(m):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            out.append("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d))
    with open(path, "w") as f:
        f.writelines(out)


if __name__ == "__main__":
    main()
