#!/usr/bin/env python3
"""Writes generated "hard case" triangle meshes (OBJ) into OUTDIR and checks each one: edge- and vertex-manifold,
consistently oriented, no degenerate triangle, 500-20000 triangles, the intended topology. Prints one line per mesh
(V, F, boundary loops, genus, components, orientation, smallest angle); exits 1 when a check fails.
Deterministic (fixed seeds). Usage: python3 bench/hard_cases.py OUTDIR"""
import os
import sys

import numpy as np

# ---------------------------------------------------------------- building blocks


def weld(V, F, digits=9):
    """Merges vertices at the same position (rounded to `digits`), drops unused ones."""
    keys, inv = np.unique(np.round(np.asarray(V, float), digits), axis=0, return_inverse=True)
    F = inv.reshape(-1)[np.asarray(F)]
    used, F = np.unique(F, return_inverse=True)
    return keys[used], F.reshape(-1, 3)


def merge(parts):
    """Concatenates (V, F) parts and welds them into one mesh."""
    Vs, Fs, off = [], [], 0
    for V, F in parts:
        Vs.append(np.asarray(V, float))
        Fs.append(np.asarray(F, int).reshape(-1, 3) + off)
        off += len(V)
    return weld(np.concatenate(Vs), np.concatenate(Fs))


def normals(V, F):
    return np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])


def orient(V, F, outward):
    """Flips each triangle whose normal points against outward(centroids) (a folded triangle then shows up as an
    orientation error in the self-check)."""
    F = np.array(F, int).reshape(-1, 3)
    bad = np.einsum("ij,ij->i", normals(V, F), outward(V[F].mean(axis=1))) < 0
    F[bad] = F[bad][:, ::-1]
    return V, F


def zip_rings(a, ta, b, tb):
    """Triangle strip between closed rings a and b (vertex ids, angles increasing from about 0); a ring b of one
    vertex gives a fan. Advances on the ring whose next vertex comes first in angle."""
    n, m = len(a), len(b)
    ta, tb = list(ta) + [ta[0] + 2 * np.pi], list(tb) + [tb[0] + 2 * np.pi]
    tris, i, j = [], 0, 0
    while i < n or (j < m and m > 1):
        if i < n and (j == m or m == 1 or ta[i + 1] <= tb[j + 1]):
            tris.append((a[i], a[(i + 1) % n], b[j % m]))
            i += 1
        else:
            tris.append((a[i % n], b[(j + 1) % m], b[j]))
            j += 1
    return tris


def rect_patch(origin, eu, ev, nu, nv, normal, holes=()):
    """Planar grid of nu x nv cells at origin + i eu + j ev (eu orthogonal to ev), two triangles per cell, facing
    `normal`. Each hole (ic, jc, k, radius, nseg) replaces the 2k x 2k cells around grid point (ic, jc) by a strip
    from their square of 8k grid points to a circle of nseg points."""
    o, eu, ev = (np.asarray(x, float) for x in (origin, eu, ev))
    pts, ids, tris = [], {}, []

    def vid(i, j):
        if (i, j) not in ids:
            ids[i, j] = len(pts)
            pts.append(o + i * eu + j * ev)
        return ids[i, j]

    def in_hole(i, j):
        return any(abs(i + 0.5 - h[0]) < h[2] and abs(j + 0.5 - h[1]) < h[2] for h in holes)

    for i in range(nu):
        for j in range(nv):
            if not in_hole(i, j):
                a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
                tris += [(a, b, c), (a, c, d)]
    lu, lv = np.linalg.norm(eu), np.linalg.norm(ev)
    for ic, jc, k, radius, nseg in holes:
        sq = square_ring(k)
        ring = [vid(ic + di, jc + dj) for di, dj in sq]
        t_sq = [np.arctan2(dj * lv, di * lu) % (2 * np.pi) for di, dj in sq]
        t = 2 * np.pi * np.arange(nseg) / nseg
        circle = list(range(len(pts), len(pts) + nseg))
        center = o + ic * eu + jc * ev
        pts += [center + radius * np.cos(s) * eu / lu + radius * np.sin(s) * ev / lv for s in t]
        tris += zip_rings(ring, t_sq, circle, t)
    V = np.array(pts)
    return orient(V, tris, lambda c: np.broadcast_to(np.asarray(normal, float), c.shape))


