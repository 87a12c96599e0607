// Complex Hermitian stiffness matrices of the covering (thesis 3.2.3, (3.8)) and the complex curl* (3.3).
#include "cover/complex_stiffness.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <vector>

#include "common/errors.h"
#include "common/quarter_turn.h"

namespace quadcover {

namespace {

void check_matching(const Mesh& mesh, const Eigen::VectorXi& matching, const char* where) {
  if (matching.size() != mesh.num_edges())
    throw InputError("", 0, std::string(where) + ": matching has " + std::to_string(matching.size()) +
                                " entries, the mesh has " + std::to_string(mesh.num_edges()) + " edges");
}

/// Reference face r(e) of (3.5): the face with the smaller index (the only face on the boundary).
int reference_face(const Mesh& mesh, int e) {
  const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
  if (s < 0) return t;
  if (t < 0) return s;
  return std::min(s, t);
}

/// Layer shift of function values when crossing edge e from face f into the other face: w_other = i^shift w_f.
int crossing_shift(const Mesh& mesh, const Eigen::VectorXi& matching, int e, int f) {
  return mesh.EF()(e, 0) == f ? -matching[e] : matching[e];
}

/// The edge of face f (face-edge index) shared with face g, or -1.
int shared_face_edge(const Mesh& mesh, int f, int g) {
  for (int k = 0; k < 3; ++k)
    if (mesh.neighbor(f, k) == g) return k;
  return -1;
}

}  // namespace

Eigen::MatrixX3i edge_layers(const Mesh& mesh, const Eigen::VectorXi& matching) {
  check_matching(mesh, matching, "edge_layers");
  Eigen::MatrixX3i mu(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      const int r = reference_face(mesh, e);
      // Value in f = i^{shift(r -> f)} · value in r.
      mu(f, k) = r == f ? 0 : mod4(crossing_shift(mesh, matching, e, r));
    }
  return mu;
}

VertexLayers vertex_layers(const Mesh& mesh, const Eigen::VectorXi& matching) {
  check_matching(mesh, matching, "vertex_layers");
  VertexLayers out;
  out.layer = Eigen::MatrixX3i::Zero(mesh.num_faces(), 3);
  out.branch = Eigen::VectorXi::Zero(mesh.num_vertices());
  std::vector<int> acc;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const auto fan = mesh.fan(v);
    const int d = static_cast<int>(fan.size());
    if (d == 0) continue;
    acc.assign(static_cast<std::size_t>(d), 0);
    for (int i = 0; i + 1 < d; ++i) {
      const int f = fan[i].face, g = fan[i + 1].face;
      const int k = shared_face_edge(mesh, f, g);
      acc[i + 1] = acc[i] + crossing_shift(mesh, matching, mesh.FE()(f, k), f);
    }
    if (!mesh.is_boundary_vertex(v)) {
      const int f = fan[d - 1].face, g = fan[0].face;
      const int k = shared_face_edge(mesh, f, g);
      const int total = acc[d - 1] + crossing_shift(mesh, matching, mesh.FE()(f, k), f);
      if (mod4(total) != 0) {  // branch point: the face cycle does not close (3.2.2)
        out.branch[v] = 1;
        continue;
      }
    }
    int ref = 0;  // the lowest-index face around v fixes the gauge (thesis 3.2.2)
    for (int i = 1; i < d; ++i)
      if (fan[i].face < fan[ref].face) ref = i;
    for (int i = 0; i < d; ++i) out.layer(fan[i].face, fan[i].corner) = mod4(acc[i] - acc[ref]);
  }
  return out;
}

Eigen::SparseMatrix<Complex> complex_nonconforming_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching) {
  const Eigen::MatrixX3i mu = edge_layers(mesh, matching);
  std::vector<Eigen::Triplet<Complex>> trip;
  trip.reserve(static_cast<std::size_t>(9 * mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double A = mesh.face_areas()[f];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        // ∫_f ⟨∇ψ_a, ∇ψ_b⟩ = ⟨e_a, e_b⟩ / A_f (∇ψ = -J e / A), = -2 cot of the angle between e_a and e_b (1.5).
        const double K = std::real(std::conj(mesh.edge_vector_local(f, a)) * mesh.edge_vector_local(f, b)) / A;
        // conj(i^{μ_a}) i^{μ_b}: the element energy Σ K_ab Re(conj(w_a) w_b) of the local values w = i^μ ū.
        trip.emplace_back(mesh.FE()(f, a), mesh.FE()(f, b), K * ipow(mu(f, b) - mu(f, a)));
      }
  }
  Eigen::SparseMatrix<Complex> L(mesh.num_edges(), mesh.num_edges());
  L.setFromTriplets(trip.begin(), trip.end());
  L.makeCompressed();
  return L;
}

