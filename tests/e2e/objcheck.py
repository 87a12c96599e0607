"""Independent checks of quadcover's output files, written against the file formats only (standard library).

- read_obj: v / vt / f (v, v/vt, v/vt/vn, v//vn) with 1-based or negative indices.
- polygon_topology: manifoldness (edges in at most two faces, consistent orientation, one fan per vertex),
  closedness, Euler characteristic and connected components of a polygon mesh.
- seam_check: seamlessness of a per-corner parameterization (thesis 2.1 / 4.2): across every interior edge the
  two sides' coordinates differ by z -> i^k z + c with c in Z[i].
- uv_flips: signed parameter-space areas (flipped = negative, thesis 2.1 requirement 2).
"""

import math


class ObjError(Exception):
    pass


class Obj:
    def __init__(self):
        self.v = []       # [(x, y, z)]
        self.vt = []      # [(u, v)]
        self.faces = []   # [[vertex index, ...]] 0-based
        self.face_vt = []  # [[vt index or None, ...]] 0-based, parallel to faces


def _index(token, count, path, line_no):
    i = int(token)
    i = i - 1 if i > 0 else count + i
    if not 0 <= i < count:
        raise ObjError(f"{path}:{line_no}: index {token} out of range (count {count})")
    return i


def read_obj(path):
    obj = Obj()
    with open(path, encoding="utf-8") as f:
        for line_no, line in enumerate(f, 1):
            parts = line.split()
            if not parts or parts[0].startswith("#"):
                continue
            tag = parts[0]
            try:
                if tag == "v":
                    obj.v.append(tuple(float(x) for x in parts[1:4]))
                    if len(parts) < 4:
                        raise ObjError(f"{path}:{line_no}: vertex with fewer than 3 coordinates")
                elif tag == "vt":
                    obj.vt.append((float(parts[1]), float(parts[2])))
                elif tag == "f":
                    vs, ts = [], []
                    for corner in parts[1:]:
                        fields = corner.split("/")
                        vs.append(_index(fields[0], len(obj.v), path, line_no))
                        ts.append(_index(fields[1], len(obj.vt), path, line_no)
                                  if len(fields) > 1 and fields[1] else None)
                    if len(vs) < 3:
                        raise ObjError(f"{path}:{line_no}: face with {len(vs)} corners")
                    obj.faces.append(vs)
                    obj.face_vt.append(ts)
            except (ValueError, IndexError) as e:
                raise ObjError(f"{path}:{line_no}: cannot parse '{line.strip()}': {e}") from e
    return obj


class Topology:
    """What polygon_topology found; `problems` lists every manifoldness violation (empty = manifold)."""

    def __init__(self):
        self.problems = []
        self.vertices = self.edges = self.faces = 0
        self.boundary_edges = 0
        self.components = 0
        self.unreferenced_vertices = 0
        self.edge_faces = {}  # (min v, max v) -> [faces]

    @property
    def manifold(self):
        return not self.problems

    @property
    def closed(self):
        return self.boundary_edges == 0

    @property
    def euler_characteristic(self):
        return self.vertices - self.edges + self.faces


