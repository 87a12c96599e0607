"""Tests of the quadcover Python module: shapes and dtypes, topological invariants of real meshes, and the
seamlessness of the returned UVs checked here independently of the C++ code."""
import math
import os

import numpy as np
import pytest

import quadcover

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data")


def mesh(name):
    d = quadcover.load(os.path.join(DATA, name + ".obj"))
    return d["V"], d["F"]


def test_load_returns_arrays():
    V, F = mesh("bunny_3k")
    assert V.shape == (1839, 3) and V.dtype == np.float64
    assert F.shape == (3674, 3) and np.issubdtype(F.dtype, np.integer)
    assert F.min() == 0 and F.max() == V.shape[0] - 1


@pytest.mark.parametrize("name,genus", [("bunny_3k", 0), ("torus_5k", 1), ("eight_genus2", 2), ("fertility_genus4", 4)])
def test_info_topology(name, genus):
    V, F = mesh(name)
    info = quadcover.info(V, F)
    assert info["genus"] == genus
    assert info["faces"] == F.shape[0] and info["vertices"] == V.shape[0]
    # Closed surfaces: V - E + F = 2 - 2g and every edge has two faces (3F = 2E).
    assert info["euler_characteristic"] == 2 - 2 * genus
    assert 3 * info["faces"] == 2 * info["edges"]


def test_info_rejects_broken_mesh_with_a_clear_error():
    d = quadcover.load(os.path.join(DATA, "bad", "fandisk_nonmanifold_edge_fin.obj"))
    with pytest.raises(ValueError, match="non-manifold"):
        quadcover.info(d["V"], d["F"])
    with pytest.raises(ValueError):
        quadcover.load(os.path.join(DATA, "no_such_file.obj"))


def test_load_reads_per_corner_texture_coordinates(tmp_path):
    p = tmp_path / "quad_uv.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
    d = quadcover.load(str(p))
    assert d["uv"].shape == (4, 2)
    assert d["face_uv"] == [[0, 1, 2], [0, 2, 3]]
    np.testing.assert_array_equal(d["F"], [[0, 1, 2], [0, 2, 3]])


def test_field_has_a_frame_per_face_and_branch_points_on_a_sphere():
    V, F = mesh("bunny_3k")
    f = quadcover.field(V, F)
    assert f["X"].shape == (F.shape[0],) and np.iscomplexobj(f["X"])
    assert np.all(np.abs(f["X"]) > 0)
    assert f["matching"].shape == (f["edges"].shape[0],)
    # Poincaré-Hopf: a cross field on a sphere needs singularities; each has a fractional index.
    assert len(f["branch_points"]) > 0
    assert all(q % 4 != 0 for _, q in f["branch_points"])
    # The frame vectors lie in the face planes: X3 = Re X b1 + Im X b2 is orthogonal to the face normal.
    X3 = f["X"].real[:, None] * f["basis1"] + f["X"].imag[:, None] * f["basis2"]
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    assert np.max(np.abs(np.einsum("ij,ij->i", X3, n)) / np.linalg.norm(n, axis=1) / np.abs(f["X"])) < 1e-9


def seam_defect(F, uv):
    """Largest deviation from z -> i^k z + c with c in Z[i] across interior edges, and the number of cut edges."""
    z = uv[..., 0] + 1j * uv[..., 1]
    where = {}
    for f in range(F.shape[0]):
        for k in range(3):
            where[(F[f, k], F[f, (k + 1) % 3])] = (f, k)
    worst, cut = 0.0, 0
    for (a, b), (f, k) in where.items():
        if (b, a) not in where or a > b:
            continue
        g, l = where[(b, a)]
        za, zb = z[f, k], z[f, (k + 1) % 3]
        wb, wa = z[g, l], z[g, (l + 1) % 3]
        best = min(range(4), key=lambda r: abs(1j ** r * (zb - za) - (wb - wa)))
        rot = 1j ** best
        c = wa - rot * za
        err = max(abs(rot * (zb - za) - (wb - wa)), abs(c - complex(round(c.real), round(c.imag))))
        worst = max(worst, err)
        cut += abs(wa - za) > 1e-9 or abs(wb - zb) > 1e-9
    return worst, cut