Eigen::SparseMatrix<Complex> complex_conforming_stiffness(const Mesh& mesh, const Eigen::VectorXi& matching,
                                                          const Eigen::VectorXd& face_weights) {
  if (face_weights.size() != 0 && face_weights.size() != mesh.num_faces())
    throw InputError("", 0, "complex_conforming_stiffness: face_weights needs one weight per face");
  const VertexLayers vl = vertex_layers(mesh, matching);
  std::vector<Eigen::Triplet<Complex>> trip;
  trip.reserve(static_cast<std::size_t>(9 * mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double A = mesh.face_areas()[f], w = face_weights.size() ? face_weights[f] : 1.0;
    for (int a = 0; a < 3; ++a) {
      const int p = mesh.F()(f, a);
      for (int b = 0; b < 3; ++b) {
        const int q = mesh.F()(f, b);
        if (vl.branch[p] || vl.branch[q]) {
          trip.emplace_back(p, q, Complex(0));  // stored: one pattern for every matching
          continue;
        }
        // ∫_f ⟨∇φ_p, ∇φ_q⟩ = ⟨e_p, e_q⟩ / (4 A_f), e_p the edge opposite p (∇φ_p = J e_p / 2A).
        const double K =
            w * std::real(std::conj(mesh.edge_vector_local(f, a)) * mesh.edge_vector_local(f, b)) / (4 * A);
        trip.emplace_back(p, q, K * ipow(vl.layer(f, b) - vl.layer(f, a)));
      }
    }
  }
  for (int p = 0; p < mesh.num_vertices(); ++p)
    if (vl.branch[p]) trip.emplace_back(p, p, Complex(1, 0));
  Eigen::SparseMatrix<Complex> L(mesh.num_vertices(), mesh.num_vertices());
  L.setFromTriplets(trip.begin(), trip.end());
  L.makeCompressed();
  return L;
}

Eigen::VectorXcd complex_curl_star(const Mesh& mesh, const FrameField& field) {
  check_matching(mesh, field.matching, "complex_curl_star");
  if (field.X.size() != mesh.num_faces() || field.Y.size() != mesh.num_faces())
    throw InputError("", 0, "complex_curl_star: the frame field has the wrong number of faces");
  const Eigen::MatrixX3i mu = edge_layers(mesh, field.matching);
  Eigen::VectorXcd curl = Eigen::VectorXcd::Zero(mesh.num_edges());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Complex e = mesh.edge_vector_local(f, k);  // positively oriented in f
      const Complex ez(std::real(std::conj(e) * field.X[f]), std::real(std::conj(e) * field.Y[f]));  // ⟨Z_f, e⟩
      // curl* = -Σ_f conj(i^μ) ⟨Z_f, e_f⟩: the right-hand side of the normal equation, negated.
      curl[mesh.FE()(f, k)] -= ipow(-mu(f, k)) * ez;
    }
  return curl;
}

Eigen::MatrixX3cd layered_values(const Mesh& mesh, const VertexLayers& layers, const Eigen::VectorXcd& u) {
  Eigen::MatrixX3cd c(mesh.num_faces(), 3);
  // Face by face on both cores (every map check of the untangling and relaxation runs this on the whole mesh).
  tbb::parallel_for(tbb::blocked_range<int>(0, mesh.num_faces(), 4096), [&](const tbb::blocked_range<int>& faces) {
    for (int f = faces.begin(); f < faces.end(); ++f)
      for (int a = 0; a < 3; ++a) {
        const int p = mesh.F()(f, a);
        c(f, a) = layered_value(layers, f, a, p, u[p]);
      }
  });
  return c;
}

}  // namespace quadcover