def square_ring(k):
    """Offsets of the 8k grid points on the square of half-width k, counter-clockwise from (k, 0)."""
    side = [(k, j) for j in range(0, k)] + [(i, k) for i in range(k, -k, -1)]
    side += [(-k, j) for j in range(k, -k, -1)] + [(i, -k) for i in range(-k, k)]
    return side + [(k, j) for j in range(-k, 0)]


def circle_ring(pts, radius, count, z):
    """Appends a ring of `count` points at height z to pts; returns (ids, angles)."""
    t = 2 * np.pi * np.arange(count) / count
    ids = list(range(len(pts), len(pts) + count))
    pts.extend(np.stack([radius * np.cos(t), radius * np.sin(t), np.full(count, z)], -1))
    return ids, t


def torus(R, r, n, m):
    """n x m grid torus around the z axis, outward normals."""
    u, v = np.meshgrid(2 * np.pi * np.arange(n) / n, 2 * np.pi * np.arange(m) / m, indexing="ij")
    V = np.stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], -1)
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    a, b = i * m + j, (i + 1) % n * m + j
    c, d = (i + 1) % n * m + (j + 1) % m, i * m + (j + 1) % m
    F = np.concatenate([np.stack([a, b, c], -1), np.stack([a, c, d], -1)]).reshape(-1, 3)
    return V.reshape(-1, 3), F


def icosphere(levels):
    """Unit icosphere: icosahedron (faces = vertex triples at edge length 2) split `levels` times, outward."""
    p = (1 + 5 ** 0.5) / 2
    V = [(s1, s2 * p, 0) for s1 in (-1, 1) for s2 in (-1, 1)]
    V = np.array([w for x in V for w in (x, x[2:] + x[:2], x[1:] + x[:1])], float)
    D = np.linalg.norm(V[:, None] - V[None], axis=2)
    F = [(a, b, c) for a in range(12) for b in range(a + 1, 12) for c in range(b + 1, 12)
         if abs(D[a, b] - 2) < 1e-9 and abs(D[b, c] - 2) < 1e-9 and abs(D[a, c] - 2) < 1e-9]
    V, F = orient(V / np.linalg.norm(V, axis=1)[:, None], F, lambda c: c)
    V = list(V)
    for _ in range(levels):
        mid = {}

        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                mid[key] = len(V)
                V.append((V[a] + V[b]) / np.linalg.norm(V[a] + V[b]))
            return mid[key]

        F = np.array([t for a, b, c in F for t in
                      ((a, m(a, b), m(c, a)), (m(a, b), b, m(b, c)), (m(c, a), m(b, c), c),
                       (m(a, b), m(b, c), m(c, a)))])
    return np.array(V), F


# ---------------------------------------------------------------- the cases: (V, F) each


def box_patches(size, counts):
    """The six grid faces of an axis-aligned box [0, size], counts[a] cells along axis a."""
    E = np.eye(3)
    parts = []
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        for s in (0, 1):
            eu, ev = E[b] * size[b] / counts[b], E[c] * size[c] / counts[c]
            parts.append(rect_patch(E[a] * s * size[a], eu, ev, counts[b], counts[c], E[a] * (2 * s - 1)))
    return parts


def thin_box():
    # Hard: 8 box corners (cones), each one cell across the 0.08-thin side from the next.
    return merge(box_patches((1.0, 1.0, 0.08), (11, 11, 1)))


