# SPDX-License-Identifier: BSD-3-Clause
"""Blender add-on: Quad Remesh (quadcover). Object > Quad Remesh (quadcover), and a panel in the mesh's Object Data
properties next to Blender's Remesh. The remesh runs on a worker thread (progress in the status bar, Esc cancels);
the result is a new object (or replaces the mesh) with the original's transform and materials. Loose parts are
remeshed one by one, n-gons triangulated first, non-manifold places reported and cut out."""
import os
import sys

import bpy
import numpy as np

from . import job as job_module

bl_info = {
    "name": "Quad Remesh (quadcover)",
    "author": "quadcover authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Object > Quad Remesh (quadcover); Properties > Object Data > Quad Remesh (quadcover)",
    "description": "Quad remeshing with seamless QuadCover parameterizations (the quadcover Python module)",
    "category": "Mesh",
}

ADDON = __name__


# ---- finding the quadcover module -------------------------------------------------------------------------------

def default_module_paths():
    """Where the module may be when the preference is empty: $QUADCOVER_PYTHONPATH, the build tree of the repository
    this add-on lives in (build/python), then whatever `import quadcover` finds (pip install, dist-packages)."""
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
    paths = [os.environ.get("QUADCOVER_PYTHONPATH", "")]
    if os.path.isfile(os.path.join(repo, "blender", "quadcover_remesh", "__init__.py")):  # run from the repository
        paths.append(os.path.join(repo, "build", "python"))
    return [p for p in paths if p]


def load_quadcover(preferred=""):
    """Imports quadcover from the preference's folder, else the defaults. Raises ImportError saying where it looked."""
    tried = []
    for path in ([bpy.path.abspath(preferred)] if preferred else []) + default_module_paths():
        if os.path.isdir(os.path.join(path, "quadcover")):
            if path not in sys.path:
                sys.path.insert(0, path)
            break
        tried.append(path)
    try:
        import quadcover
    except ImportError as e:
        where = ", ".join(tried + ["sys.path"])
        raise ImportError(f"the quadcover Python module was not found (looked in {where}: {e}); build it "
                          "(-DQUADCOVER_BUILD_PYTHON=ON) or pip install it, and set its folder in the add-on "
                          "preferences") from e
    if not hasattr(quadcover, "remesh") or not hasattr(quadcover, "Cancelled"):
        raise ImportError(f"{getattr(quadcover, '__file__', quadcover)} is not the quadcover package (no remesh)")
    return quadcover


def preferences(context):
    addon = context.preferences.addons.get(ADDON)
    return addon.preferences if addon else None


def quadcover_module(context):
    prefs = preferences(context)
    return load_quadcover(prefs.module_path if prefs else "")


class QUADCOVER_AP_preferences(bpy.types.AddonPreferences):
    bl_idname = ADDON
    module_path: bpy.props.StringProperty(
        name="quadcover module folder", subtype="DIR_PATH", default="",
        description="Folder that holds the quadcover package (e.g. BUILD/python); empty: the repository's "
                    "build/python, then the installed package")

    def draw(self, context):
        self.layout.prop(self, "module_path")
        try:
            qc = load_quadcover(self.module_path)
            self.layout.label(text=f"quadcover {qc.__version__}: {os.path.dirname(qc.__file__)}", icon="CHECKMARK")
        except ImportError as e:
            self.layout.label(text=str(e)[:160], icon="ERROR")


# ---- settings ---------------------------------------------------------------------------------------------------

FIELD_STYLES = [("auto", "Auto", "Smooth on a closed surface (Curvature where its result is not valid), "
                 "Curvature on one with a boundary"),
                ("curvature", "Curvature", "Cross field along the principal curvature directions (thesis ch. 5)"),
                ("smooth", "Smooth", "Smoothest cross field: lower distortion on organic shapes")]
SHARP_EDGES = [("ANGLE", "By Angle", "Sharp features: the edges sharper than Feature Angle"),
               ("MARKED", "Marked Sharp", "Sharp features: the edges marked sharp (Edge > Mark Sharp), whatever their "
                "angle")]
OUTPUTS = [("NEW", "New Object", "Add the result as a new object next to the original"),
           ("REPLACE", "Replace", "Replace the original's mesh (undo brings it back)")]


def _settings_props():
    return {
        "target_faces": bpy.props.IntProperty(name="Target Faces", default=2000, min=0, soft_max=200000,
                                              description="Target quad count over the whole object (0 = default "
                                              "density); loose parts share it by area"),
        "feature_angle": bpy.props.FloatProperty(name="Feature Angle", subtype="ANGLE", default=np.radians(35.0),
                                                 min=0.0, max=np.pi, description="Edges whose faces meet at more "
                                                 "than this angle (on creases of at least 8 edges) are followed by "
                                                 "the quads; 0 = no sharp features (boundaries are still followed)"),
        "sharp_edges": bpy.props.EnumProperty(name="Sharp Edges", items=SHARP_EDGES, default="ANGLE"),
        "align_boundary": bpy.props.BoolProperty(name="Align to Boundary", default=True,
                                                 description="Quad edges run exactly along open boundaries and "
                                                 "along the sharp features of Feature Angle"),
        "smoothing": bpy.props.IntProperty(name="Smoothing", default=20, min=0, max=200,
                                           description="Rounds of tangential quad smoothing on the surface"),
        "field_style": bpy.props.EnumProperty(name="Field", items=FIELD_STYLES, default="auto"),
        "output": bpy.props.EnumProperty(name="Output", items=OUTPUTS, default="NEW"),
        "suffix": bpy.props.StringProperty(name="Name Suffix", default="_quadcover"),
        "select_problems": bpy.props.BoolProperty(name="Select Problems", default=False,
                                                  description="Select the non-manifold vertices of the original "
                                                  "(see them in Edit mode)"),
    }


