"""Headless test of the Blender add-on (blender/quadcover_remesh):

    blender -b --factory-startup --python tests/blender/test_addon.py [-- BUILD/python]

A UV sphere, a torus and tests/data/bunny_3k.obj become all-quad objects with the original's transform and
materials; loose parts and n-gons are handled; Suzanne with a fin (1 non-manifold edge, 2 non-manifold vertices)
gives a clear report and its manifold parts are remeshed; Esc / cancel leaves the scene unchanged. Prints
"N passed, N failed" and exits non-zero on a failure."""
import os
import sys
import time
import traceback

import addon_utils
import bpy
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
MODULE_DIR = os.path.abspath(argv[0]) if argv else os.path.join(ROOT, "build", "python")
sys.path.insert(0, os.path.join(ROOT, "blender"))

addon_utils.enable("quadcover_remesh", default_set=True, handle_error=lambda e: traceback.print_exc())
import quadcover_remesh  # noqa: E402
from quadcover_remesh import prep  # noqa: E402

bpy.context.preferences.addons["quadcover_remesh"].preferences.module_path = MODULE_DIR

results = []


def check(name):
    def wrap(fn):
        t0 = time.perf_counter()
        try:
            fn()
            results.append((name, True, ""))
            print(f"PASS {name} ({time.perf_counter() - t0:.2f} s)", flush=True)
        except Exception:
            results.append((name, False, traceback.format_exc()))
            print(f"FAIL {name}\n{traceback.format_exc()}", flush=True)
        return fn
    return wrap


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    for m in list(bpy.data.meshes):
        bpy.data.meshes.remove(m)


def select_only(*objs):
    bpy.ops.object.select_all(action="DESELECT")
    for o in objs:
        o.select_set(True)
    bpy.context.view_layer.objects.active = objs[0]


def dress(obj):
    """A transform and a material the result must keep."""
    obj.location = (1.0, -2.0, 0.5)
    obj.rotation_euler = (0.3, 0.0, 1.1)
    obj.scale = (1.5, 1.5, 0.75)
    mat = bpy.data.materials.new("quadcover_test_material")
    obj.data.materials.append(mat)
    bpy.context.view_layer.update()
    return mat


def remesh(obj, **kw):
    select_only(obj)
    before = set(bpy.data.objects.keys())
    assert bpy.ops.object.quadcover_remesh(**kw) == {"FINISHED"}
    new = [bpy.data.objects[n] for n in set(bpy.data.objects.keys()) - before]
    assert len(new) == 1, f"expected one new object, got {new}"
    return new[0]


def face_sizes(obj):
    return np.array([len(p.vertices) for p in obj.data.polygons])


def loose_parts(obj):
    """Blender's loose parts: the pieces connected through edges (union-find over the polygons' vertices)."""
    me = obj.data
    parent = list(range(len(me.vertices)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for p in me.polygons:
        vs = list(p.vertices)
        for a, b in zip(vs, vs[1:]):
            parent[find(a)] = find(b)
    used = {v for p in me.polygons for v in p.vertices}
    return len({find(v) for v in used})


def assert_all_quads_like(result, original, suffix="_quadcover"):
    sizes = face_sizes(result)
    assert len(sizes) > 50 and np.all(sizes == 4), f"{result.name}: face sizes {np.unique(sizes)}"
    assert result.name == original.name + suffix
    np.testing.assert_allclose(np.array(result.matrix_world), np.array(original.matrix_world), atol=1e-6)
    assert [m.name for m in result.data.materials] == [m.name for m in original.data.materials]


@check("UV sphere -> all quads on the sphere, transform and material kept, original untouched")
def _():
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=1.0)
    sphere = bpy.context.active_object
    dress(sphere)
    n_before = len(sphere.data.vertices)
    result = remesh(sphere, target_faces=600)
    assert_all_quads_like(result, sphere)
    r = np.linalg.norm(np.array([v.co[:] for v in result.data.vertices]), axis=1)  # local coordinates
    assert np.all(np.abs(r - 1.0) < 0.02), f"radius {r.min()}..{r.max()}"
    assert len(sphere.data.vertices) == n_before and len(bpy.data.objects) == 2
    # The target reaches the remesher: four times the faces asked, about four times the faces made (the accuracy
    # of the count itself is the remesher's, tested there).
    bpy.data.objects.remove(result)
    coarse = len(remesh(sphere, target_faces=300).data.polygons)
    fine = len(remesh(sphere, target_faces=1200).data.polygons)
    assert 3.0 < fine / coarse < 5.0, (coarse, fine)


@check("torus (genus 1) -> all quads, Euler characteristic 0")
def _():
    clear_scene()
    bpy.ops.mesh.primitive_torus_add(major_segments=48, minor_segments=16)
    torus = bpy.context.active_object
    dress(torus)
    result = remesh(torus, target_faces=800, field_style="smooth")
    assert_all_quads_like(result, torus)
    me = result.data
    assert len(me.vertices) - len(me.edges) + len(me.polygons) == 0


@check("bunny_3k.obj imported -> all quads")
def _():
    clear_scene()
    bpy.ops.wm.obj_import(filepath=os.path.join(ROOT, "tests", "data", "bunny_3k.obj"))
    bunny = bpy.context.selected_objects[0]
    result = remesh(bunny, target_faces=1500)
    assert_all_quads_like(result, bunny)


@check("replace mode swaps the mesh in place, keeping object and transform")
def _():
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12)
    sphere = bpy.context.active_object
    dress(sphere)
    old_mesh, M = sphere.data.name, np.array(sphere.matrix_world)
    select_only(sphere)
    assert bpy.ops.object.quadcover_remesh(target_faces=400, output="REPLACE") == {"FINISHED"}
    assert len(bpy.data.objects) == 1 and sphere.data.name != old_mesh
    assert np.all(face_sizes(sphere) == 4)
    np.testing.assert_allclose(np.array(sphere.matrix_world), M)
    assert len(sphere.data.materials) == 1