def coarse_close_cones():
    # Hard: 6 narrow bumps in pairs 0.35 rad apart on a coarse sphere: cones a few triangles apart.
    V, F = icosphere(3)
    centers = np.array([(1, 0, 0), (0, 1, 0), (0, 0, 1)], float)
    sides = np.array([(0, 0, 1), (1, 0, 0), (0, 1, 0)], float)
    bumps = [np.cos(s * 0.175) * c + np.sin(s * 0.175) * t for c, t in zip(centers, sides) for s in (-1, 1)]
    angle = np.arccos(np.clip(V @ np.array(bumps).T, -1, 1))
    return V * (1 + 0.3 * np.exp(-0.5 * (angle / 0.15) ** 2).sum(axis=1))[:, None], F


def slivers_cylinder():
    # Hard: 256 x 3 side triangles of aspect ~40, caps of concentric rings, 90-degree creases at the rims.
    H, pts, tris = 3.0, [], []
    side = [circle_ring(pts, 1.0, 256, z) for z in np.linspace(0, H, 4)]
    rings = list(zip(side, side[1:]))
    for z in (0.0, H):
        cap = [circle_ring(pts, r, n, z) for r, n in ((1.0, 256), (0.75, 64), (0.5, 16), (0.25, 8), (0.0, 1))]
        rings += list(zip(cap, cap[1:]))
    for (a, ta), (b, tb) in rings:
        tris += zip_rings(a, ta, b, tb)
    V, F = weld(np.array(pts), tris)
    return orient(V, F, lambda c: c - (0, 0, H / 2))


def thin_handle():
    # Hard: a handle of radius 0.04 (12 triangles around) on a ring of radius 1: the density must resolve it.
    return torus(1.0, 0.04, 400, 12)


def pinched_handle():
    # Hard: a ring of tube radius 0.3 pinched to 0.03 over a quarter of its length (a thin handle on a thick body,
    # 24 triangles around): the default h, set by the thick part, is longer than a third of the thin part's girth.
    n, m = 200, 24
    u, v = np.meshgrid(2 * np.pi * np.arange(n) / n, 2 * np.pi * np.arange(m) / m, indexing="ij")
    t = np.clip((np.minimum(u, 2 * np.pi - u) - 0.4) / 0.4, 0, 1)
    r = 0.03 + 0.27 * t * t * (3 - 2 * t)
    V = np.stack([(1 + r * np.cos(v)) * np.cos(u), (1 + r * np.cos(v)) * np.sin(u), r * np.sin(v)], -1)
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    a, b = i * m + j, (i + 1) % n * m + j
    c, d = (i + 1) % n * m + (j + 1) % m, i * m + (j + 1) % m
    F = np.concatenate([np.stack([a, b, c], -1), np.stack([a, c, d], -1)]).reshape(-1, 3)
    return V.reshape(-1, 3), F


def fan_disk():
    # Hard: a flat disk fanned around its one interior vertex (600 triangles, a planar CAD face): the index +1 has no
    # other interior vertex to be split over.
    n = 600
    t = 2 * np.pi * np.arange(n) / n
    V = np.concatenate([[[0.0, 0.0, 0.0]], np.stack([np.cos(t), np.sin(t), np.zeros(n)], -1)])
    F = np.array([(0, 1 + k, 1 + (k + 1) % n) for k in range(n)])
    return V, F


def plate_tiny_holes():
    # Hard: 12 tiny octagonal holes (radius 0.03) in an open 2 x 2 plate: 13 boundaries to align to.
    n, h, rng, centers = 40, 0.05, np.random.default_rng(3), []
    while len(centers) < 12:
        c = tuple(rng.integers(3, n - 2, size=2))
        if all(max(abs(c[0] - d[0]), abs(c[1] - d[1])) >= 4 for d in centers):
            centers.append(c)
    holes = [(i, j, 1, 0.03, 8) for i, j in centers]
    V, F = rect_patch((-1, -1, 0), (h, 0, 0), (0, h, 0), n, n, (0, 0, 1), holes)
    return weld(V, F)