@pytest.mark.parametrize("name", ["torus_5k", "bunny_3k"])
def test_parameterize_is_seamless_with_integer_translations(name):
    V0, F0 = mesh(name)
    result = quadcover.parameterize(V0, F0)
    uv, report = result
    V, F = result.V, result.F  # the map's triangulation: the input's, or its refinement (input vertices first)
    assert uv.shape == (F.shape[0], 3, 2)
    assert F.shape[0] == F0.shape[0] + report["refinement"]["added_faces"]
    assert np.allclose(V[: len(V0)], V0)
    extent = np.ptp(uv.reshape(-1, 2), axis=0).max()
    worst, cut = seam_defect(F, uv)
    assert worst < 1e-6 * max(1.0, extent)
    assert cut > 0  # a closed surface of genus >= 0 with cones (or a torus) needs a cut somewhere
    assert report["parameterization"]["energy_curl"] >= 0 and report["parameterization"]["energy_harmonic"] >= 0
    assert report["mesh"]["faces"] == F0.shape[0]
    # The report's counts match the signed areas of the returned UVs: flipped if A_uv < -1e-8 A_ref, collapsed if
    # |A_uv| <= 1e-8 A_ref, with A_ref the 3D area scaled by total |UV area| / total 3D area.
    e1, e2 = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]
    area = 0.5 * (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    d1, d2 = V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]
    area3d = 0.5 * np.linalg.norm(np.cross(d1, d2), axis=1)
    ref = 1e-8 * area3d * np.abs(area).sum() / area3d.sum()
    p = report["parameterization"]
    assert p["flipped_triangles"] == int(np.sum(area < -ref))
    assert p["collapsed_triangles"] == int(np.sum(np.abs(area) <= ref))
    assert p["non_positive_triangles"] == p["flipped_triangles"] + p["collapsed_triangles"]


def test_parameterize_density_follows_edge_length():
    V, F = mesh("torus_5k")
    uv1, r1 = quadcover.parameterize(V, F, edge_length=0.2)
    uv2, r2 = quadcover.parameterize(V, F, edge_length=0.1)
    # Halving h doubles the grid coordinates: four times the parameter area (the quad count).
    assert r2["parameterization"]["uv_area"] / r1["parameterization"]["uv_area"] == pytest.approx(4.0, rel=0.1)
    with pytest.raises(ValueError):
        quadcover.parameterize(V, F, lattice="hexagonal")


def test_remesh_torus_gives_a_closed_quad_mesh():
    V, F = mesh("torus_5k")
    QV, Q, report = quadcover.remesh(V, F)
    assert isinstance(Q, np.ndarray) and Q.shape[1] == 4
    assert QV.shape[1] == 3 and Q.max() < QV.shape[0]
    # A closed all-quad mesh of genus 1: V - E + F = 0 with E = 2F, so V = F.
    edges = {tuple(sorted((q[i], q[(i + 1) % 4]))) for q in Q.tolist() for i in range(4)}
    assert len(edges) == 2 * Q.shape[0]
    assert QV.shape[0] - len(edges) + Q.shape[0] == 0
    assert report["quad_mesh"] is not None and report["extraction"]["quads"] == Q.shape[0]