@check("two loose parts with n-gons (cylinder caps) are remeshed each")
def _():
    clear_scene()
    bpy.ops.mesh.primitive_cylinder_add(vertices=32, location=(0, 0, 0))  # 32-gon caps
    cyl = bpy.context.active_object
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, location=(4, 0, 0))
    sph = bpy.context.active_object
    select_only(cyl, sph)
    bpy.ops.object.join()
    joined = bpy.context.active_object
    assert max(face_sizes(joined)) == 32 and loose_parts(joined) == 2
    result = remesh(joined, target_faces=800)
    sizes = face_sizes(result)
    assert loose_parts(result) == 2
    assert np.mean(sizes == 4) > 0.97, np.unique(sizes, return_counts=True)


@check("feature angle and boundary alignment reach the remesher: cylinder rims on quad edges only with both")
def _():
    import quadcover

    from quadcover_remesh import job as job_module

    # The panel's rows are enabled (not greyed out) with this build's module, and the settings are passed on.
    assert job_module.supported(quadcover, job_module.FEATURE_ANGLE_NAMES) == "feature_angle"
    assert job_module.supported(quadcover, job_module.BOUNDARY_NAMES) == "align_curves"
    kw = job_module.remesh_kwargs(quadcover, job_module.Settings(feature_angle=20.0, align_boundary=False), 500)
    assert kw["feature_angle"] == 20.0 and kw["align_curves"] is False and kw["faces"] == 500, kw
    clear_scene()
    # 90 degree rims at z = +-1; caps as triangle fans around a centre vertex
    bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=1.0, depth=2.0, end_fill_type="TRIFAN")
    cyl = bpy.context.active_object

    def rim_edges(angle_degrees, align):
        """Quad edges lying on a rim (both ends on the same rim circle)."""
        result = remesh(cyl, target_faces=800, feature_angle=np.radians(angle_degrees), align_boundary=align)
        P = np.array([v.co[:] for v in result.data.vertices])
        E = np.array([e.vertices[:] for e in result.data.edges])
        bpy.data.objects.remove(result)
        on = (np.abs(np.abs(P[:, 2]) - 1.0) < 1e-3) & (np.abs(np.hypot(P[:, 0], P[:, 1]) - 1.0) < 0.02)
        return int(np.sum(on[E[:, 0]] & on[E[:, 1]] & (np.sign(P[E[:, 0], 2]) == np.sign(P[E[:, 1], 2]))))

    aligned, no_features, not_aligned = rim_edges(35, True), rim_edges(0, True), rim_edges(35, False)
    print(f"  quad edges on the rims: 35 deg aligned {aligned}, 0 deg {no_features}, 35 deg not aligned {not_aligned}")
    # Two rims of length 2 pi at h ~ 0.15 (800 quads on area 6 pi): ~80 edges when both rims are quad edge loops.
    assert aligned > 70 and aligned > 1.5 * no_features and aligned > 1.5 * not_aligned