def jagged_disk():
    # Hard: a saddle disk whose boundary radius 1 + 0.15 sin(17 t) zigzags every 7 boundary edges.
    k, pts, tris = 18, [], []
    # rings of 6i points inside, then 119 points on every ray of the outer band, which alone gets the teeth
    rings = [circle_ring(pts, i / k, 1 if i == 0 else 6 * i if i <= 12 else 119, 0.0) for i in range(k + 1)]
    for (a, ta), (b, tb) in zip(rings[:0:-1], rings[-2::-1]):
        tris += zip_rings(a, ta, b, tb)
    P = np.array(pts)
    rho, t = np.linalg.norm(P[:, :2], axis=1), np.arctan2(P[:, 1], P[:, 0])
    w = np.clip((rho - 13 / k) / (5 / k), 0, 1)  # linear, so that rho * (1 + 0.15 w sin) grows with rho
    P[:, :2] *= (1 + 0.15 * w * np.sin(17 * t))[:, None]
    P[:, 2] = 0.1 * (P[:, 0] ** 2 - P[:, 1] ** 2)
    return orient(P, tris, lambda c: np.broadcast_to((0.0, 0.0, 1.0), c.shape))


def noisy_sphere():
    # Hard: curvature noise: every vertex moved radially by up to 3 % (seed 7).
    V, F = icosphere(4)
    return V * np.random.default_rng(7).uniform(0.97, 1.03, len(V))[:, None], F


def sphere_tiny_holes():
    # Hard: a scan's holes: 8 single triangles, two rings apart or more, removed from an icosphere (holes of 3 edges,
    # about 0.6 default quad edges around each).
    V, F = icosphere(4)
    rng, removed, near = np.random.default_rng(11), [], set()
    for f in rng.permutation(len(F)):
        if len(removed) == 8:
            break
        if not set(F[f]) & near:
            removed.append(f)
            ring = {v for t in F if set(t) & set(F[f]) for v in t}
            near |= {v for t in F if set(t) & ring for v in t}
    return V, np.delete(F, removed, axis=0)


def sharp_bracket():
    # Hard: CAD block: L profile extruded, a drilled hole (radius 0.15) through one leg, 90-degree creases.
    h = 1 / 16  # grid step; the L: x in [0, 2] x y in [0, 0.5] plus x in [0, 0.5] x y in [0.5, 2], z in [0, 1]
    x, y, z = np.eye(3) * h
    drill = (1.375, 0.5)  # (x, z) of the hole's axis: grid point (22, 8) on y = 0 and (14, 8) on y = 0.5
    parts = [rect_patch((0, 0, s), x, y, 32, 8, (0, 0, 2 * s - 1)) for s in (0, 1)]
    parts += [rect_patch((0, 0.5, s), x, y, 8, 24, (0, 0, 2 * s - 1)) for s in (0, 1)]
    parts += [rect_patch((0, 0, 0), x, z, 32, 16, (0, -1, 0), [(22, 8, 3, 0.15, 24)]),
              rect_patch((2, 0, 0), y, z, 8, 16, (1, 0, 0)),
              rect_patch((0.5, 0.5, 0), x, z, 24, 16, (0, 1, 0), [(14, 8, 3, 0.15, 24)]),
              rect_patch((0.5, 0.5, 0), y, z, 24, 16, (1, 0, 0)),
              rect_patch((0, 2, 0), x, z, 8, 16, (0, 1, 0)),
              rect_patch((0, 0, 0), y, z, 32, 16, (-1, 0, 0))]
    # the drilled cylinder along y through (x, z) = (1.375, 0.5); its normals point to the axis
    pts, tris = [], []
    rings = [circle_ring(pts, 0.15, 24, s) for s in np.linspace(0, 0.5, 9)]
    for (a, ta), (b, tb) in zip(rings, rings[1:]):
        tris += zip_rings(a, ta, b, tb)
    axis = np.array([drill[0], 0, drill[1]])
    P = np.array(pts)[:, [0, 2, 1]] + axis
    parts.append(orient(P, tris, lambda c: axis - c * (1, 0, 1)))
    return merge(parts)


def inverted_torus():
    # Hard: every face oriented inward (a consistently but wrongly oriented closed surface).
    V, F = torus(1.0, 0.35, 120, 40)
    return V, F[:, ::-1]