def test_remesh_quad_smoothing_keeps_connectivity_and_evens_out_edges():
    V, F = mesh("bunny_3k")
    QV0, Q0, r0 = quadcover.remesh(V, F, smooth_quads=0)
    QV, Q, r = quadcover.remesh(V, F)
    assert r0["quad_smoothing"]["iterations"] == 0
    assert r["quad_smoothing"]["iterations"] == 20 and r["quad_smoothing"]["rigidity"] == 0.5
    assert np.array_equal(Q, Q0)  # same faces, only the vertices move
    assert np.abs(QV - QV0).max() > 0
    assert r["quad_mesh"]["rsd_edge_length"] < r0["quad_mesh"]["rsd_edge_length"]
    assert r["quad_mesh"]["rsd_corner_angle"] < r0["quad_mesh"]["rsd_corner_angle"]
    assert r["parameterization"] == r0["parameterization"]  # the map itself is untouched
    with pytest.raises(ValueError, match="smooth_rigidity"):
        quadcover.remesh(V, F, smooth_rigidity=1.5)


def test_parameterize_relocation_lowers_curl_energy_and_branch_points():
    V, F = mesh("bunny_3k")
    _, none = quadcover.parameterize(V, F, optimize="none")
    # defaults: optimize="relocate", rounding="search3"; keep_better=False always returns the optimized field's map
    result = quadcover.parameterize(V, F, keep_better=False)
    uv, reloc = result
    assert none["optimize"]["mode"] == "none" and reloc["optimize"]["mode"] == "relocate"
    assert reloc["rounding"]["strategy"] == "search3"
    assert reloc["rounding"]["E_H"] == pytest.approx(reloc["parameterization"]["energy_harmonic"], rel=1e-12)
    o = reloc["optimize"]
    # Algorithm 6.1 without creation: never more branch points, never a higher E_D along the log. The count
    # before is the field's (measured independently by field()); the cones of the map follow.
    assert o["branch_points_before"] == len(quadcover.field(V, F)["branch_points"])
    assert o["branch_points_after"] <= o["branch_points_before"]
    assert reloc["parameterization"]["branch_points"] <= none["parameterization"]["branch_points"]
    eds = [o["E_D_before"]] + [e["E_D"] for e in o["log"]]
    assert all(b <= a * (1 + 1e-12) for a, b in zip(eds, eds[1:]))
    # ... and the parameterization's own E_D (curl removal on the covering) follows.
    assert reloc["parameterization"]["energy_curl"] < none["parameterization"]["energy_curl"]
    worst, _ = seam_defect(result.F, uv)
    assert worst < 1e-6 * max(1.0, np.ptp(uv.reshape(-1, 2), axis=0).max())
    assert reloc["optimize"]["kept"] == "optimized"
    # keep_better (default): the map with the lower E_D + E_H of the two fields.
    _, best = quadcover.parameterize(V, F)
    total = lambda r: r["parameterization"]["energy_curl"] + r["parameterization"]["energy_harmonic"]
    assert total(best) == pytest.approx(min(total(none), total(reloc)), rel=1e-9)
    assert best["optimize"]["kept"] == ("original" if total(none) < total(reloc) else "optimized")
    with pytest.raises(ValueError, match="optimiz"):
        quadcover.parameterize(V, F, optimize="everything")
    with pytest.raises(ValueError, match="rounding"):
        quadcover.parameterize(V, F, rounding="nearest")
    with pytest.raises(ValueError):
        quadcover.parameterize(V, F, max_iterations=-2)  # -1 = auto, 0 = until converged


def test_remesh_full_optimization_respects_the_budget():
    V, F = mesh("bunny_3k")
    QV, Q, report = quadcover.remesh(V, F, optimize="full", rounding="exact", max_iterations=150)
    o = report["optimize"]
    assert o["mode"] == "full" and o["stopped_early"]
    # The budget is checked between batches of candidate evaluations, so it may be passed by a few.
    assert 0 < o["evaluations"] <= 1.25 * 150
    assert o["E_D_after"] <= o["E_D_before"]
    assert report["rounding"]["strategy"] == "exact"
    assert report["rounding"]["E_H"] == pytest.approx(report["parameterization"]["energy_harmonic"], rel=1e-12)
    assert report["quad_mesh"]["faces"] == len(Q) > 0


