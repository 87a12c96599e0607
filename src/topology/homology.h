#pragma once
// Homology generators γ_k read off a cut graph, their dual cycles γ_k*, and periods b_j(X) = ∫_{γ_j*} ω_X of
// locally integrable fields (thesis 1.2.5, Def. 1.14).
//
// The generators are the fundamental cycles of the cut graph K (with all boundary vertices of a component
// identified, so a generator may also be a path from boundary to boundary: a relative cycle). Per component there
// are 2g of them on a closed surface and 2g + b - 1 with b > 0 boundary loops, the dimension of the harmonic space.
// Generator j contains exactly one leftover edge e_j of Algorithm 1.16 that no other generator contains; its dual
// cycle crosses e_j from the left of γ_j to its right and then returns through the cotree T*, so it crosses no other
// generator (thesis 1.2.6) and b_j(Σ_k) = δ_jk.
//
// Reference implementation on the real surface M (used by topology/harmonic_basis.h): the product reads its periods
// from the covering's cut (param/cover_cut.h); tests/param/reference_stack_test.cpp compares the two period
// lattices with a matching ≡ 0.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "calculus/vector_field.h"
#include "topology/cut_graph.h"

namespace quadcover {

/// An edge walk γ_k. Closed generators return to their first vertex (vertices.back() == vertices.front()) and
/// avoid the boundary; open generators run from a boundary vertex to a boundary vertex (possibly the same one).
struct HomologyGenerator {
  std::vector<int> vertices;  ///< v_0 … v_m
  std::vector<int> edges;     ///< m edges, edges[i] joins vertices[i] and vertices[i+1]
  bool closed = true;
  int crossing_edge = -1;  ///< e_j, the edge its dual cycle crosses
};

/// A closed walk in the dual graph: faces[i] -> faces[(i+1) % n] across edges[i].
struct DualCycle {
  std::vector<int> faces;
  std::vector<int> edges;
};

struct HomologyBasis {
  std::vector<HomologyGenerator> generators;  ///< γ_1 … γ_n
  std::vector<DualCycle> dual_cycles;         ///< γ_1* … γ_n*, γ_j* crosses γ_j once from its left to its right
  /// n by #F complex, the period operator: b_j(X) = Σ_t Re(conj(D_jt) X_t), D_jt the displacement between the
  /// midpoints of the edges through which γ_j* enters and leaves t, in t's basis.
  Eigen::SparseMatrix<Complex> period_operator;
  int size() const { return static_cast<int>(generators.size()); }  ///< \pre none
};

/// Generators and dual cycles of the cut graph `graph` of `mesh` (deterministic: connecting paths are chosen
/// shortest first). O(n · size()).
/// \pre graph = cut_graph(mesh, …).
HomologyBasis homology_basis(const Mesh& mesh, const CutGraph& graph);

/// Periods b_j(X) along the dual cycles (Def. 1.14), #generators. Meaningful for fields with curl* = 0 on the
/// interior edges (Lemma 1.13); zero for gradients (Corollary 1.15). \throw InputError if X.size() != #F.
Eigen::VectorXd periods(const HomologyBasis& basis, const VectorField& X);

}  // namespace quadcover