def needle_triangles():
    # Hard: UV sphere 64 x 32: pole fans of 5.6-degree needles and thin slivers in the rings next to them.
    pts, tris = [], []
    rings = [circle_ring(pts, np.sin(t), 1 if i in (0, 32) else 64, np.cos(t))
             for i, t in enumerate(np.linspace(0, np.pi, 33))]
    for a, b in zip(rings, rings[1:]):
        a, b = (b, a) if len(a[0]) == 1 else (a, b)
        tris += zip_rings(a[0], a[1], b[0], b[1])
    V, F = weld(np.array(pts), tris)
    return orient(V, F, lambda c: c)


def gear():
    # Hard: a coarse CAD export of a spur gear with 16 teeth: a prism over an outline of 8 vertices a tooth, caps fanned
    # around their centres. Both outlines and the tooth corners are 90° creases on chains of at most 3 edges (too
    # short for feature curves; followed as crisp creases between corners).
    n, pts = 128, []
    for z in (0.3, 0.0):
        for k in range(n):
            r = 1.0 if 2 <= k % 8 < 6 else 0.8
            pts.append((r * np.cos(2 * np.pi * k / n), r * np.sin(2 * np.pi * k / n), z))
    pts += [(0.0, 0.0, 0.3), (0.0, 0.0, 0.0)]
    tris = []
    for k in range(n):
        t, t1, b, b1 = k, (k + 1) % n, n + k, n + (k + 1) % n
        tris += [(2 * n, t, t1), (2 * n + 1, b1, b), (b, b1, t1), (b, t1, t)]
    return np.array(pts), np.array(tris)


def sharp_tetrahedron():
    # Hard: a tall tetrahedron whose side faces meet at 30-degree apex angles (a +3/4 cone of the field at the
    # apex: one quad corner) and whose base corners carry half cones; 40 x 40 subdivided faces.
    half = np.radians(15.0)
    slant = 0.5 / np.tan(half)
    height = np.sqrt(slant**2 - 1 / 12)
    B = np.array([[0, 0, 0], [1, 0, 0], [0.5, np.sqrt(3) / 2, 0]])
    apex = np.array([0.5, np.sqrt(3) / 6, height])
    n, pts, tris = 40, [], []
    for P, Q, R in ((B[0], B[2], B[1]), (B[0], B[1], apex), (B[1], B[2], apex), (B[2], B[0], apex)):
        ids = {}
        for i in range(n + 1):
            for j in range(n + 1 - i):
                ids[i, j] = len(pts)
                pts.append(P + (Q - P) * i / n + (R - P) * j / n)
        for i in range(n):
            for j in range(n - i):
                tris.append((ids[i, j], ids[i + 1, j], ids[i, j + 1]))
                if i + j < n - 1:
                    tris.append((ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]))
    V, F = weld(np.array(pts), tris)
    return orient(V, F, lambda c: c - V.mean(axis=0))