@check("edges marked sharp are the features with Sharp Edges = Marked: one marked rim on quad edges, not the other")
def _():
    import quadcover

    from quadcover_remesh import job as job_module

    assert job_module.supported(quadcover, job_module.FEATURE_EDGE_NAMES) == "features"
    marked = np.array([[0, 1], [1, 2]])
    kw = job_module.remesh_kwargs(quadcover, job_module.Settings(sharp_edges="MARKED"), 500, marked)
    assert "feature_angle" not in kw and kw["features"].tolist() == marked.tolist(), kw
    assert "features" not in job_module.remesh_kwargs(quadcover, job_module.Settings(), 500, marked)
    # prep.part_edges: original pairs in the part's own numbers, either order, non-edges left out
    part = prep.Part(np.zeros((4, 3)), np.array([[0, 1, 2], [0, 2, 3]]), np.array([10, 11, 12, 13]), 1.0)
    assert prep.part_edges(part, [[11, 10], [12, 10], [11, 13], [99, 10]]).tolist() == [[0, 1], [0, 2]]
    clear_scene()
    bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=1.0, depth=2.0, end_fill_type="TRIFAN")
    cyl = bpy.context.active_object
    co = np.array([v.co[:] for v in cyl.data.vertices])
    for e in cyl.data.edges:  # the top rim only (both ends on the circle at z = 1)
        a, b = (co[i] for i in e.vertices)
        e.use_edge_sharp = bool(min(a[2], b[2]) > 0.999 and min(np.hypot(*a[:2]), np.hypot(*b[:2])) > 0.999)
    assert sum(e.use_edge_sharp for e in cyl.data.edges) == 32

    def rim_edges(result, z):
        P = np.array([v.co[:] for v in result.data.vertices])
        E = np.array([e.vertices[:] for e in result.data.edges])
        on = (np.abs(P[:, 2] - z) < 1e-3) & (np.abs(np.hypot(P[:, 0], P[:, 1]) - 1.0) < 0.02)
        return int(np.sum(on[E[:, 0]] & on[E[:, 1]]))

    result = remesh(cyl, target_faces=800, sharp_edges="MARKED")
    top, bottom = rim_edges(result, 1.0), rim_edges(result, -1.0)
    print(f"  quad edges on the marked rim {top}, on the unmarked one {bottom}")
    # the marked rim (2 pi at h ~ 0.15) is an edge loop of ~40 quad edges; the unmarked 90-degree rim is not followed
    assert top > 35 and top > 2 * bottom


@check("two selected objects: one result each, named after its original")
def _():
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, location=(-3, 0, 0))
    a = bpy.context.active_object
    bpy.ops.mesh.primitive_torus_add(location=(3, 0, 0))
    b = bpy.context.active_object
    select_only(a, b)
    assert bpy.ops.object.quadcover_remesh(target_faces=400) == {"FINISHED"}
    assert sorted(bpy.data.objects.keys()) == sorted([a.name, b.name, a.name + "_quadcover", b.name + "_quadcover"])
    for o in (a, b):
        result = bpy.data.objects[o.name + "_quadcover"]
        assert_all_quads_like(result, o)
        assert result.select_get()


def suzanne_with_fin():
    """Suzanne plus one triangle on an existing edge: 1 non-manifold edge, 2 non-manifold vertices."""
    bpy.ops.mesh.primitive_monkey_add()
    monkey = bpy.context.active_object
    me = monkey.data
    e = me.edges[100]
    a, b = e.vertices
    tip = (np.array(me.vertices[a].co) + np.array(me.vertices[b].co)) / 2 + np.array([0.0, 0.0, 0.4])
    me.vertices.add(1)
    me.vertices[-1].co = tip
    me.loops.add(3)
    me.polygons.add(1)
    me.loops[-3].vertex_index, me.loops[-2].vertex_index, me.loops[-1].vertex_index = a, b, len(me.vertices) - 1
    me.polygons[-1].loop_start, me.polygons[-1].loop_total = len(me.loops) - 3, 3
    me.update(calc_edges=True)
    return monkey, (a, b)


@check("Suzanne: loose parts remeshed; with a fin: a clear non-manifold report, manifold parts remeshed")
def _():
    clear_scene()
    bpy.ops.mesh.primitive_monkey_add()
    monkey = bpy.context.active_object
    result = remesh(monkey, target_faces=800)
    assert loose_parts(result) == 3  # head and two eyes
    clear_scene()
    monkey, (a, b) = suzanne_with_fin()
    select_only(monkey)
    props = bpy.context.scene.quadcover
    props.target_faces, props.select_problems = 800, True
    s = quadcover_remesh.Session(bpy.context, [monkey], props)
    s.job.run()
    created, lines = s.apply(bpy.context)
    text = "\n".join(lines)
    print("  Blender reports:\n   " + text.replace("\n", "\n   "))
    assert "Suzanne: 1 non-manifold edge, 2 non-manifold vertices" in text, text
    assert "manifold parts are remeshed separately" in text
    assert len(created) == 1 and len(created[0].data.polygons) > 400
    selected = sorted(v.index for v in monkey.data.vertices if v.select)
    assert selected == sorted((a, b)), selected
    # The operator reports the same and finishes.
    select_only(monkey)
    assert bpy.ops.object.quadcover_remesh(target_faces=800) == {"FINISHED"}


