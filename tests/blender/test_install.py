"""Headless test of installing the add-on as a user does (Preferences > Add-ons > Install from a zip), run with
BLENDER_USER_SCRIPTS set to an empty temporary folder (scripts/tests.d/36_blender.sh does):

    BLENDER_USER_SCRIPTS=$(mktemp -d) blender -b --factory-startup --python tests/blender/test_install.py -- \
        BUILD/python

Outside the repository the add-on cannot guess the module's folder: the operator must fail with a clear error, not a
traceback; with the folder set in the add-on preferences it remeshes. Prints "N passed, N failed"."""
import os
import shutil
import sys
import tempfile
import traceback

import addon_utils
import bpy

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MODULE_DIR = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
results = []


def step(name, fn):
    try:
        fn()
        results.append(True)
        print(f"PASS {name}", flush=True)
    except Exception:
        results.append(False)
        print(f"FAIL {name}\n{traceback.format_exc()}", flush=True)


def install():
    user = os.environ.get("BLENDER_USER_SCRIPTS", "")
    assert user and not os.listdir(user), "run with BLENDER_USER_SCRIPTS set to an empty folder"
    zip_base = os.path.join(tempfile.mkdtemp(), "quadcover_remesh")
    archive = shutil.make_archive(zip_base, "zip", os.path.join(ROOT, "blender"), "quadcover_remesh")
    assert bpy.ops.preferences.addon_install(filepath=archive) == {"FINISHED"}
    addon_utils.enable("quadcover_remesh", default_set=True)
    import quadcover_remesh

    assert os.path.realpath(quadcover_remesh.__file__).startswith(os.path.realpath(user)), quadcover_remesh.__file__
    assert "quadcover_remesh" in bpy.context.preferences.addons


def missing_module_is_a_clear_error():
    os.environ.pop("QUADCOVER_PYTHONPATH", None)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12)
    try:
        bpy.ops.object.quadcover_remesh(target_faces=300)
    except RuntimeError as e:  # Blender turns the operator's ERROR report into this exception
        assert "quadcover Python module was not found" in str(e) and "preferences" in str(e), str(e)
    else:
        raise AssertionError("the operator ran without the module")
    assert len(bpy.data.objects) == 1


def preference_finds_the_module():
    bpy.context.preferences.addons["quadcover_remesh"].preferences.module_path = MODULE_DIR
    assert bpy.ops.object.quadcover_remesh(target_faces=300) == {"FINISHED"}
    result = bpy.context.active_object
    assert result.name.endswith("_quadcover") and all(len(p.vertices) == 4 for p in result.data.polygons)


for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
step("install from a zip into the user's add-ons", install)
step("without the module: a clear error naming the preference", missing_module_is_a_clear_error)
step("with the module folder in the preferences: remeshes", preference_finds_the_module)
passed = sum(results)
print(f"blender install: {passed} passed, {len(results) - passed} failed", flush=True)
os._exit(0 if passed == len(results) == 3 else 1)
