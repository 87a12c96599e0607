"""Mesh preparation for the add-on, in numpy only (no bpy, testable anywhere): find what a manifold remesher
cannot take (non-manifold edges and vertices, badly oriented edges) and cut the triangle mesh into manifold parts
there and at its loose parts, each to be remeshed on its own."""
from dataclasses import dataclass, field
from typing import List

import numpy as np


@dataclass
class Part:
    """One manifold piece: its own vertex array, triangles into it, and the original index of each vertex."""

    vertices: np.ndarray
    triangles: np.ndarray
    original_vertices: np.ndarray
    area: float


@dataclass
class Preparation:
    parts: List[Part]
    nonmanifold_edges: np.ndarray  # #k×2 original vertex pairs: edges with more than two triangles
    misoriented_edges: np.ndarray  # #k×2: two triangles that traverse the edge the same way
    nonmanifold_vertices: np.ndarray  # original indices: more than one fan of triangles meets there
    degenerate_triangles: int = 0
    notes: List[str] = field(default_factory=list)

    @property
    def problem_vertices(self):
        return np.unique(np.concatenate([self.nonmanifold_edges.ravel(), self.misoriented_edges.ravel(),
                                         self.nonmanifold_vertices])).astype(np.int64)

    def summary(self):
        """'1 non-manifold edge, 2 non-manifold vertices' or '' when the mesh is clean."""
        items = [(len(self.nonmanifold_edges), "non-manifold edge"), (len(self.misoriented_edges),
                 "inconsistently oriented edge"), (len(self.nonmanifold_vertices), "non-manifold vertex"),
                 (self.degenerate_triangles, "degenerate triangle")]
        return ", ".join(f"{n} {w}{'' if n == 1 else ('ices' if w.endswith('vertex') else 's')}".replace(
            "vertexices", "vertices") for n, w in items if n)


def _components(n, a, b):
    """Connected-component label (the smallest member) of each of n nodes joined by the pairs (a[i], b[i]),
    vectorized: each round hooks the larger label of every unequal pair onto the smaller (labels[i] <= i always),
    then jumps pointers to the roots; a few rounds (about log n) suffice."""
    labels = np.arange(n)
    a, b = np.asarray(a, dtype=np.int64), np.asarray(b, dtype=np.int64)
    while True:
        la, lb = labels[a], labels[b]
        unequal = la != lb
        if not unequal.any():
            return labels
        hi, lo = np.maximum(la, lb)[unequal], np.minimum(la, lb)[unequal]
        order = np.lexsort((lo, hi))  # by hi, then lo: the first of each hi is its smallest lo
        hi, lo = hi[order], lo[order]
        first = np.r_[True, hi[1:] != hi[:-1]]
        labels[hi[first]] = np.minimum(labels[hi[first]], lo[first])
        while True:
            jumped = labels[labels]
            if np.array_equal(jumped, labels):
                break
            labels = jumped


def _triangle_areas(V, T):
    return 0.5 * np.linalg.norm(np.cross(V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 0]]), axis=1)


