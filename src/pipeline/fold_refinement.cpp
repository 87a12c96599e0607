// Targeted refinement of the triangles the untangling leaves non-positive (see fold_refinement.h).
#include "pipeline/fold_refinement.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "common/seconds_since.h"
#include "field/indices.h"
#include "mesh/vertex_rings.h"
#include "param/cover_cut.h"
#include "param/density.h"
#include "param/disk_functions.h"
#include "param/ring_winding.h"
#include "param/seams.h"
#include "pipeline/split_map.h"

namespace quadcover {

namespace {

/// The scaled gauged frames Z of the map (the untangler's Jacobian reference): ρ_f · scale · i^{r_f} (X_f, Y_f), ρ_f
/// the density factor of f's component (param/density.h).
FramePairs map_frames(const Mesh& mesh, const FrameField& field, const Parameterization& map) {
  FramePairs Z(mesh.num_faces(), 2);
  const Eigen::VectorXd rho = face_density(mesh, map.component_density);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto [x, y] = turn_frame(field.X[f], field.Y[f], map.face_rotation[f]);
    Z(f, 0) = rho[f] * map.scale * x;
    Z(f, 1) = rho[f] * map.scale * y;
  }
  return Z;
}

/// ½‖X̃ − ∇φ̃‖² on the covering = Σ_t A_t (|Z⁰_t − ∇φ⁰_t|² + |Z¹_t − ∇φ¹_t|²) (6.1.1).
double field_distance(const Mesh& mesh, const FramePairs& Z, const Eigen::MatrixX3cd& uv) {
  double s = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto [g0, g1] = face_gradient(mesh, uv, f);
    s += mesh.face_areas()[f] * (std::norm(Z(f, 0) - g0) + std::norm(Z(f, 1) - g1));
  }
  return s;
}

/// The held components a release may give up: those of the vertices of enforced curves (not the branch points, not
/// the kernel pins of param/harmonic_correction.h, which only fix the map's translation).
std::vector<char> releasable_components(const Mesh& mesh, const Parameterization& map) {
  const int nv = mesh.num_vertices();
  std::vector<char> on_curve(static_cast<std::size_t>(nv), 0);
  for (const Parameterization::Curve& curve : map.aligned_curves)
    if (curve.enforced)
      for (int e : curve.edges) on_curve[mesh.E()(e, 0)] = on_curve[mesh.E()(e, 1)] = 1;
  std::vector<char> r(static_cast<std::size_t>(2 * nv), 0);
  for (int p = 0; p < nv; ++p)
    if (on_curve[p] && !map.subspace.branch[p]) r[p] = map.subspace.fixed[p], r[nv + p] = map.subspace.fixed[nv + p];
  return r;
}

/// Gives up the curve pins of one corner of every face the subspace holds at zero area (param/untangle.h
/// release_stuck_corners): no refinement opens such a face. Returns the released vertices.
std::vector<int> release_held_corners(const Mesh& mesh, const FrameField& field, Parameterization& map) {
  const VertexLayers layers{map.subspace.layer, map.subspace.branch};
  return release_stuck_corners(mesh, layers, map.uv, map_frames(mesh, field, map), map.subspace.fixed,
                               releasable_components(mesh, map));
}

/// One round: the curve pins that hold a face at zero area released, the map carried over to the mesh with `edges`
/// split, then untangled in its subspace there (releasing again where a child is held).
struct Round {
  SplitMap split;
  ParamDiagnostics::Untangling untangling;
};

Round refine_round(const Mesh& mesh, const FrameField& field, const Parameterization& map,
                   const std::vector<int>& edges, const std::vector<int>& released_faces,
                   const UntangleOptions& options, ProgressSink& progress) {
  Parameterization released = map;
  std::vector<int> coarse_released = release_held_corners(mesh, field, released);
  const std::vector<char> coarse_releasable = releasable_components(mesh, released);
  const int nv0 = mesh.num_vertices();
  for (int f : released_faces)  // the last resort: the corners of faces no refinement has unfolded
    for (int c = 0; c < 3; ++c) {
      const int p = mesh.F()(f, c);
      if (!coarse_releasable[p] && !coarse_releasable[nv0 + p]) continue;
      for (const int i : {p, nv0 + p})
        if (coarse_releasable[i]) released.subspace.fixed[i] = 0;
      coarse_released.push_back(p);
    }
  Round r{split_map(mesh, field, released, edges), {}};
  const Mesh& fine = r.split.mesh;
  Parameterization& P = r.split.map;
  const int nv = fine.num_vertices();
  const VertexLayers layers{P.subspace.layer, P.subspace.branch};
  const std::vector<char> fixed = untangle_fixed_components(fine, layers, {}, P.subspace.fixed);
  const std::vector<char> releasable = releasable_components(fine, P);
  UntangleOptions release = options;
  release.release_curve_corners = true;
  const Eigen::VectorXcd u =
      untangle_and_rewind(fine, layers, P.uv, map_frames(fine, r.split.field, P), fixed, Eigen::VectorXcd::Zero(nv),
                          cross_field_quarter_index(fine, r.split.field), release, progress, r.untangling, releasable);
  P.uv -= layered_values(fine, layers, u);
  for (int p : r.untangling.released_vertices)
    for (const int i : {p, nv + p})
      if (releasable[i]) P.subspace.fixed[i] = 0;
  r.untangling.released_vertices.insert(r.untangling.released_vertices.end(), coarse_released.begin(),
                                        coarse_released.end());
  std::sort(r.untangling.released_vertices.begin(), r.untangling.released_vertices.end());
  r.untangling.released_vertices.erase(
      std::unique(r.untangling.released_vertices.begin(), r.untangling.released_vertices.end()),
      r.untangling.released_vertices.end());
  return r;
}