def polygon_topology(num_vertices, faces, max_problems=10):
    t = Topology()
    t.faces = len(faces)
    half = {}   # directed edge (a, b) -> face
    undirected = {}
    corners_of = [[] for _ in range(num_vertices)]  # v -> [(face, prev, next)]
    for fi, face in enumerate(faces):
        n = len(face)
        if len(set(face)) != n:
            t.problems.append(f"face {fi} repeats a vertex: {face}")
        for j in range(n):
            a, b = face[j], face[(j + 1) % n]
            if (a, b) in half:
                t.problems.append(f"directed edge ({a}, {b}) in faces {half[(a, b)]} and {fi} "
                                  "(inconsistent orientation or non-manifold edge)")
            half[(a, b)] = fi
            undirected.setdefault((min(a, b), max(a, b)), []).append(fi)
            corners_of[face[j]].append((fi, face[j - 1], face[(j + 1) % n]))
    for e, fs in undirected.items():
        if len(fs) > 2:
            t.problems.append(f"edge {e} in {len(fs)} faces {fs}")
    t.edge_faces = undirected
    t.edges = len(undirected)
    t.boundary_edges = sum(1 for fs in undirected.values() if len(fs) == 1)
    # One fan per vertex: faces around v linked through the edges (v, x) they share.
    for v, corners in enumerate(corners_of):
        if not corners:
            t.unreferenced_vertices += 1
            continue
        parent = list(range(len(corners)))

        def find(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        by_neighbour = {}
        for i, (_, prev, nxt) in enumerate(corners):
            for x in (prev, nxt):
                if x in by_neighbour:
                    parent[find(i)] = find(by_neighbour[x])
                else:
                    by_neighbour[x] = i
        fans = len({find(i) for i in range(len(corners))})
        if fans > 1:
            t.problems.append(f"vertex {v}: {fans} separate fans of faces meet there")
    t.vertices = num_vertices - t.unreferenced_vertices
    # Components through shared edges.
    parent = list(range(len(faces)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for fs in undirected.values():
        for f in fs[1:]:
            parent[root(f)] = root(fs[0])
    t.components = len({root(i) for i in range(len(faces))})
    del t.problems[max_problems:]
    return t


def _gauss_distance(c):
    return abs(complex(c.real - round(c.real), c.imag - round(c.imag)))


class SeamCheck:
    def __init__(self):
        self.cut_edges = 0             # interior edges whose two sides have different coordinates
        self.max_transition_error = 0.0  # max |phi_t - (i^k phi_s + c)| at the edge's endpoints
        self.max_translation_defect = 0.0  # max distance of c to Z[i]
        self.extent = 0.0              # largest coordinate range of the map
        self.worst_edge = None


def seam_check(obj):
    """Seamlessness of the per-corner map of a triangle OBJ with vt; see the module doc."""
    uv = [[complex(*obj.vt[t]) for t in ts] for ts in obj.face_vt]
    us = [z.real for zs in uv for z in zs]
    vs = [z.imag for zs in uv for z in zs]
    s = SeamCheck()
    s.extent = max(max(us) - min(us), max(vs) - min(vs)) if us else 0.0
    sides = {}
    for fi, face in enumerate(obj.faces):
        n = len(face)
        for j in range(n):
            a, b = face[j], face[(j + 1) % n]
            sides.setdefault((min(a, b), max(a, b)), []).append((fi, {a: uv[fi][j], b: uv[fi][(j + 1) % n]}))
    for (a, b), fs in sides.items():
        if len(fs) != 2:
            continue
        p, q = fs[0][1], fs[1][1]
        if p[a] == q[a] and p[b] == q[b]:
            continue
        s.cut_edges += 1
        best = None
        for k in range(4):  # transition z -> i^k z + c (1.4: matching in Z_4)
            r = 1j ** k
            c = q[a] - r * p[a]
            err = abs(r * p[b] + c - q[b])
            score = (err + _gauss_distance(c), err, _gauss_distance(c))
            best = score if best is None or score < best else best
        if best[1] > s.max_transition_error:
            s.max_transition_error, s.worst_edge = best[1], (a, b)
        s.max_translation_defect = max(s.max_translation_defect, best[2])
    return s


def uv_signed_areas(obj):
    areas = []
    for ts in obj.face_vt:
        (u0, v0), (u1, v1), (u2, v2) = (obj.vt[t] for t in ts[:3])
        areas.append(0.5 * ((u1 - u0) * (v2 - v0) - (u2 - u0) * (v1 - v0)))
    return areas


def uv_quarter_indices(obj):
    """{interior vertex: 4 (1 - theta / 2 pi) rounded}, theta the sum of the signed UV corner angles of a triangle
    map at the vertex (a corner with a side of zero length adds nothing): the map's winding around each vertex."""
    theta = [0.0] * len(obj.v)
    sides = {}
    for face, ts in zip(obj.faces, obj.face_vt):
        for c in range(3):
            a, b, d = (obj.vt[ts[(c + k) % 3]] for k in range(3))
            x1, y1, x2, y2 = b[0] - a[0], b[1] - a[1], d[0] - a[0], d[1] - a[1]
            theta[face[c]] += math.atan2(x1 * y2 - y1 * x2, x1 * x2 + y1 * y2)
            edge = (min(face[c], face[(c + 1) % 3]), max(face[c], face[(c + 1) % 3]))
            sides[edge] = sides.get(edge, 0) + 1
    boundary = {v for e, n in sides.items() if n == 1 for v in e}
    used = {v for face in obj.faces for v in face}
    return {v: round(4 * (1 - theta[v] / (2 * math.pi))) for v in sorted(used - boundary)}


def face_areas(obj):
    """3D area of each face (fan triangulation)."""
    out = []
    for face in obj.faces:
        p0, total = obj.v[face[0]], 0.0
        for j in range(1, len(face) - 1):
            p1, p2 = obj.v[face[j]], obj.v[face[j + 1]]
            a = [p1[i] - p0[i] for i in range(3)]
            b = [p2[i] - p0[i] for i in range(3)]
            c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
            total += 0.5 * math.sqrt(sum(x * x for x in c))
        out.append(total)
    return out


def mesh_area(obj):
    total = 0.0
    for face in obj.faces:
        p0 = obj.v[face[0]]
        for j in range(1, len(face) - 1):
            p1, p2 = obj.v[face[j]], obj.v[face[j + 1]]
            a = [p1[i] - p0[i] for i in range(3)]
            b = [p2[i] - p0[i] for i in range(3)]
            cx = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
            total += 0.5 * math.sqrt(sum(x * x for x in cx))
    return total


def read_png(path):
    """Decodes an 8-bit non-interlaced PNG (grey, RGB, RGBA) with zlib: returns (width, height, channels, rows),
    rows a list of bytes objects after undoing the scanline filters (PNG spec 9.2)."""
    import struct
    import zlib
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ObjError(f"{path}: not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0]:
            raise ObjError(f"{path}: CRC error in chunk {kind!r}")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    if header is None:
        raise ObjError(f"{path}: no IHDR")
    w, h, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        raise ObjError(f"{path}: unsupported PNG (depth {depth}, colour type {colour}, interlace {interlace})")
    raw = zlib.decompress(idat)
    stride = w * channels
    if len(raw) != h * (stride + 1):
        raise ObjError(f"{path}: {len(raw)} bytes of image data for {w}x{h}x{channels}")
    rows, prev = [], bytearray(stride)
    for y in range(h):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            elif kind != 0:
                raise ObjError(f"{path}: unknown filter {kind} in row {y}")
        rows.append(bytes(line))
        prev = line
    return w, h, channels, rows