class _HalfEdges:
    """Half-edge h = 3t + k runs a[h] = T[t, k] -> b[h] = T[t, k+1]; nxt[h] = 3t + (k+1) % 3 starts where h ends.
    edge[h]: its undirected edge; count[e]: half-edges on e; pairs: the two half-edges of each 2-count edge."""

    def __init__(self, T, nv):
        nt = len(T)
        h = np.arange(3 * nt)
        self.nxt = 3 * (h // 3) + (h % 3 + 1) % 3
        self.a = T.ravel()
        self.b = self.a[self.nxt]
        key = np.minimum(self.a, self.b) * nv + np.maximum(self.a, self.b)
        self.keys, self.edge, self.count = np.unique(key, return_inverse=True, return_counts=True)
        self.edge = self.edge.ravel()
        self.nv = nv
        order = np.argsort(self.edge, kind="stable")
        two = np.nonzero(self.count == 2)[0]
        first = np.searchsorted(self.edge[order], two)
        self.h0, self.h1 = order[first], order[first + 1]
        self.same_direction = self.a[self.h0] == self.a[self.h1]  # a misoriented pair

    def vertex_pairs(self, edges):
        return np.stack([self.keys[edges] // self.nv, self.keys[edges] % self.nv], 1)


def _orientation_flips(nt, he, area):
    """Which triangles to flip so that every 2-count edge is traversed in opposite directions, per connected part;
    parts where that is impossible (non-orientable) are left as they are. Returns (flip mask, number of such parts).
    Orientation double cover: node 2t+s is triangle t with orientation s; a pair whose two half-edges run the same
    way joins opposite orientations. A part is orientable iff its two copies stay apart; then flip the triangles
    whose unflipped copy is not the one holding the part's first triangle unflipped (labels are smallest members,
    so that copy's label is even), or the others where those hold more than half the part's area: the
    orientation most of the surface has is kept."""
    t0, t1, odd = he.h0 // 3, he.h1 // 3, he.same_direction.astype(np.int64)
    a = np.concatenate([2 * t0, 2 * t0 + 1])
    b = np.concatenate([2 * t1 + odd, 2 * t1 + (1 - odd)])
    label = _components(2 * nt, a, b)
    orientable = label[0::2] != label[1::2]
    flip = orientable & (label[0::2] % 2 == 1)
    part = np.minimum(label[0::2], label[1::2]) // 2
    flipped_area = np.bincount(part, weights=area * flip, minlength=nt)
    total_area = np.bincount(part, weights=area, minlength=nt)
    flip ^= orientable & (flipped_area[part] > 0.5 * total_area[part])
    bad_parts = len(np.unique(label[0::2][~orientable]))
    return flip, bad_parts


def prepare(V, T, min_triangles=4):
    """Cuts the triangle mesh (V #V×3, T #T×3) into manifold parts: triangles are first flipped to agree with their
    neighbours (orientable parts), then glued only across edges with exactly two triangles traversing them in
    opposite directions; vertices where several fans of a part meet are duplicated per fan; degenerate
    (zero-area or repeated-index) triangles are dropped. Parts with fewer than min_triangles are dropped (noted)."""
    V = np.asarray(V, dtype=np.float64)
    T = np.asarray(T, dtype=np.int64).reshape(-1, 3)
    area = _triangle_areas(V, T)
    degenerate = (T[:, 0] == T[:, 1]) | (T[:, 1] == T[:, 2]) | (T[:, 0] == T[:, 2]) | ~(area > 0)
    T, area = T[~degenerate].copy(), area[~degenerate]
    nt, notes = len(T), []
    he = _HalfEdges(T, len(V))
    flip, non_orientable = _orientation_flips(nt, he, area)
    if flip.any():
        T[flip] = T[flip][:, ::-1]
        he = _HalfEdges(T, len(V))
        notes.append(f"{int(flip.sum())} triangle{'s' if flip.sum() != 1 else ''} flipped to match "
                     "their neighbours' orientation")
    if non_orientable:
        notes.append(f"{non_orientable} non-orientable piece{'s' if non_orientable != 1 else ''} (like a Möbius "
                     "strip) cut along its inconsistently oriented edges")
    glued = ~he.same_direction
    h0, h1 = he.h0[glued], he.h1[glued]
    comp = _components(nt, h0 // 3, h1 // 3)
    # Corners (one per half-edge start) across a glued edge a->b / b->a: a's corners h0 ~ next(h1), b's next(h0) ~ h1.
    fan = _components(3 * nt, np.concatenate([h0, he.nxt[h0]]), np.concatenate([he.nxt[h1], h1]))
    vf = np.unique(he.a * (3 * nt) + fan)
    fans_per_vertex = np.bincount(vf // (3 * nt), minlength=len(V))
    nonmanifold_vertices = np.nonzero(fans_per_vertex > 1)[0].astype(np.int64)
    parts, dropped = [], 0
    fan_t = fan.reshape(nt, 3)
    by_comp = np.argsort(comp, kind="stable")
    _, starts = np.unique(comp[by_comp], return_index=True)
    for tris in np.split(by_comp, starts[1:]) if nt else []:
        if len(tris) < min_triangles:
            dropped += 1
            continue
        # One new vertex per fan: a vertex shared by two fans of this part becomes two.
        _, first_corner, new_index = np.unique(fan_t[tris].ravel(), return_index=True, return_inverse=True)
        orig = T[tris].ravel()[first_corner]
        parts.append(Part(V[orig], new_index.reshape(-1, 3).astype(np.int32), orig, float(area[tris].sum())))
    if dropped:
        notes.append(f"{dropped} piece{'s' if dropped != 1 else ''} of fewer than {min_triangles} triangles left out")
    misoriented = np.nonzero(he.count == 2)[0][he.same_direction]
    return Preparation(parts, he.vertex_pairs(np.nonzero(he.count > 2)[0]), he.vertex_pairs(misoriented),
                       nonmanifold_vertices, int(degenerate.sum()), notes)


def face_targets(parts, total_faces, minimum=24):
    """Target quad count per part, proportional to area, at least `minimum` each (0 = the remesher's default)."""
    if total_faces <= 0:
        return [0] * len(parts)
    areas = np.array([p.area for p in parts], dtype=np.float64)
    share = areas / areas.sum() if areas.sum() > 0 else np.full(len(parts), 1.0 / max(1, len(parts)))
    return [max(minimum, int(round(total_faces * s))) for s in share]


def part_edges(part, pairs):
    """The edges of the part's triangles whose original vertices are one of `pairs` (#k×2 original vertex indices, in
    either order), in the part's own vertex indices (#m×2, each edge once, sorted); a pair that is not an edge of
    the part is left out. A vertex the preparation duplicated per fan gives each of its copies' edges."""
    P = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    T = np.asarray(part.triangles, dtype=np.int64)
    if len(P) == 0 or len(T) == 0:
        return np.zeros((0, 2), dtype=np.int64)
    E = np.sort(np.concatenate([T[:, [0, 1]], T[:, [1, 2]], T[:, [2, 0]]]), axis=1)
    orig = np.asarray(part.original_vertices, dtype=np.int64)
    n = int(max(orig.max(), P.max())) + 1
    a, b = orig[E[:, 0]], orig[E[:, 1]]
    keys = np.minimum(a, b) * n + np.maximum(a, b)
    wanted = np.minimum(P[:, 0], P[:, 1]) * n + np.maximum(P[:, 0], P[:, 1])
    return np.unique(E[np.isin(keys, wanted)], axis=0)