def bad_mesh(name):
    import quadcover

    return quadcover.read(os.path.join(ROOT, "tests", "data", "bad", name + ".obj"))


def quadcover_module_read(name):
    import quadcover

    return quadcover.read(os.path.join(ROOT, "tests", "data", name + ".obj"))


def opposite_halfedges(T):
    """True if every interior edge of T is traversed once each way (a consistently oriented manifold)."""
    he = {}
    for t in T:
        for k in range(3):
            e = (int(t[k]), int(t[(k + 1) % 3]))
            he[e] = he.get(e, 0) + 1
    return all(n == 1 for n in he.values())


@check("prep: flipped triangles reoriented, non-manifold vertex split, Klein bottle cut; parts pass quadcover.info")
def _():
    import quadcover

    m = bad_mesh("blobby_inconsistent_orientation")
    p = prep.prepare(m.vertices, m.faces)
    assert len(p.parts) == 1 and p.summary() == "" and "flipped" in p.notes[0], (p.summary(), p.notes)
    assert opposite_halfedges(p.parts[0].triangles)
    assert quadcover.info(p.parts[0].vertices, p.parts[0].triangles)["faces"] == len(m.faces)
    # A minority of flipped triangles, the first among them: the majority's orientation is kept.
    bunny = quadcover_module_read("bunny_3k")
    T = np.array(bunny.faces)
    T[:1000] = T[:1000, ::-1]
    p = prep.prepare(bunny.vertices, T)
    np.testing.assert_array_equal(p.parts[0].original_vertices[p.parts[0].triangles], bunny.faces)
    m = bad_mesh("cow_orig_nonmanifold_vertex")
    with_problem = prep.prepare(m.vertices, m.faces)
    assert with_problem.summary() == "1 non-manifold vertex" and len(with_problem.nonmanifold_vertices) == 1
    part = with_problem.parts[0]
    assert len(part.vertices) == len(m.vertices) + 1  # the vertex is split into its two fans
    quadcover.info(part.vertices, part.triangles)  # raises if still non-manifold
    m = bad_mesh("torus_klein_nonorientable")
    p = prep.prepare(m.vertices, m.faces)
    assert any("non-orientable" in n for n in p.notes) and len(p.misoriented_edges) > 0
    for part in p.parts:
        assert opposite_halfedges(part.triangles)


@check("a sphere with half its faces flipped still becomes one all-quad object")
def _():
    import bmesh

    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16)
    sphere = bpy.context.active_object
    bm = bmesh.new()
    bm.from_mesh(sphere.data)
    bmesh.ops.reverse_faces(bm, faces=[f for f in bm.faces if f.calc_center_median().x > 0.1])
    bm.to_mesh(sphere.data)
    bm.free()
    select_only(sphere)
    props = bpy.context.scene.quadcover
    props.target_faces, props.select_problems = 600, False
    s = quadcover_remesh.Session(bpy.context, [sphere], props)
    s.job.run()
    created, lines = s.apply(bpy.context)
    assert any("flipped to match" in line for line in lines), lines
    assert len(created) == 1 and np.all(face_sizes(created[0]) == 4) and loose_parts(created[0]) == 1
    # The orientation of the larger half (x <= 0.1, not reversed: outward) is kept: normals point out.
    me = created[0].data
    outward = [np.dot(np.array(p.normal), np.array(p.center)) > 0 for p in me.polygons]
    assert all(outward), sum(outward)


class FakeEvent:
    def __init__(self, type):
        self.type = type


class FakeOperator:
    """Stands in for the running modal operator (no window in background mode): same methods, reports kept."""

    def __init__(self, session):
        self._session, self._timer, self.reports = session, None, []
        self.report = lambda level, text: self.reports.append((level, text))
        self._cleanup = lambda ctx: None  # no timer and no progress bar without a window
        self._finish = lambda ctx: quadcover_remesh.QUADCOVER_OT_remesh._finish(self, ctx)