SETTING_NAMES = list(_settings_props())

QUADCOVER_PG_settings = type("QUADCOVER_PG_settings", (bpy.types.PropertyGroup,),
                             {"__annotations__": _settings_props()})


def settings_from(props):
    return job_module.Settings(target_faces=props.target_faces, feature_angle=float(np.degrees(props.feature_angle)),
                               align_boundary=props.align_boundary, smoothing=props.smoothing,
                               field_style=props.field_style, sharp_edges=props.sharp_edges)


# ---- Blender mesh <-> arrays ------------------------------------------------------------------------------------

def mesh_arrays(obj, depsgraph):
    """World-independent vertex positions and triangles (n-gons triangulated by Blender's loop triangles) of the
    object with its modifiers applied, its edges marked sharp (#k×2 vertex pairs); also whether vertex indices are
    the original mesh's (no modifiers)."""
    evaluated = obj.evaluated_get(depsgraph)
    me = evaluated.to_mesh()
    try:
        me.calc_loop_triangles()
        V = np.empty(3 * len(me.vertices), dtype=np.float64)
        me.vertices.foreach_get("co", V)
        T = np.empty(3 * len(me.loop_triangles), dtype=np.int64)
        me.loop_triangles.foreach_get("vertices", T)
        sharp = np.zeros(len(me.edges), dtype=bool)
        me.edges.foreach_get("use_edge_sharp", sharp)
        E = np.empty(2 * len(me.edges), dtype=np.int64)
        me.edges.foreach_get("vertices", E)
        same = len(me.vertices) == len(obj.data.vertices)
    finally:
        evaluated.to_mesh_clear()
    return V.reshape(-1, 3), T.reshape(-1, 3), E.reshape(-1, 2)[sharp], same


def build_mesh(name, result):
    verts, faces, offset = [], [], 0
    for V, F in zip(result.vertices, result.faces):
        verts.extend(map(tuple, np.asarray(V, dtype=np.float64)))
        faces.extend([i + offset for i in f] for f in F)
        offset += len(V)
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    me.validate(clean_customdata=False)
    me.update()
    return me


class Session:
    """One run of the operator: prepares the selected objects (UI thread), runs the job, and applies the results
    (UI thread). The modal operator and the blocking execute() both drive it; tests drive it directly."""

    def __init__(self, context, objects, props):
        self.qc = quadcover_module(context)
        self.props = {n: getattr(props, n) for n in SETTING_NAMES}
        self.names = [o.name for o in objects]
        depsgraph = context.evaluated_depsgraph_get()
        meshes, self.same_indices = {}, {}
        for o in objects:
            V, T, S, self.same_indices[o.name] = mesh_arrays(o, depsgraph)
            meshes[o.name] = (V, T, S)
        self.job = job_module.RemeshJob(self.qc, meshes, settings_from(props))

    def problems(self):
        """Report lines on what prep.prepare found (after the job ran)."""
        lines = []
        for name, p in self.job.objects.items():
            s = p.summary()
            if s:
                lines.append(f"{name}: {s}: cut there, the {len(p.parts)} manifold part"
                             f"{'s are' if len(p.parts) != 1 else ' is'} remeshed separately"
                             + (" (Select Problems marks them)" if not self.props["select_problems"] else ""))
            if not p.parts:
                lines.append(f"{name}: nothing to remesh (no manifold part of 4 or more triangles)")
        return lines

    def apply(self, context):
        """Adds (or swaps in) the results; returns (created objects, warning lines)."""
        created, lines = [], self.problems()
        for name in self.names:
            obj = bpy.data.objects.get(name)
            r = self.job.results.get(name)
            lines += [f"{name}: {m}" for m in (r.messages if r else [])]
            if self.props["select_problems"] and obj is not None and self.same_indices[name] and r is not None:
                bad = set(self.job.objects[name].problem_vertices.tolist())
                for v in obj.data.vertices:
                    v.select = v.index in bad
            if obj is None or r is None or not r.vertices:
                continue
            if r.non_quads:
                lines.append(f"{name}: {r.non_quads} of {r.quads + r.non_quads} faces are not quads")
            me = build_mesh(name + self.props["suffix"], r)
            for m in obj.data.materials:
                me.materials.append(m)
            if self.props["output"] == "REPLACE":
                obj.data = me
                created.append(obj)
                continue
            new = bpy.data.objects.new(name + self.props["suffix"], me)
            for c in obj.users_collection:
                c.objects.link(new)
            new.matrix_world = obj.matrix_world.copy()
            created.append(new)
        return created, lines


