// Even branch point fix-up over the rotated lattice (thesis 4.2.2): a GF(2) system on the path parities.
#include "param/even_branch_fix.h"

#include <cmath>

#include "common/quarter_turn.h"
#include "param/disk_functions.h"
#include "param/lattice.h"

namespace quadcover {

bool solve_gf2(std::vector<std::vector<std::uint64_t>> A, std::vector<char> r, int ncols, std::vector<char>& x) {
  const int nrows = static_cast<int>(A.size());
  std::vector<int> pivot_col(static_cast<std::size_t>(nrows), -1);
  int row = 0;
  for (int col = 0; col < ncols && row < nrows; ++col) {
    const std::size_t w = static_cast<std::size_t>(col) / 64;
    const std::uint64_t bit = std::uint64_t{1} << (col % 64);
    int p = row;
    while (p < nrows && !(A[p][w] & bit)) ++p;
    if (p == nrows) continue;
    std::swap(A[p], A[row]);
    std::swap(r[p], r[row]);
    for (int q = 0; q < nrows; ++q)
      if (q != row && (A[q][w] & bit)) {
        for (std::size_t k = 0; k < A[q].size(); ++k) A[q][k] ^= A[row][k];
        r[q] ^= r[row];
      }
    pivot_col[row] = col;
    ++row;
  }
  bool ok = true;
  x.assign(static_cast<std::size_t>(ncols), 0);
  for (int q = 0; q < nrows; ++q) {
    if (pivot_col[q] >= 0)
      x[pivot_col[q]] = r[q];
    else if (r[q])
      ok = false;
  }
  return ok;
}

std::vector<int> fix_even_branch_points(const Mesh& mesh, const CoverCut& cc, std::vector<Complex>& rounded,
                                        const std::function<double(int path)>& price) {
  const int n = cc.num_paths(), ne = mesh.num_edges(), nv = mesh.num_vertices();
  Eigen::VectorXcd cr = Eigen::VectorXcd::Zero(ne);
  for (int j = 0; j < n; ++j) cr[cc.path_edge[j]] = rounded[j];
  complete_translations(mesh, cc, cr);
  const auto bits = path_parities(mesh, cc);
  std::vector<int> evens;
  std::vector<std::vector<std::uint64_t>> A;
  std::vector<char> r;
  for (int q = 0; q < nv; ++q) {
    if (!cc.branch[q] || mod4(cc.quarter_index[q]) != 2) continue;
    std::vector<std::uint64_t> row(bits.empty() ? 0 : bits[0].size(), 0);
    for (const FanCrossing& x : fan_crossings(mesh, q))
      if (cc.graph.cut[x.edge])
        for (std::size_t w = 0; w < row.size(); ++w) row[w] ^= bits[x.edge][w];
    evens.push_back(q);
    A.push_back(row);
    r.push_back(distance_to_gaussian_integers(branch_point_image(mesh, cc, cr, q)) > 0.25 ? 1 : 0);
  }
  std::vector<char> x;
  const bool ok = solve_gf2(A, r, n, x);
  for (int j = 0; j < n; ++j) {
    if (!x[j]) continue;
    // The parity step ±(1±i) with the smallest price.
    Complex best = 0;
    double best_d = INFINITY;
    for (const Complex delta : {Complex(1, 1), Complex(-1, -1), Complex(1, -1), Complex(-1, 1)}) {
      rounded[j] += delta;
      const double d = price(j);
      rounded[j] -= delta;
      if (d < best_d) best_d = d, best = delta;
    }
    rounded[j] += best;
  }
  std::vector<int> unfixed;
  if (!ok) {  // the even points that stay at half-integers
    for (int j = 0; j < n; ++j) cr[cc.path_edge[j]] = rounded[j];
    complete_translations(mesh, cc, cr);
    for (int q : evens)
      if (distance_to_gaussian_integers(branch_point_image(mesh, cc, cr, q)) > 0.25) unfixed.push_back(q);
  }
  return unfixed;
}

}  // namespace quadcover