def voxel_surface(solid, cells):
    """Boundary of a set of unit voxels (bool array, padded with empty ones) as triangles, each voxel face split into
    cells x cells squares of two triangles (diagonals alternating), facing out of the solid."""
    pts, tris = [], []
    grid = np.stack(np.meshgrid(np.arange(cells + 1), np.arange(cells + 1), indexing="ij"), -1).reshape(-1, 2) / cells
    quads = [(i * (cells + 1) + j, (i + 1) * (cells + 1) + j, (i + 1) * (cells + 1) + j + 1, i * (cells + 1) + j + 1)
             for i in range(cells) for j in range(cells)]
    for axis in range(3):
        a1, a2 = [a for a in range(3) if a != axis]
        for side in (-1, 1):
            step = np.zeros(3, int)
            step[axis] = side
            faces = np.argwhere(solid & ~np.roll(solid, -side, axis=axis))
            for voxel in faces:
                base = voxel.astype(float) + (step > 0) * np.eye(3)[axis]
                e1, e2 = np.eye(3)[a1], np.eye(3)[a2]
                if np.dot(np.cross(e1, e2), step) < 0:
                    e1, e2 = e2, e1
                off = len(pts)
                pts.extend(base + g[0] * e1 + g[1] * e2 for g in grid)
                for k, quad in enumerate(quads):
                    p, q, r, t = (off + v for v in quad)
                    tris += [(p, q, r), (p, r, t)] if (k // cells + k % cells) % 2 else [(p, q, t), (q, r, t)]
    return weld(np.array(pts), tris)


def lattice_plate(holes, cells, smoothing, tiny_holes, seed=5):
    """A scan-like plate with holes x holes square through-holes (genus holes²): a voxel plate 2 thick, holes 3 wide
    between bars 2 wide, faces split cells x cells, Taubin-smoothed `smoothing` times (rounded, no sharp edges when
    > 0), and `tiny_holes` scan holes (one triangle or the fan of a vertex removed, two rings apart or more)."""
    width = holes * 5 + 2
    solid = np.zeros((width + 2, width + 2, 4), bool)
    solid[1:width + 1, 1:width + 1, 1:3] = True
    for i in range(holes):
        for j in range(holes):
            solid[3 + 5 * i:6 + 5 * i, 3 + 5 * j:6 + 5 * j, 1:3] = False
    V, F = voxel_surface(solid, cells)
    neighbours = [set() for _ in V]
    for a, b, c in F.tolist():
        neighbours[a] |= {b, c}
        neighbours[b] |= {a, c}
        neighbours[c] |= {a, b}
    rows = np.repeat(np.arange(len(V)), [len(n) for n in neighbours])
    cols = np.concatenate([sorted(n) for n in neighbours])
    degree = np.array([len(n) for n in neighbours], float)
    for _ in range(smoothing):
        for lam in (0.5, -0.53):
            mean = np.zeros_like(V)
            np.add.at(mean, rows, V[cols])
            V = V + lam * (mean / degree[:, None] - V)
    rng, removed, near = np.random.default_rng(seed), [], np.zeros(len(V), bool)
    vertex_faces = [[] for _ in V]
    for f, t in enumerate(F.tolist()):
        for v in t:
            vertex_faces[v].append(f)
    for f in rng.permutation(len(F)):
        if len(removed) == tiny_holes:
            break
        ring = {v for g in (h for u in F[f] for h in vertex_faces[u]) for v in F[g]}
        ring2 = {v for u in ring for g in vertex_faces[u] for v in F[g]}
        if near[list(ring2)].any():
            continue
        removed.append(vertex_faces[F[f][0]] if len(removed) % 3 == 2 else [f])
        near[list(ring2)] = True
    gone = np.zeros(len(F), bool)
    for group in removed:
        gone[group] = True
    return weld(V, F[~gone])


def lattice_scan():
    # Hard: a scan of a perforated plate: genus 9 (3 x 3 through-holes, bars 2/3 of the holes' width), rounded, with
    # 6 tiny scan holes (a triangle or a vertex's fan): handles, holes far below the default quad size, no creases.
    return lattice_plate(3, 3, 8, 6)


def bolted_plate(cell=0.25, nseg=16, levels=1):
    # Hard: a CAD plate 4 x 3 x 0.25 with 11 drilled bolt holes (genus 11) of radius 0.3-0.46 cells, triangulated as
    # CAD exports are (strips from a ring of grid points to each hole's n-gon, walls of `levels` rows): small holes
    # with 90-degree rims, slivers.
    nu, nv, thickness = int(round(4 / cell)), int(round(3 / cell)), 0.25
    x, y, z = np.array([cell, 0, 0]), np.array([0, cell, 0]), np.array([0, 0, thickness / levels])
    holes = [(round((i + 0.5) * nu / 4), round((j + 0.5) * nv / 3), 1, (0.3 + 0.08 * ((i + j) % 3)) * cell, nseg)
             for i in range(4) for j in range(3) if (i, j) != (3, 2)]
    parts = [rect_patch((0, 0, s), x, y, nu, nv, (0, 0, 1 if s else -1), holes) for s in (0, thickness)]
    parts += [rect_patch((0, 0, 0), x, z, nu, levels, (0, -1, 0)), rect_patch((0, 3, 0), x, z, nu, levels, (0, 1, 0)),
              rect_patch((0, 0, 0), y, z, nv, levels, (-1, 0, 0)), rect_patch((4, 0, 0), y, z, nv, levels, (1, 0, 0))]
    for ic, jc, _, radius, n in holes:
        pts, tris = [], []
        rings = [circle_ring(pts, radius, n, s) for s in np.linspace(0, thickness, levels + 1)]
        for (a, ta), (b, tb) in zip(rings, rings[1:]):
            tris += zip_rings(a, ta, b, tb)
        centre = np.array([ic * cell, jc * cell, 0])
        parts.append(orient(np.array(pts) + centre, tris, lambda c, centre=centre: (centre - c) * (1, 1, 0)))
    return merge(parts)


def bolted_plate_fine():
    # Hard: the same plate on a grid twice as fine, holes of 24 sides in two rows: the smallest holes are about 2.4
    # default quad edges around (a handle thinner than a quad).
    return bolted_plate(0.125, 24, 2)


# name -> (generator, expected (boundary loops, genus, components), expected orientation of a closed surface)
CASES = {
    "thin_box": (thin_box, (0, 0, 1), "outward"),
    "coarse_close_cones": (coarse_close_cones, (0, 0, 1), "outward"),
    "slivers_cylinder": (slivers_cylinder, (0, 0, 1), "outward"),
    "thin_handle": (thin_handle, (0, 1, 1), "outward"),
    "pinched_handle": (pinched_handle, (0, 1, 1), "outward"),
    "fan_disk": (fan_disk, (1, 0, 1), "open"),
    "plate_tiny_holes": (plate_tiny_holes, (13, 0, 1), "open"),
    "jagged_disk": (jagged_disk, (1, 0, 1), "open"),
    "noisy_sphere": (noisy_sphere, (0, 0, 1), "outward"),
    "sphere_tiny_holes": (sphere_tiny_holes, (8, 0, 1), "open"),
    "sharp_bracket": (sharp_bracket, (0, 1, 1), "outward"),
    "inverted_torus": (inverted_torus, (0, 1, 1), "inward"),
    "needle_triangles": (needle_triangles, (0, 0, 1), "outward"),
    "sharp_tetrahedron": (sharp_tetrahedron, (0, 0, 1), "outward"),
    "gear": (gear, (0, 0, 1), "outward"),
    "lattice_scan": (lattice_scan, (6, 9, 1), "open"),
    "bolted_plate": (bolted_plate, (0, 11, 1), "outward"),
    "bolted_plate_fine": (bolted_plate_fine, (0, 11, 1), "outward"),
}

# ---------------------------------------------------------------- self-check


class UnionFind:
    """Disjoint sets of any hashable items (also bench/check_outputs.py's)."""

    def __init__(self):
        self.parent = {}

    def find(self, a):
        self.parent.setdefault(a, a)
        while self.parent[a] != a:
            self.parent[a] = self.parent[self.parent[a]]
            a = self.parent[a]
        return a

    def union(self, a, b):
        self.parent[self.find(a)] = self.find(b)


def check(V, F):
    """Topology and validity of a triangle mesh: (dict of numbers, list of problems)."""
    problems, directed, count = [], set(), {}
    for f in F.tolist():
        for a, b in zip(f, f[1:] + f[:1]):
            if (a, b) in directed:
                problems.append("inconsistent orientation at edge %d-%d" % (a, b))
            directed.add((a, b))
            count[min(a, b), max(a, b)] = count.get((min(a, b), max(a, b)), 0) + 1
    problems += ["edge %d-%d in %d faces" % (e + (c,)) for e, c in count.items() if c > 2]
    problems += ["vertex %d pinched (%d fans)" % vf for vf in pinched_vertices(F)]
    if len(np.unique(F)) != len(V):
        problems.append("%d unused vertices" % (len(V) - len(np.unique(F))))
    area = np.linalg.norm(normals(V, F), axis=1) / 2
    if (area <= 1e-12 * area.mean()).any():
        problems.append("%d degenerate triangles" % (area <= 1e-12 * area.mean()).sum())
    if not 500 <= len(F) <= 20000:
        problems.append("%d triangles, not 500-20000" % len(F))
    uf = UnionFind()
    for a, b in count:
        uf.union(a, b)
    comps = {uf.find(v) for v in range(len(V))}
    bedges = [e for e, c in count.items() if c == 1]
    # boundary loops = cycle rank of the boundary edge graph (exact for disjoint loops, also counts touching ones)
    buf = UnionFind()
    for a, b in bedges:
        buf.union(a, b)
    bverts = {v for e in bedges for v in e}
    loops = len(bedges) - len(bverts) + len({buf.find(v) for v in bverts})
    chi = len(V) - len(count) + len(F)
    genus = (2 * len(comps) - chi - loops) / 2
    volume = np.einsum("ij,ij->i", V[F[:, 0]], np.cross(V[F[:, 1]], V[F[:, 2]])).sum() / 6
    side = "open" if loops else ("outward" if volume > 0 else "inward")
    return dict(V=len(V), F=len(F), loops=loops, genus=genus, comps=len(comps), side=side,
                min_angle=min_angle(V, F)), problems


def pinched_vertices(F):
    """(vertex, number of fans) for each vertex whose incident triangles form more than one edge-connected fan."""
    links = {}
    for a, b, c in F.tolist():
        for v, w1, w2 in ((a, b, c), (b, c, a), (c, a, b)):
            links.setdefault(v, []).append((w1, w2))
    out = []
    for v, link in links.items():
        ws = sorted({w for e in link for w in e})
        index = {w: i for i, w in enumerate(ws)}
        uf = UnionFind()
        for w1, w2 in link:
            uf.union(index[w1], index[w2])
        fans = len({uf.find(i) for i in range(len(ws))})
        if fans > 1:
            out.append((v, fans))
    return out


def min_angle(V, F):
    """Smallest corner angle in degrees."""
    P = V[F]
    worst = 180.0
    for k in range(3):
        u, w = P[:, (k + 1) % 3] - P[:, k], P[:, (k + 2) % 3] - P[:, k]
        cos = np.einsum("ij,ij->i", u, w) / (np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1))
        worst = min(worst, np.degrees(np.arccos(np.clip(cos, -1, 1))).min())
    return worst


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines("v %.12g %.12g %.12g\n" % tuple(p) for p in V)
        f.writelines("f %d %d %d\n" % tuple(t + 1) for t in F)