/// Takes a kept round into `out` (the refined mesh, field and map; the map's untangling record on the new mesh).
void keep_round(Round& r, int coarse_faces, int split_edges, FoldRefinement& out) {
  FoldRefinementReport& rep = out.report;
  ++rep.kept_rounds;
  rep.split_edges += split_edges;
  rep.added_faces += r.split.mesh.num_faces() - coarse_faces;
  rep.non_positive_after = r.untangling.non_positive_after;
  rep.untangle_iterations += r.untangling.iterations + r.untangling.polish_iterations;
  out.split.insert(out.split.end(), r.split.split.begin(), r.split.split.end());
  out.mesh = std::make_shared<const Mesh>(std::move(r.split.mesh));
  out.field = std::move(r.split.field);
  out.map = std::move(r.split.map);
  ParamDiagnostics::Untangling& u = out.map.diagnostics.untangling;
  u.non_positive_after = r.untangling.non_positive_after;
  u.min_det = r.untangling.min_det;
  u.stuck_faces = std::move(r.untangling.stuck_faces);
  u.unresolved_faces = std::move(r.untangling.unresolved_faces);
  for (int p : r.untangling.released_vertices) u.released_vertices.push_back(p);
  for (int p : r.untangling.rewound_vertices) u.rewound_vertices.push_back(p);
  for (int p : r.untangling.cone_disk_vertices) u.cone_disk_vertices.push_back(p);
  for (std::vector<int>* list : {&u.released_vertices, &u.rewound_vertices, &u.cone_disk_vertices}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
}

/// The curves' largest deviation from their iso-lines on the final map (released corners move off them).
void measure_curve_deviations(const Mesh& mesh, Parameterization& map) {
  for (Parameterization::Curve& curve : map.aligned_curves) {
    curve.max_deviation = 0;
    for (std::size_t j = 0; j < curve.edges.size(); ++j) {
      const int e = curve.edges[j], f = mesh.face_of_edge(e);
      for (int end = 0; end < 2; ++end) {
        const Complex z = map.uv(f, mesh.corner_of(f, mesh.E()(e, end)));
        const double coordinate = curve.edge_coordinates[j] == 0 ? z.real() : z.imag();
        curve.max_deviation = std::max(curve.max_deviation, std::abs(coordinate - curve.edge_values[j]));
      }
    }
  }
}

}  // namespace

std::vector<int> grow_faces(const Mesh& mesh, const std::vector<int>& faces, int rings) {
  std::vector<char> in(static_cast<std::size_t>(mesh.num_faces()), 0);
  for (int f : faces) in[f] = 1;
  if (rings > 0) {  // the faces with a vertex in the faces' vertices grown by rings − 1
    std::vector<char> vertex(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (int f : faces)
      for (int c = 0; c < 3; ++c) vertex[mesh.F()(f, c)] = 1;
    vertex = grow_vertex_rings(mesh, std::move(vertex), rings - 1);
    for (int f = 0; f < mesh.num_faces(); ++f)
      in[f] = in[f] || vertex[mesh.F()(f, 0)] || vertex[mesh.F()(f, 1)] || vertex[mesh.F()(f, 2)];
  }
  std::vector<int> out;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (in[f]) out.push_back(f);
  return out;
}

std::vector<int> edges_of_faces(const Mesh& mesh, const std::vector<int>& faces) {
  std::vector<int> edges;
  for (int f : faces)
    for (int k = 0; k < 3; ++k) edges.push_back(mesh.FE()(f, k));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

FoldRefinement refine_folds(const Mesh& mesh, const FrameField& field, const Parameterization& map,
                            const FoldRefinementOptions& options, ProgressSink& progress) {
  const auto start = std::chrono::steady_clock::now();
  FoldRefinement out;
  FoldRefinementReport& rep = out.report;
  rep.non_positive_before = rep.non_positive_after = flipped_triangles(mesh, map.uv).non_positive;
  if (options.max_rounds <= 0 || rep.non_positive_before == 0 || !options.untangle.enabled) return out;
  const double distance_before = field_distance(mesh, map_frames(mesh, field, map), map.uv);
  const Mesh* current_mesh = &mesh;
  const FrameField* current_field = &field;
  const Parameterization* current_map = &map;
  // Escalation after a round without progress: the faces' 1-ring as well, then also the curve pins of their corners.
  int escalation = 0;
  while (rep.rounds < options.max_rounds && rep.non_positive_after > 0 && !progress.skip_improvements()) {
    ++rep.rounds;
    const std::vector<int> bad = flipped_triangles(*current_mesh, current_map->uv).flipped_faces;
    const std::vector<int> edges = edges_of_faces(*current_mesh, grow_faces(*current_mesh, bad, escalation > 0));
    Round r = refine_round(*current_mesh, *current_field, *current_map, edges,
                           escalation > 1 ? bad : std::vector<int>{}, options.untangle, progress);
    progress.report("param", -1,
                    "fold refinement round " + std::to_string(rep.rounds) + ": " + std::to_string(edges.size()) +
                        " edges split, " + std::to_string(r.untangling.non_positive_after) + " non-positive");
    if (r.untangling.non_positive_after >= rep.non_positive_after) {  // no progress: undone
      if (++escalation > 2) break;
      continue;
    }
    keep_round(r, current_mesh->num_faces(), static_cast<int>(edges.size()), out);
    current_mesh = out.mesh.get();
    current_field = &out.field;
    current_map = &out.map;
  }
  if (out.mesh) measure_curve_deviations(*out.mesh, out.map);
  if (out.mesh)
    rep.energy = field_distance(*out.mesh, map_frames(*out.mesh, out.field, out.map), out.map.uv) - distance_before;
  rep.seconds = seconds_since(start);
  return out;
}

}  // namespace quadcover