def test_parameterize_stiffening_lowers_flips_and_keeps_energies():
    # couplingdown's plain map folds (tests/param/stiffening_test.cpp); stiffening (off by default since the untangler
    # makes maps injective) keeps E_H and the periods, never adds folds to the map it starts from, says what it did.
    V, F = mesh("couplingdown_genus9")
    # One density and one field for both: no validity retries (which could pick another density for one of them)
    # and no cone merges, moves or separation (which make the map again when the map is not valid); the curvature-
    # guided field of the case in tests/param/stiffening_test.cpp.
    same = dict(optimize="none", relaxation=0, validity_retries=0, merge_cones=False, move_cones=False,
                separate_cones=False, field="curvature")
    uv0, plain = quadcover.parameterize(V, F, **same)
    stiffened = quadcover.parameterize(V, F, stiffening=6, **same)
    uv1, stiff = stiffened
    assert plain["stiffening"]["iterations"] == 0 and plain["stiffening"]["E_K"] == 0
    for r in (plain, stiffened[1]):  # merge_cones / move_cones = False are honoured
        assert r["untangling"]["merged_cone_pairs"] == 0 and r["untangling"]["moved_wound_cones"] == 0
    s = stiff["stiffening"]
    assert s["iterations"] > 0 and s["flipped_after"] <= s["flipped_before"]
    assert stiff["parameterization"]["energy_harmonic"] == pytest.approx(plain["parameterization"]["energy_harmonic"], rel=1e-12)
    assert s["E_K"] >= 0
    # The untangler runs after it either way: its map (before the fold refinement) is no worse with stiffening.
    untangled = lambda r: r["fold_refinement"]["non_positive_before"]
    assert untangled(stiff) <= untangled(plain)
    worst, _ = seam_defect(stiffened.F, uv1)
    assert worst < 1e-6 * max(1.0, np.ptp(uv1.reshape(-1, 2), axis=0).max())
    with pytest.raises(ValueError):
        quadcover.parameterize(V, F, stiffening=-1)


def test_parameterize_relaxation_lowers_arap_and_keeps_the_map_seamless():
    # The ARAP relaxation (param/relaxation.h) keeps E_D, E_H and the seams, lowers the ARAP distortion of the
    # map, and reports its price E_R > 0 (one field for both: with field="auto" a map that is not valid would be made
    # again from the curvature-guided field); the curvature preset is accepted and gives another map.
    V, F = mesh("fandisk")
    _, plain = quadcover.parameterize(V, F, optimize="none", stiffening=0, relaxation=0, field="smooth")
    relaxed_result = quadcover.parameterize(V, F, optimize="none", stiffening=0, field="smooth")
    uv, relaxed = relaxed_result
    assert plain["relaxation"]["iterations"] == 0 and relaxed["relaxation"]["iterations"] > 0
    assert relaxed["parameterization"]["energy_harmonic"] == pytest.approx(plain["parameterization"]["energy_harmonic"], rel=1e-12)
    assert relaxed["relaxation"]["E_R"] > 0
    assert relaxed["relaxation"]["arap_after"] < relaxed["relaxation"]["arap_before"]
    assert relaxed["parameterization"]["arap"] < plain["parameterization"]["arap"]
    worst, _ = seam_defect(relaxed_result.F, uv)  # the map's triangulation (refined where it folded)
    assert worst < 1e-6 * max(1.0, np.ptp(uv.reshape(-1, 2), axis=0).max())
    assert relaxed["options"]["field"] == "smooth" and not relaxed["options"]["field_auto"]
    _, curvature = quadcover.parameterize(V, F, optimize="none", field="curvature")
    assert curvature["options"]["field"] == "curvature" and not curvature["options"]["field_auto"]
    assert curvature["parameterization"]["energy_curl"] != pytest.approx(relaxed["parameterization"]["energy_curl"], rel=1e-6)
    with pytest.raises(ValueError):
        quadcover.parameterize(V, F, relaxation=-1)
    with pytest.raises(ValueError):
        quadcover.parameterize(V, F, field="wobbly")