def main():
    if len(sys.argv) != 2 or any(a.startswith("-") for a in sys.argv[1:]):  # --help, or an option: the usage
        sys.exit(__doc__)
    outdir = sys.argv[1]
    os.makedirs(outdir, exist_ok=True)
    failed = False
    print("%-24s %6s %6s %6s %6s %6s %8s %9s" % ("mesh", "V", "F", "loops", "genus", "comps", "side", "min_angle"))
    for name, (make, topology, side) in CASES.items():
        V, F = make()
        V, F = np.asarray(V, float), np.asarray(F, int)
        info, problems = check(V, F)
        if (info["loops"], info["genus"], info["comps"]) != topology:
            problems.append("topology (loops, genus, components) %s, expected %s"
                            % ((info["loops"], info["genus"], info["comps"]), topology))
        if info["side"] != side:
            problems.append("orientation %s, expected %s" % (info["side"], side))
        write_obj(os.path.join(outdir, name + ".obj"), V, F)
        print("%-24s %6d %6d %6d %6g %6d %8s %9.2f" % (name + ".obj", info["V"], info["F"], info["loops"],
                                                       info["genus"], info["comps"], info["side"], info["min_angle"]))
        for p in problems[:10]:
            print("  PROBLEM: " + p)
        failed |= bool(problems)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
