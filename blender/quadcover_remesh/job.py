"""The remesh job of the add-on, run off Blender's UI thread (no bpy here): remeshes the prepared parts of each
object one after the other with quadcover.remesh, reports progress, and can be cancelled between parts or, when
the module takes a progress callback, inside a part."""
import threading
import time
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

from . import prep


@dataclass
class Settings:
    target_faces: int = 2000
    feature_angle: float = 35.0  # degrees, 0 = no sharp features: remesh(feature_angle=)
    align_boundary: bool = True  # boundaries and sharp features on quad edges: remesh(align_curves=)
    smoothing: int = 20  # rounds of quad smoothing
    field_style: str = "auto"
    sharp_edges: str = "ANGLE"  # ANGLE: edges above feature_angle; MARKED: the edges marked sharp (remesh(features=))


# Keyword names of these settings in quadcover.remesh (an older module lacks them: the panel greys them out and they are not passed).
FEATURE_ANGLE_NAMES = ("feature_angle",)
BOUNDARY_NAMES = ("align_curves",)
FEATURE_EDGE_NAMES = ("features",)


def supported(quadcover, names):
    """The first of names that quadcover.remesh takes, or None."""
    native = getattr(quadcover, "_quadcover", quadcover)
    accepts = getattr(quadcover, "accepts", None)
    for n in names:
        if accepts is not None and accepts(native.remesh, n):
            return n
    return None


def remesh_kwargs(quadcover, settings: Settings, faces: int, marked=None):
    """The keywords of quadcover.remesh for one part; marked: its edges marked sharp (#k×2 part vertex indices), the
    sharp features instead of the angle when settings.sharp_edges is MARKED and the module takes them."""
    kw = {"field": settings.field_style, "smooth_quads": int(settings.smoothing)}
    if faces > 0:
        kw["faces"] = int(faces)
    given = supported(quadcover, FEATURE_EDGE_NAMES) if settings.sharp_edges == "MARKED" else None
    name = supported(quadcover, FEATURE_ANGLE_NAMES)
    if given:
        kw[given] = np.zeros((0, 2), dtype=np.int64) if marked is None else np.asarray(marked, dtype=np.int64)
    elif name:
        kw[name] = float(settings.feature_angle)
    name = supported(quadcover, BOUNDARY_NAMES)
    if name:
        kw[name] = bool(settings.align_boundary)
    return kw


@dataclass
class ObjectResult:
    name: str
    vertices: List[np.ndarray] = field(default_factory=list)  # one array per remeshed part
    faces: List[list] = field(default_factory=list)
    messages: List[str] = field(default_factory=list)  # warnings for Blender's report area
    quads: int = 0
    non_quads: int = 0


class RemeshJob:
    """meshes: {name: (V, T)} or {name: (V, T, S)} triangle meshes, S the edges marked sharp (#k×2 vertex pairs). start() runs run() on a thread: prep.prepare() on each (.objects),
    then the remesh of every part; cancel() asks it to stop; status() gives (fraction, text) for the status bar;
    done tells when it has stopped (results in .results, .error)."""

    def __init__(self, quadcover, meshes: Dict[str, tuple], settings: Settings):
        self.qc = quadcover
        self.meshes = meshes
        self.objects: Dict[str, prep.Preparation] = {}
        self.settings = settings
        self.results: Dict[str, ObjectResult] = {}
        self.error: Optional[str] = None
        self.cancelled = False
        self._cancel = threading.Event()
        self._lock = threading.Lock()
        self._fraction, self._text = 0.0, "starting"
        self._thread = None
        self.seconds = 0.0

    # ---- control (UI thread)
    def start(self):
        self._thread = threading.Thread(target=self.run, name="quadcover-remesh", daemon=True)
        self._thread.start()

    def cancel(self):
        self._cancel.set()

    @property
    def done(self):
        return self._thread is not None and not self._thread.is_alive()

    def wait(self, timeout=None):
        if self._thread is not None:
            self._thread.join(timeout)

    def status(self):
        with self._lock:
            return self._fraction, self._text

    # ---- work (worker thread, or the caller's in background mode)
    def _set(self, fraction, text):
        with self._lock:
            self._fraction, self._text = fraction, text

    def run(self):
        t0 = time.perf_counter()
        try:
            self._run()
        except self.qc.Cancelled:
            self.cancelled = True
        except Exception as e:  # anything else ends the job with a message, never kills Blender
            self.error = f"{type(e).__name__}: {e}"
        if self._cancel.is_set():
            self.cancelled = True
        self.seconds = time.perf_counter() - t0

    def _run(self):
        for name, (V, T, *_) in self.meshes.items():
            self._set(0.0, f"{name}: checking {len(T)} triangles")
            self.objects[name] = prep.prepare(V, T)
            if self._cancel.is_set():
                raise self.qc.Cancelled("cancelled")
        jobs = [(name, p, part, n) for name, p in self.objects.items()
                for part, n in zip(p.parts, prep.face_targets(p.parts, self.settings.target_faces))]
        total = sum(len(part.triangles) for _, _, part, _ in jobs) or 1
        done_tris = 0
        for name, p in self.objects.items():
            self.results[name] = ObjectResult(name, messages=list(p.notes))
        for k, (name, p, part, faces) in enumerate(jobs):
            if self._cancel.is_set():
                raise self.qc.Cancelled("cancelled")
            label = f"{name} part {k + 1}/{len(jobs)}"
            base = done_tris / total

            def progress(stage, fraction, message, base=base, label=label):
                # fraction is the stage's own (-1: unknown): it goes in the text; the bar counts finished parts.
                pct = f" {100 * min(1.0, fraction):.0f}%" if fraction >= 0 else ""
                self._set(base, f"{label}: {stage}{pct} {message}".strip())
                return self._cancel.is_set()

            self._set(base, f"{label}: remeshing {len(part.triangles)} triangles")
            try:
                sharp = self.meshes[name][2] if len(self.meshes[name]) > 2 else None
                marked = None if sharp is None else prep.part_edges(part, sharp)
                QV, Q, report = self.qc.remesh(part.vertices, part.triangles, progress=progress,
                                               **remesh_kwargs(self.qc, self.settings, faces, marked))
            except self.qc.Cancelled:
                raise
            except (ValueError, RuntimeError) as e:
                if self._cancel.is_set():
                    raise self.qc.Cancelled("cancelled") from e
                first = str(e).splitlines()[0] if str(e) else type(e).__name__
                self.results[name].messages.append(f"part {k + 1} ({len(part.triangles)} triangles) not "
                                                   f"remeshed: {first}")
            else:
                r = self.results[name]
                faces_list = Q.tolist() if isinstance(Q, np.ndarray) else [list(f) for f in Q]
                r.vertices.append(np.asarray(QV))
                r.faces.append(faces_list)
                r.quads += sum(1 for f in faces_list if len(f) == 4)
                r.non_quads += sum(1 for f in faces_list if len(f) != 4)
            done_tris += len(part.triangles)
        self._set(1.0, "done")