@check("Esc while running: the modal operator cancels and the scene is unchanged")
def _():
    clear_scene()
    bpy.ops.wm.obj_import(filepath=os.path.join(ROOT, "tests", "data", "bunny_3k.obj"))
    bunny = bpy.context.selected_objects[0]
    select_only(bunny)
    objects, meshes = sorted(bpy.data.objects.keys()), sorted(bpy.data.meshes.keys())
    co = np.array([v.co[:] for v in bunny.data.vertices])
    op = FakeOperator(quadcover_remesh.Session(bpy.context, [bunny], bpy.context.scene.quadcover))
    job = op._session.job
    job.start()
    modal = quadcover_remesh.QUADCOVER_OT_remesh.modal
    assert modal(op, bpy.context, FakeEvent("TIMER")) == {"RUNNING_MODAL"}
    # Esc once the remesher reports a stage of its own (the part is being remeshed, not yet started or done).
    native_progress = quadcover_remesh.job_module.supported(job.qc, ("progress",)) is not None
    t0 = time.time()
    def before_the_remesher_reports(text):
        return text == "starting" or "checking" in text or (native_progress and "remeshing" in text)

    while before_the_remesher_reports(job.status()[1]):
        assert not job.done and time.time() - t0 < 60, job.status()
        time.sleep(0.005)
    stage_at_esc = job.status()[1]
    assert modal(op, bpy.context, FakeEvent("ESC")) == {"CANCELLED"}
    job.wait(60)
    assert job.done and job.cancelled, stage_at_esc
    if native_progress:  # the remesh itself stopped: the part has no result
        assert not job.results["bunny_3k"].vertices, stage_at_esc
        print(f"  Esc at '{stage_at_esc}': stopped inside the remesh")
    assert sorted(bpy.data.objects.keys()) == objects and sorted(bpy.data.meshes.keys()) == meshes
    np.testing.assert_array_equal(np.array([v.co[:] for v in bunny.data.vertices]), co)
    assert any("cancelled" in t for _, t in op.reports)
    # Without Esc the same modal loop finishes with the result.
    op = FakeOperator(quadcover_remesh.Session(bpy.context, [bunny], bpy.context.scene.quadcover))
    op._session.job.start()
    t0 = time.time()
    while (state := modal(op, bpy.context, FakeEvent("TIMER"))) == {"RUNNING_MODAL"} and time.time() - t0 < 120:
        time.sleep(0.05)
    assert state == {"FINISHED"}, (state, op.reports)
    assert len(bpy.data.objects) == 2


@check("a missing module gives a clear error, not a traceback")
def _():
    try:
        quadcover_remesh.load_quadcover("/nonexistent/folder")  # falls back to the defaults: still found
    except ImportError:
        raise AssertionError("the default module paths should still find quadcover")
    import quadcover

    assert os.path.dirname(os.path.dirname(quadcover.__file__)) == MODULE_DIR


@check("param's OBJ imports into Blender with the map as its UV layer, corner by corner")
def _():
    import subprocess
    import tempfile

    cli = os.path.join(os.path.dirname(MODULE_DIR), "quadcover")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bunny.param.obj")
        subprocess.run([cli, "param", "-q", os.path.join(ROOT, "tests", "data", "bunny_3k.obj"), "-o", path],
                       check=True)
        vt, faces = [], []  # the map as written: vt lines, and per face the (vertex, vt) indices of its corners
        with open(path) as f:
            for line in f:
                if line.startswith("vt "):
                    vt.append([float(x) for x in line.split()[1:3]])
                elif line.startswith("f "):
                    faces.append([tuple(int(i) - 1 for i in c.split("/")[:2]) for c in line.split()[1:]])
        vt = np.array(vt)
        clear_scene()
        assert bpy.ops.wm.obj_import(filepath=path) == {"FINISHED"}
        me = bpy.context.selected_objects[0].data
    assert len(me.uv_layers) == 1 and len(me.polygons) == len(faces), (len(me.uv_layers), len(me.polygons))
    uv = np.array([d.uv[:] for d in me.uv_layers[0].data])
    worst = 0.0
    for p, corners in zip(me.polygons, faces):
        assert [me.loops[k].vertex_index for k in p.loop_indices] == [v for v, _ in corners], p.index
        got = uv[list(p.loop_indices)]
        worst = max(worst, float(np.max(np.abs(got - vt[[t for _, t in corners]]) / np.maximum(1.0, np.abs(got)))))
    assert worst < 1e-6, f"UVs differ from the vt lines by {worst} (relative to float32)"


passed = sum(ok for _, ok, _ in results)
failed = len(results) - passed
print(f"blender: {passed} passed, {failed} failed")
sys.stdout.flush()
os._exit(0 if failed == 0 and passed > 0 else 1)
