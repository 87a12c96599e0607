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


class _UnionFind:
    def __init__(self, n):
        self.parent = np.arange(n)

    def find(self, a):
        root = a
        while self.parent[root] != root:
            root = self.parent[root]
        while self.parent[a] != root:
            self.parent[a], a = root, self.parent[a]
        return root

    def union(self, a, b):
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[max(ra, rb)] = min(ra, rb)


def _triangle_areas(V, T):
    return 0.5 * np.linalg.norm(np.cross(V[T[:, 1]] - V[T[:, 0]], V[T[:, 2]] - V[T[:, 0]]), axis=1)


def _edge_table(T):
    """Per half-edge (3 per triangle, edge k of t goes T[t,k] -> T[t,k+1]): undirected key id, direction sign."""
    a = T.ravel()
    b = np.roll(T, -1, axis=1).ravel()
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    keys, inverse, counts = np.unique(np.stack([lo, hi], 1), axis=0, return_inverse=True, return_counts=True)
    return keys, inverse.ravel(), counts, a < b


def prepare(V, T, min_triangles=4):
    """Cuts the triangle mesh (V #V×3, T #T×3) into manifold parts: triangles are glued only across edges with
    exactly two triangles traversing them in opposite directions; vertices where several fans of a part meet are
    duplicated per fan; degenerate (zero-area or repeated-index) triangles are dropped. Parts with fewer than
    min_triangles triangles are dropped with a note."""
    V = np.asarray(V, dtype=np.float64)
    T = np.asarray(T, dtype=np.int64).reshape(-1, 3)
    area = _triangle_areas(V, T)
    degenerate = (T[:, 0] == T[:, 1]) | (T[:, 1] == T[:, 2]) | (T[:, 0] == T[:, 2]) | ~(area > 0)
    T, area = T[~degenerate], area[~degenerate]
    keys, edge_of, counts, forward = _edge_table(T)
    nt = len(T)
    tri_of = np.repeat(np.arange(nt), 3)
    # Edges seen by exactly two half-edges of opposite directions glue their triangles.
    fwd_count = np.bincount(edge_of, weights=forward, minlength=len(keys))
    glued = (counts == 2) & (fwd_count == 1)
    misoriented = (counts == 2) & (fwd_count != 1)
    uf = _UnionFind(nt)
    order = np.argsort(edge_of, kind="stable")
    e_sorted = edge_of[order]
    starts = np.searchsorted(e_sorted, np.nonzero(glued)[0])
    for s in starts:
        uf.union(tri_of[order[s]], tri_of[order[s + 1]])
    # Corners: (triangle, vertex) grouped into fans: corners of the same vertex in triangles glued across an edge
    # at that vertex. Union the corners across each glued edge at both its ends.
    corner_uf = _UnionFind(3 * nt)
    corner_index = {}
    for t in range(nt):
        for k in range(3):
            corner_index[(t, int(T[t, k]))] = 3 * t + k
    for s in starts:
        h0, h1 = order[s], order[s + 1]
        t0, t1 = tri_of[h0], tri_of[h1]
        for v in keys[e_sorted[s]]:
            corner_uf.union(corner_index[(t0, int(v))], corner_index[(t1, int(v))])
    fan_root = np.array([corner_uf.find(c) for c in range(3 * nt)]).reshape(nt, 3)
    fans_per_vertex = {}
    for t in range(nt):
        for k in range(3):
            fans_per_vertex.setdefault(int(T[t, k]), set()).add(int(fan_root[t, k]))
    nonmanifold_vertices = np.array(sorted(v for v, f in fans_per_vertex.items() if len(f) > 1), dtype=np.int64)
    comp = np.array([uf.find(t) for t in range(nt)])
    parts, notes, dropped = [], [], 0
    for root in np.unique(comp):
        tris = np.nonzero(comp == root)[0]
        if len(tris) < min_triangles:
            dropped += 1
            continue
        # One new vertex per fan: a vertex shared by two fans of this part becomes two.
        roots = fan_root[tris]
        uniq, new_index = np.unique(roots.ravel(), return_inverse=True)
        first_corner = {int(r): i for i, r in enumerate(uniq)}
        orig = np.empty(len(uniq), dtype=np.int64)
        flat_t = T[tris].ravel()
        for c, r in enumerate(roots.ravel()):
            orig[first_corner[int(r)]] = flat_t[c]
        parts.append(Part(V[orig], new_index.reshape(-1, 3).astype(np.int32), orig, float(area[tris].sum())))
    if dropped:
        notes.append(f"{dropped} piece{'s' if dropped != 1 else ''} of fewer than {min_triangles} triangles left out")
    return Preparation(parts, keys[counts > 2], keys[misoriented], nonmanifold_vertices, int(degenerate.sum()),
                       notes)


def face_targets(parts, total_faces, minimum=24):
    """Target quad count per part, proportional to area, at least `minimum` each (0 = the remesher's default)."""
    if total_faces <= 0:
        return [0] * len(parts)
    areas = np.array([p.area for p in parts], dtype=np.float64)
    share = areas / areas.sum() if areas.sum() > 0 else np.full(len(parts), 1.0 / max(1, len(parts)))
    return [max(minimum, int(round(total_faces * s))) for s in share]
