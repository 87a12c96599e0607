#!/usr/bin/env python3
"""Independent check of the OBJ files bench/hard_cases.sh wrote (never its JSON reports): for each case NAME of
RUNS.tsv (lines: name, param exit, param seconds, param stderr lines, remesh exit, remesh seconds, remesh stderr
lines) it reads DIR/NAME.obj, DIR/NAME.param.obj and DIR/NAME.quads.obj and prints one Markdown table row:
flipped/collapsed triangles of the map, faces/non-quads/topology of the quad mesh against the input's.
Usage: bench/check_outputs.py DIR RUNS.tsv"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hard_cases import UnionFind  # noqa: E402 (the generator's, one implementation)

TAU = 1e-8  # relative area below which a triangle of the map counts as collapsed


def read_obj(path):
    """(positions, texture coordinates, faces as lists of (v, vt or None), 0-based)."""
    V, VT, faces = [], [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                V.append([float(x) for x in w[1:4]])
            elif w[0] == "vt":
                VT.append([float(x) for x in w[1:3]])
            elif w[0] == "f":
                faces.append([corner(c, len(V), len(VT)) for c in w[1:]])
    return np.array(V, float).reshape(-1, 3), np.array(VT, float).reshape(-1, 2), faces


def corner(text, nv, nvt):
    """'v', 'v/vt', 'v//vn' or 'v/vt/vn' -> (v, vt or None), 0-based (negative = relative)."""
    parts = text.split("/")
    v = int(parts[0])
    vt = int(parts[1]) if len(parts) > 1 and parts[1] else None
    return (v - 1 if v > 0 else nv + v), (None if vt is None else vt - 1 if vt > 0 else nvt + vt)


def map_validity(path):
    """(triangles, flipped, collapsed) of a parameterized OBJ; polygons are fanned into triangles."""
    V, VT, faces = read_obj(path)
    tris = np.array([(f[0], f[i], f[i + 1]) for f in faces for i in range(1, len(f) - 1)], dtype=object)
    if len(tris) == 0 or any(c[1] is None for t in tris for c in t):
        raise ValueError("no triangles with vt corners")
    v = np.array([[c[0] for c in t] for t in tris])
    t = np.array([[c[1] for c in t] for t in tris])
    P, U = V[v], VT[t]
    e1, e2 = U[:, 1] - U[:, 0], U[:, 2] - U[:, 0]
    a_uv = 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    a_3d = 0.5 * np.linalg.norm(np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), axis=1)
    a_ref = a_3d * (a_uv.sum() / a_3d.sum())
    return len(tris), int((a_uv < -TAU * a_ref).sum()), int((np.abs(a_uv) <= TAU * a_ref).sum())


def topology(path):
    """Counts and topology of a polygon mesh OBJ, from the faces' vertex indices only (orientable assumed)."""
    _, _, faces = read_obj(path)
    faces = [[c[0] for c in f] for f in faces]
    uses, comp = {}, UnionFind()
    for f in faces:
        for a, b in zip(f, f[1:] + f[:1]):
            uses[min(a, b), max(a, b)] = uses.get((min(a, b), max(a, b)), 0) + 1
            comp.union(a, b)
    verts = {v for f in faces for v in f}
    per = {r: [0, 0, 0, 0] for r in {comp.find(v) for v in verts}}  # V, E, F, boundary loops
    for v in verts:
        per[comp.find(v)][0] += 1
    for a, b in uses:
        per[comp.find(a)][1] += 1
    for f in faces:
        per[comp.find(f[0])][2] += 1
    # boundary loops of a component = cycle rank of its edges used once (E - V + connected parts)
    border, bverts = UnionFind(), {}
    bedges = [e for e, n in uses.items() if n == 1]
    for a, b in bedges:
        border.union(a, b)
        per[comp.find(a)][3] += 1
        bverts[a] = bverts[b] = True
    for v in bverts:
        per[comp.find(v)][3] -= 1
    for r in {border.find(v) for v in bverts}:
        per[comp.find(r)][3] += 1
    chi = sum(nv - ne + nf for nv, ne, nf, _ in per.values())
    loops = sum(p[3] for p in per.values())
    genus = sum((2 - (nv - ne + nf) - nb) / 2 for nv, ne, nf, nb in per.values())
    return dict(faces=len(faces), non_quads=sum(len(f) != 4 for f in faces), comps=len(per), loops=loops,
                chi=chi, genus=genus, manifold_edges=max(uses.values(), default=0) <= 2)


def fmt(x):
    return "%g" % x if isinstance(x, float) else str(x)


def row(d, name, run):
    """One table row; a missing or unreadable output gives '-' cells and a note."""
    p_rc, p_s, p_err, r_rc, r_s, r_err = run
    notes = []
    ref = topology(os.path.join(d, name + ".obj"))
    try:
        tris, flipped, collapsed = map_validity(os.path.join(d, name + ".param.obj"))
    except (OSError, ValueError) as e:
        tris = flipped = collapsed = "-"
        notes.append("param OBJ: %s" % (e.strerror if isinstance(e, OSError) else e))
    try:
        q = topology(os.path.join(d, name + ".quads.obj"))
        same = all(q[k] == ref[k] for k in ("comps", "genus", "loops"))
        quads = [q["faces"], q["non_quads"], q["comps"], q["loops"], q["chi"], fmt(q["genus"]),
                 "yes" if q["manifold_edges"] else "no", "yes" if same else "no"]
    except (OSError, ValueError) as e:
        quads = ["-"] * 8
        notes.append("quads OBJ: %s" % (e.strerror if isinstance(e, OSError) else e))
    cells = [name, ref["faces"], "%d/%s/%d" % (ref["comps"], fmt(ref["genus"]), ref["loops"]),
             p_rc, p_s, p_err, tris, flipped, collapsed, r_rc, r_s, r_err] + quads
    return "| " + " | ".join(str(c) for c in cells) + " |", notes


def main():
    if len(sys.argv) != 3 or any(a.startswith("-") for a in sys.argv[1:]):  # --help, or an option: the usage
        sys.exit(__doc__)
    d, runs = sys.argv[1], sys.argv[2]
    head = ["mesh", "input F", "input c/g/b", "param exit", "param s", "param stderr", "param tris", "flipped",
            "collapsed", "remesh exit", "remesh s", "remesh stderr", "quad faces", "non-quads", "components",
            "boundary loops", "χ", "g", "manifold edges", "same topology"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    all_notes = []
    with open(runs) as f:
        for line in f:
            if line.strip():
                name, *run = line.split()
                text, notes = row(d, name, run)
                print(text)
                all_notes += ["%s: %s" % (name, n) for n in notes]
    print()
    print("input c/g/b = components/genus/boundary loops of the input; a map triangle is flipped when its signed uv "
          "area < -%g A_ref and collapsed when |area| <= %g A_ref (A_ref = its 3D area x total uv area / total 3D "
          "area); χ and g sum over the quad mesh's components; exit 124 = timeout." % (TAU, TAU))
    for n in all_notes:
        print("- " + n)


if __name__ == "__main__":
    main()
