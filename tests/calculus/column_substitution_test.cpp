// Column-wise triangular solves (calculus/column_substitution.h) on the Cholesky factor of a real mesh's Laplacian:
// the split of the back substitution covers every column once, keeps each part's columns reading only their part
// and the top, and gives the numbers of one pass; a chain (no two subtrees) is not split; the forward substitution
// from a sparse right-hand side is the full one.
#include "calculus/column_substitution.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <vector>

#include "calculus/stiffness.h"
#include "calculus_test_util.h"

namespace quadcover {
namespace {

using testing::cached_mesh;
using testing::random_vector;

using Factor = Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;

LowerColumns<double> columns_of(const Factor& factor) {
  const Eigen::SparseMatrix<double>& L = factor.matrixL().nestedExpression();
  return LowerColumns<double>::compressed(static_cast<int>(L.cols()), L.outerIndexPtr(), L.innerIndexPtr(),
                                          L.valuePtr());
}

// 𝔏 + diag(vertex areas): positive definite with the pattern of the mesh's vertex graph.
Eigen::SparseMatrix<double> laplacian_plus_mass(const Mesh& mesh) {
  Eigen::SparseMatrix<double> A = conforming_stiffness(mesh);
  const Eigen::VectorXd a = vertex_areas(mesh);
  for (int p = 0; p < mesh.num_vertices(); ++p) A.coeffRef(p, p) += a[p];
  return A;
}

TEST(ColumnSubstitution, SplitBackSubstitutionGivesTheNumbersOfOnePass) {
  const Factor factor(laplacian_plus_mass(cached_mesh("fertility_genus4")));
  ASSERT_EQ(factor.info(), Eigen::Success);
  const LowerColumns<double> L = columns_of(factor);
  const SubstitutionSplit split = split_substitution(L, 0);
  ASSERT_FALSE(split.empty());
  std::vector<int> part_of(static_cast<std::size_t>(L.size()), -2);
  long entries[2] = {0, 0};
  for (const int j : split.top) part_of[j] = -1;
  for (int part = 0; part < 2; ++part) {
    EXPECT_TRUE(std::is_sorted(split.part[part].rbegin(), split.part[part].rend()));
    for (const int j : split.part[part]) {
      ASSERT_EQ(part_of[j], -2) << "column " << j << " twice";
      part_of[j] = part;
      entries[part] += L.length[j];
    }
  }
  EXPECT_EQ(std::count(part_of.begin(), part_of.end(), -2), 0);  // every column once
  long top_entries = 0;
  for (const int j : split.top) top_entries += L.length[j];
  EXPECT_LT(3 * top_entries, entries[0] + entries[1] + top_entries);  // AMD's last clique on top: about a sixth here
  EXPECT_GT(3 * std::min(entries[0], entries[1]), std::max(entries[0], entries[1]));  // about balanced
  for (int j = 0; j < L.size(); ++j)
    for (int q = 1; q < L.length[j]; ++q) {
      const int row = L.rows[j][q];
      EXPECT_TRUE(part_of[row] == -1 || part_of[row] == part_of[j]) << "column " << j << ", row " << row;
    }
  Eigen::VectorXd one_pass = random_vector(L.size(), 5), split_pass = one_pass;
  back_substitute(L, SubstitutionSplit{}, one_pass.data());
  back_substitute(L, split, split_pass.data());
  EXPECT_EQ(split_pass, one_pass);                           // bitwise: each column's arithmetic is the same
  EXPECT_TRUE(split_substitution(L, L.size() + 1).empty());  // below the size it is made for
}

// The forward substitution on two cores: the numbers of one pass up to round-off, bitwise the same on one thread
// and on two, and columns swapped in through `values` are the ones used.
TEST(ColumnSubstitution, ForwardSubstitutionSplitIsOnePassUpToRoundOffWhateverTheThreads) {
  const Factor factor(laplacian_plus_mass(cached_mesh("fertility_genus4")));
  const LowerColumns<double> L = columns_of(factor);
  const SubstitutionSplit split = split_substitution(L, 0);
  ASSERT_FALSE(split.empty());
  ASSERT_EQ(split.top_position.size(), static_cast<std::size_t>(L.size()));
  for (std::size_t t = 0; t < split.top.size(); ++t) EXPECT_EQ(split.top_position[split.top[t]], static_cast<int>(t));
  const Eigen::VectorXd b = random_vector(L.size(), 8);
  Eigen::VectorXd one_pass = b;
  forward_substitute(L, 0, one_pass.data());
  const auto own = [&](int j) { return L.values[j]; };
  Eigen::VectorXd two_cores = b, one_thread = b;
  forward_substitute_split(L, split, own, two_cores.data());
  tbb::task_arena(1).execute([&] { forward_substitute_split(L, split, own, one_thread.data()); });
  EXPECT_LT((two_cores - one_pass).norm(), 1e-13 * one_pass.norm());
  EXPECT_EQ(two_cores, one_thread);
  // A column scaled by 2 swapped in: the solution's entry there halves (its diagonal doubled, the rest follows).
  const int j = split.part[0].back();
  std::vector<double> doubled(L.values[j], L.values[j] + L.length[j]);
  for (double& v : doubled) v *= 2;
  Eigen::VectorXd swapped = b;
  forward_substitute_split(
      L, split, [&](int c) { return c == j ? doubled.data() : L.values[c]; }, swapped.data());
  EXPECT_NEAR(swapped[j], 0.5 * two_cores[j], 1e-12 * std::abs(two_cores[j]));
  EXPECT_GT((swapped - two_cores).norm(), 0.0);
}

TEST(ColumnSubstitution, AChainIsNotSplit) {
  const int n = 500;
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < n; ++k) {
    t.emplace_back(k, k, 3.0);
    if (k + 1 < n) t.emplace_back(k + 1, k, -1.0), t.emplace_back(k, k + 1, -1.0);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const Factor factor(A);
  const LowerColumns<double> L = columns_of(factor);
  const SubstitutionSplit split = split_substitution(L, 0);
  EXPECT_TRUE(split.empty());  // a path: every subtree but one leaf holds more than half of the rest
}

TEST(ColumnSubstitution, ForwardSubstitutionFromASparseRightHandSideIsTheFullOne) {
  const Factor factor(laplacian_plus_mass(cached_mesh("bunny_3k")));
  const LowerColumns<double> L = columns_of(factor);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(L.size());
  b[L.size() / 3] = 2.0, b[L.size() / 2] = -1.0;
  const Eigen::VectorXd full = factor.matrixL().solve(b);
  Eigen::VectorXd sparse = b;
  forward_substitute(L, L.size() / 3, sparse.data());
  EXPECT_LT((sparse - full).norm(), 1e-14 * full.norm());
  EXPECT_GT(std::count(sparse.data(), sparse.data() + L.size(), 0.0),
            L.size() / 2);  // a path's worth of columns reached
}

}  // namespace
}  // namespace quadcover