def test_split_cones_keyword_chooses_which_singularities_of_the_field_are_split():
    # cow's field has +3/4 and ±1/2 singularities: split into quarters by default, kept with whole turns only.
    V, F = mesh("cow")
    _, default = quadcover.parameterize(V, F, optimize="none")
    _, whole = quadcover.parameterize(V, F, optimize="none", split_cones=4)
    assert default["options"]["split_min_quarters"] == 2 and whole["options"]["split_min_quarters"] == 4
    assert default["field"]["singularity_moves"] > 0 and whole["field"]["singularity_moves"] == 0
    with pytest.raises(ValueError, match="split_cones"):
        quadcover.parameterize(V, F, split_cones=1)


def test_separate_cones_keyword_sets_apart_the_cones_the_rounding_put_on_one_point():
    # cow with whole turns split only (its +3/4 cones kept) and its close opposite pairs kept: two close cones
    # rounded onto one lattice point leave wrong windings unless set apart (README).
    V, F = mesh("cow")
    _, off = quadcover.parameterize(V, F, separate_cones=False, split_cones=4, cancel_close_cones=False)
    _, on = quadcover.parameterize(V, F, split_cones=4, cancel_close_cones=False)
    assert off["parameterization"]["wrong_windings"] > 0 and off["rounding"]["separated_cones"] == []
    assert off["rounding"]["coincident_cone_pairs"] > 0
    assert on["parameterization"]["wrong_windings"] == 0 and on["parameterization"]["non_positive_triangles"] == 0
    assert on["rounding"]["separated_cone_pairs"] == len(on["rounding"]["separated_cones"]) > 0
    assert "cone_separation" in on["seconds"]
    assert off["untangling"]["cone_separation"]["tried"] is False
    assert on["untangling"]["cone_separation"] == {"tried": True, "kept": True, "non_positive_triangles": 0,
                                                   "wrong_windings": 0}


def test_cancel_close_cones_keyword_cancels_opposite_pairs_closer_than_a_quad_edge():
    # cow's field (no optimization) has opposite branch points less than one quad edge apart; cancelled by default.
    V, F = mesh("cow")
    plain = dict(optimize="none", merge_cones=False, move_cones=False, separate_cones=False,
                 fold_refinement_rounds=0, validity_retries=0)
    _, on = quadcover.parameterize(V, F, **plain)
    _, off = quadcover.parameterize(V, F, cancel_close_cones=False, **plain)
    cancelled = on["field"]["cancelled_close_pairs"]
    assert cancelled["original"] > 0 and cancelled["optimized"] == 0
    assert off["field"]["cancelled_close_pairs"] == {"original": 0, "optimized": 0}
    assert len(off["field"]["branch_points"]) - len(on["field"]["branch_points"]) == 2 * cancelled["original"]


def test_square_holes_keyword_frees_the_plate_side_of_small_hole_rims():
    # couplingdown_genus9's bolt holes: closed crease loops a few quad edges around. By default their rims are freed on
    # the plate's side (options.freed_hole_rims); square_holes=0 follows them on both sides, as the CLI's
    # --square-holes 0 does.
    V, F = mesh("couplingdown_genus9")
    plain = dict(optimize="none", keep_better=False, validity_retries=0, fold_refinement_rounds=0)
    _, on = quadcover.parameterize(V, F, **plain)
    _, off = quadcover.parameterize(V, F, square_holes=0, **plain)
    assert on["options"]["square_holes"] == 8 and on["options"]["freed_hole_rims"] > 0
    assert off["options"]["square_holes"] == 0 and off["options"]["freed_hole_rims"] == 0
    with pytest.raises(ValueError, match="square_holes"):
        quadcover.parameterize(V, F, square_holes=-1)