def selected_meshes(context):
    return [o for o in context.selected_objects if o.type == "MESH"] or (
        [context.active_object] if context.active_object and context.active_object.type == "MESH" else [])


def report_lines(op, lines, level):
    for line in lines:
        op.report({level}, line)


class QUADCOVER_OT_remesh(bpy.types.Operator):
    """Quad-remesh the selected meshes with quadcover (Esc cancels)"""

    bl_idname = "object.quadcover_remesh"
    bl_label = "Quad Remesh (quadcover)"
    bl_options = {"REGISTER", "UNDO"}
    __annotations__ = _settings_props()

    _session = None
    _timer = None

    @classmethod
    def poll(cls, context):
        return context.mode == "OBJECT" and bool(selected_meshes(context))

    def _start(self, context):
        try:
            self._session = Session(context, selected_meshes(context), self)
        except ImportError as e:
            self.report({"ERROR"}, str(e))
            return False
        return True

    def _finish(self, context):
        s = self._session
        if s.job.error:
            self.report({"ERROR"}, f"quadcover: {s.job.error}")
            return {"CANCELLED"}
        created, lines = s.apply(context)
        report_lines(self, lines, "WARNING")
        if not created:
            self.report({"ERROR"}, "quadcover: nothing was remeshed")
            return {"CANCELLED"}
        for o in context.selected_objects:
            o.select_set(False)
        for o in created:
            o.select_set(True)
        context.view_layer.objects.active = created[0]
        quads = sum(r.quads for r in s.job.results.values())
        self.report({"INFO"}, f"quadcover: {quads} quads in {s.job.seconds:.1f} s")
        return {"FINISHED"}

    def execute(self, context):  # blocking: scripts, redo panel and background mode
        if not self._start(context):
            return {"CANCELLED"}
        self._session.job.run()
        return self._finish(context)

    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        if not self._start(context):
            return {"CANCELLED"}
        self._session.job.start()
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.progress_begin(0, 100)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _cleanup(self, context):
        wm = context.window_manager
        if self._timer is not None:
            wm.event_timer_remove(self._timer)
            self._timer = None
        wm.progress_end()
        context.workspace.status_text_set(None)

    def modal(self, context, event):
        job = self._session.job
        if event.type == "ESC":
            job.cancel()  # the worker stops at its next progress check; its result is dropped
            self._cleanup(context)
            self.report({"WARNING"}, "quadcover: cancelled, scene unchanged")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        fraction, text = job.status()
        context.window_manager.progress_update(int(100 * fraction))
        context.workspace.status_text_set(f"Quad Remesh (quadcover): {text}   Esc: cancel")
        if not job.done:
            return {"RUNNING_MODAL"}
        self._cleanup(context)
        if job.cancelled:
            return {"CANCELLED"}
        return self._finish(context)


def _draw_settings(layout, s, qc):
    layout.prop(s, "target_faces")
    row = layout.row()
    row.enabled = qc is not None and job_module.supported(qc, job_module.FEATURE_EDGE_NAMES) is not None
    row.prop(s, "sharp_edges", expand=True)
    row = layout.row()
    row.enabled = qc is not None and job_module.supported(qc, job_module.FEATURE_ANGLE_NAMES) is not None and (
        s.sharp_edges == "ANGLE" or job_module.supported(qc, job_module.FEATURE_EDGE_NAMES) is None)
    row.prop(s, "feature_angle")
    row = layout.row()
    row.enabled = qc is not None and job_module.supported(qc, job_module.BOUNDARY_NAMES) is not None
    row.prop(s, "align_boundary")
    layout.prop(s, "smoothing")
    layout.prop(s, "field_style")
    layout.prop(s, "output", expand=True)
    if s.output == "NEW":
        layout.prop(s, "suffix")
    layout.prop(s, "select_problems")


class QUADCOVER_PT_panel(bpy.types.Panel):
    bl_label = "Quad Remesh (quadcover)"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "data"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == "MESH"

    def draw(self, context):
        s = context.scene.quadcover
        try:
            qc = quadcover_module(context)
        except ImportError as e:
            qc = None
            self.layout.label(text="quadcover module not found: see the add-on preferences", icon="ERROR")
            self.layout.label(text=str(e)[:120])
        _draw_settings(self.layout, s, qc)
        op = self.layout.operator(QUADCOVER_OT_remesh.bl_idname, icon="MOD_REMESH")
        for n in SETTING_NAMES:
            setattr(op, n, getattr(s, n))


def menu_func(self, context):
    self.layout.operator(QUADCOVER_OT_remesh.bl_idname, icon="MOD_REMESH")


CLASSES = (QUADCOVER_AP_preferences, QUADCOVER_PG_settings, QUADCOVER_OT_remesh, QUADCOVER_PT_panel)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.Scene.quadcover = bpy.props.PointerProperty(type=QUADCOVER_PG_settings)
    bpy.types.VIEW3D_MT_object.append(menu_func)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(menu_func)
    del bpy.types.Scene.quadcover
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
