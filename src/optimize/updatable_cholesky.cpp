#include "optimize/updatable_cholesky.h"

#include <cs.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "calculus/sparse_cholesky.h"
#include "common/errors.h"

namespace quadcover {

std::pair<std::vector<SparseEntry>, std::vector<SparseEntry>> deng_split(const StarChange& change) {
  double lambda2 = 0;
  for (const auto& e : change.d) lambda2 += std::norm(e.value);
  if (lambda2 == 0) return {};
  const double lambda = std::sqrt(lambda2);  // eigenvalues ±λ (6.2.1)
  const double s = std::sqrt(lambda / 2);
  std::vector<SparseEntry> w1{{change.k, s}}, w2{{change.k, s}};
  for (const auto& e : change.d) {
    const Complex u = std::conj(e.value) / lambda;  // u_j = conj(d_kj)/λ
    w1.push_back({e.index, s * u});
    w2.push_back({e.index, -s * u});
  }
  return {std::move(w1), std::move(w2)};
}

namespace {
// Below this size AMD's paths are short enough that METIS's ordering time would not pay back.
constexpr int kNestedDissectionMinSize = 1000;

/// The upper triangle of P A Pᵀ for pinv (pinv[old] = new; empty: P = I), from the upper triangle of A (upper or full
/// storage): all that CXSparse's and CHOLMOD's Cholesky factorizations read of a Hermitian matrix.
Eigen::SparseMatrix<Complex> permuted_upper(const Eigen::SparseMatrix<Complex>& A, const std::vector<int>& pinv) {
  const auto to = [&](int i) { return pinv.empty() ? i : pinv[static_cast<std::size_t>(i)]; };
  std::vector<Eigen::Triplet<Complex>> t;
  t.reserve(static_cast<std::size_t>(A.nonZeros() + A.rows()) / 2);
  for (int j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<Complex>::InnerIterator it(A, j); it; ++it) {
      const int r = static_cast<int>(it.row());
      if (r > j) continue;
      if (to(r) <= to(j))
        t.emplace_back(to(r), to(j), it.value());
      else
        t.emplace_back(to(j), to(r), std::conj(it.value()));
    }
  Eigen::SparseMatrix<Complex> out(A.rows(), A.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// Σ c_j² / nnz(L) above which the supernodal route is faster (bunny_20k 51 and armadillo_86k 61: CXSparse 1.5-2×
// faster; a 100k-face torus 223: CHOLMOD 2.5× faster).
constexpr double kSupernodalFlopsPerEntry = 128;
}  // namespace

struct UpdatableCholesky::Impl {
  cs_cis* S = nullptr;
  cs_cin* N = nullptr;  // CXSparse's factor (fallback), or null when `own` holds it
  ColumnFactor own;     // the factor from factor_in_given_order() (CHOLMOD's arrays)
  cs_ci view{};         // CXSparse's view of `own`
  ~Impl() {
    cs_ci_nfree(N);
    cs_ci_sfree(S);
  }
  cs_ci* L() { return N ? N->L : &view; }
  const cs_ci* L() const { return N ? N->L : &view; }
};

UpdatableCholesky::UpdatableCholesky() = default;
UpdatableCholesky::~UpdatableCholesky() = default;
UpdatableCholesky::UpdatableCholesky(UpdatableCholesky&&) noexcept = default;
UpdatableCholesky& UpdatableCholesky::operator=(UpdatableCholesky&&) noexcept = default;

std::vector<int> UpdatableCholesky::order_ahead(const Eigen::SparseMatrix<Complex>& A) {
  return nested_dissection_ordering(A, kNestedDissectionMinSize);
}

UpdatableCholesky::UpdatableCholesky(Eigen::SparseMatrix<Complex> A, Route route) : impl_(std::make_unique<Impl>()) {
  if (A.rows() != A.cols()) throw NumericalError("cholesky", "matrix is not square");
  A.makeCompressed();
  const int n = static_cast<int>(A.rows());
  // Nested dissection (METIS) where CHOLMOD is compiled in: the etree paths every update walks are shorter than
  // with AMD (calculus/sparse_cholesky.h). CXSparse then analyses P A Pᵀ in its natural order. Both factorizations
  // read only the upper triangle: A is freed once it is kept (half of it, permuted), before the factor is made.
  perm_ = nested_dissection_ordering(A, kNestedDissectionMinSize);
  const bool given = !perm_.empty();
  if (given) {
    pinv_.resize(n);
    for (int i = 0; i < n; ++i) pinv_[perm_[i]] = i;
  } else {  // AMD on the pattern of A + Aᵀ
    cs_ci full{static_cast<int>(A.nonZeros()), n, n, A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), -1};
    impl_->S = cs_ci_schol(1, &full);
  }
  Eigen::SparseMatrix<Complex> upper = permuted_upper(A, pinv_);  // P A Pᵀ, or A until CXSparse applies AMD's P
  A = Eigen::SparseMatrix<Complex>();
  cs_ci view{
      static_cast<int>(upper.nonZeros()), n, n, upper.outerIndexPtr(), upper.innerIndexPtr(), upper.valuePtr(), -1};
  if (given) impl_->S = cs_ci_schol(0, &view);
  if (!impl_->S) throw NumericalError("cholesky", "symbolic analysis failed (n = " + std::to_string(n) + ")");
  if (!given) {
    pinv_.assign(impl_->S->pinv, impl_->S->pinv + n);
    perm_.resize(n);
    for (int i = 0; i < n; ++i) perm_[pinv_[i]] = i;
  }
  // The numbers: CXSparse's up-looking factorization costs Σ_j c_j² (c_j = column counts of L); when that is large
  // per entry of L (big fronts, e.g. long thin meshes), CHOLMOD's supernodal one (BLAS-3) on the same permutation
  // and exact pattern pays for its conversions (BENCHMARKS.md, "Stage profile"). Both compute the unique Cholesky
  // factor of P A Pᵀ (equal up to round-off); the choice depends only on the pattern.
  double flops = 0;
  for (int j = 0; j < n; ++j) flops += std::pow(static_cast<double>(impl_->S->cp[j + 1] - impl_->S->cp[j]), 2.0);
  const bool supernodal = route == Route::Supernodal ||
                          (route == Route::Automatic && flops >= kSupernodalFlopsPerEntry * std::max(1, impl_->S->cp[n]));
  ColumnFactor& cf = impl_->own;
  if (supernodal && factor_in_given_order(given ? upper : permuted_upper(upper, pinv_), cf) &&
      std::equal(cf.p, cf.p + n + 1, impl_->S->cp)) {
    impl_->view = cs_ci{static_cast<int>(cf.nonzeros()), n, n, cf.p, cf.i, cf.x, -1};
  } else {
    cf = ColumnFactor{};
    impl_->N = cs_ci_chol(&view, impl_->S);
    if (!impl_->N)
      throw NumericalError("cholesky", "matrix is not positive definite (n = " + std::to_string(n) + ")");
  }
  parent_.assign(impl_->S->parent, impl_->S->parent + n);
  columns_ = LowerColumns<Complex>::compressed(n, col_ptr(), row_idx(), values());
  split_ = split_substitution(columns_, kSplitSubstitutionMinColumns);
  if (split_.empty()) columns_ = {};  // read by the split forward solve only
  b_ = Eigen::VectorXcd::Zero(n);
  x_ = Eigen::VectorXcd::Zero(n);
  x_norm2_ = 0;
}

bool UpdatableCholesky::supernodal() const { return impl_ && !impl_->N; }
int UpdatableCholesky::size() const { return static_cast<int>(perm_.size()); }
long UpdatableCholesky::factor_nonzeros() const { return impl_ ? impl_->L()->p[impl_->L()->n] : 0; }
const int* UpdatableCholesky::col_ptr() const { return impl_->L()->p; }
const int* UpdatableCholesky::row_idx() const { return impl_->L()->i; }
Complex* UpdatableCholesky::values() { return impl_->L()->x; }
const Complex* UpdatableCholesky::values() const { return impl_->L()->x; }

void UpdatableCholesky::full_forward_solve() {
  x_ = b_;
  cs_ci_lsolve(impl_->L(), x_.data());  // L x = P b
  x_norm2_ = x_.squaredNorm();
}

void UpdatableCholesky::set_rhs(const Eigen::VectorXcd& b) {
  if (b.size() != size()) throw NumericalError("cholesky", "right-hand side has the wrong size");
  for (int i = 0; i < size(); ++i) b_[i] = b[perm_[i]];
  full_forward_solve();
}

Eigen::VectorXcd UpdatableCholesky::solve_full() const {
  Eigen::VectorXcd y = x_;
  cs_ci_ltsolve(impl_->L(), y.data());  // Lᴴ y = x
  Eigen::VectorXcd out(size());
  for (int i = 0; i < size(); ++i) out[perm_[i]] = y[i];
  return out;
}

void UpdatableCholesky::rank1_cxsparse(std::span<const SparseEntry> w, int sigma) {
  std::vector<std::pair<int, Complex>> entries;
  for (const auto& e : w) entries.emplace_back(pinv_[e.index], e.value);
  std::sort(entries.begin(), entries.end(), [](auto& a, auto& b) { return a.first < b.first; });
  std::vector<int> Cp{0, static_cast<int>(entries.size())}, Ci;
  std::vector<Complex> Cx;
  for (auto& [i, v] : entries) Ci.push_back(i), Cx.push_back(v);
  cs_ci C{};
  C.nzmax = std::max(1, Cp[1]);
  C.m = size();
  C.n = 1;
  C.p = Cp.data();
  C.i = Ci.data();
  C.x = Cx.data();
  C.nz = -1;
  if (Cp[1] > 0 && !cs_ci_updown(impl_->L(), sigma, &C, parent_.data()))
    throw NumericalError("cholesky update",
                         "rank-1 " + std::string(sigma > 0 ? "update" : "downdate") + " lost positive definiteness");
  full_forward_solve();
}

void UpdatableCholesky::apply_star_change_cxsparse(const StarChange& change) {
  auto [w1, w2] = deng_split(change);
  if (w1.empty()) return;
  rank1_cxsparse(w1, +1);  // positive eigenvalue first (Deng)
  rank1_cxsparse(w2, -1);
}

Eigen::SparseMatrix<Complex> UpdatableCholesky::factor() const {
  const cs_ci* L = impl_->L();
  std::vector<Eigen::Triplet<Complex>> t;
  t.reserve(L->p[L->n]);
  for (int j = 0; j < L->n; ++j)
    for (int p = L->p[j]; p < L->p[j + 1]; ++p) t.emplace_back(L->i[p], j, L->x[p]);
  Eigen::SparseMatrix<Complex> out(L->n, L->n);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

// ---------------------------------------------------------------------------------------------------------------

FactorTrial::FactorTrial(int n) : slot_(n, -1), w_(n), acc_(n), db_(n), xnew_(n) {}

void FactorTrial::reset() {
  for (int j : touched_) {
    slot_[j] = -1;
    w_[j] = acc_[j] = db_[j] = xnew_[j] = 0.0;
  }
  touched_.clear();
  vals_.clear();
  valid_ = true;
  evaluated_ = false;
  full_ = false;
}

void FactorTrial::touch_path(const UpdatableCholesky& F, int j) {
  if (static_cast<int>(slot_.size()) != F.size()) {
    *this = FactorTrial(F.size());
  }
  const int* Lp = F.col_ptr();
  const Complex* Lx = F.values();
  // The etree path j -> root; once a touched column is met, all its ancestors are touched already.
  for (; j != -1 && slot_[j] < 0; j = F.etree()[j]) {
    slot_[j] = static_cast<int>(vals_.size());
    vals_.insert(vals_.end(), Lx + Lp[j], Lx + Lp[j + 1]);
    touched_.push_back(j);
  }
}

// L̃L̃ᴴ = LLᴴ + σ w wᴴ column by column along the etree path from the first nonzero of w. With α = w_j / L_jj and
// d = 1 + σ|α|²: L̃_jj = L_jj √d, L̃_ij = (L_ij + σ ᾱ w_i)/√d, w_i <- w_i - α L_ij (old L_ij), σ <- σ/d.
// (Elimination of column j leaves the Schur complement update σ/d · w̄w̄ᴴ; derived from A₂₂ - l̃l̃ᴴ.)
bool FactorTrial::rank1(const UpdatableCholesky& F, const std::vector<SparseEntry>& w, double sigma) {
  const auto& pinv = F.inverse_perm();
  int f = F.size();
  for (const auto& e : w) {
    const int j = pinv[e.index];
    touch_path(F, j);
    w_[j] += e.value;
    f = std::min(f, j);
  }
  const int* Lp = F.col_ptr();
  const int* Li = F.row_idx();
  double s = sigma;
  for (int j = f; j != -1; j = F.etree()[j]) {
    Complex* col = vals_.data() + slot_[j];
    const int len = Lp[j + 1] - Lp[j];
    const double c = col[0].real();
    const Complex alpha = w_[j] / c;
    w_[j] = 0.0;
    if (alpha == 0.0) continue;  // nothing to propagate from this column
    const double d = 1.0 + s * std::norm(alpha);
    if (!(d > 0)) {
      valid_ = false;
      return false;
    }
    const double sd = std::sqrt(d);
    col[0] = c * sd;
    const Complex sa = s * std::conj(alpha);
    const int* rows = Li + Lp[j];
    const double inv_sd = 1.0 / sd;
    for (int p = 1; p < len; ++p) {  // in real arithmetic: no NaN branches of std::complex's product, no division
      const double lr = col[p].real(), li = col[p].imag();
      Complex& wi = w_[rows[p]];
      const double wr = wi.real(), wim = wi.imag();
      col[p] = Complex((lr + (sa.real() * wr - sa.imag() * wim)) * inv_sd,
                       (li + (sa.real() * wim + sa.imag() * wr)) * inv_sd);
      wi = Complex(wr - (alpha.real() * lr - alpha.imag() * li), wim - (alpha.real() * li + alpha.imag() * lr));
    }
    s /= d;
  }
  // Every entry of w must have been consumed on the path: otherwise wwᴴ leaves the pattern of L.
  for (const auto& e : w)
    if (w_[pinv[e.index]] != 0.0) {
      w_[pinv[e.index]] = 0.0;
      valid_ = false;
    }
  return valid_;
}

bool FactorTrial::add_star_change(const UpdatableCholesky& F, const StarChange& change) {
  if (!valid_) return false;
  auto [w1, w2] = deng_split(change);
  if (w1.empty()) return true;
  evaluated_ = false;
  return rank1(F, w1, +1.0) && rank1(F, w2, -1.0);  // decreasing eigenvalue order (Deng)
}

void FactorTrial::add_rhs_change(const UpdatableCholesky& F, std::span<const SparseEntry> delta) {
  for (const auto& e : delta) {
    const int j = F.inverse_perm()[e.index];
    touch_path(F, j);
    db_[j] += e.value;
  }
  evaluated_ = false;
}

// Columns outside the touched set T are unchanged and T is closed under etree ancestors, so x_j is unchanged for
// j ∉ T. For j ∈ T: L̃_jj x̃_j = b̃_j - Σ_{i∉T} L_ji x_i - Σ_{i∈T,i<j} L̃_ji x̃_i, and the first sum equals
// b_j - L_jj x_j - Σ_{i∈T,i<j} L_ji x_i (old values), so only columns in T are read.
double FactorTrial::evaluate(const UpdatableCholesky& F) {
  if (!valid_) throw NumericalError("cholesky update", "trial evaluated after a failed update");
  std::vector<int> order = touched_;
  std::sort(order.begin(), order.end());
  const int* Lp = F.col_ptr();
  const int* Li = F.row_idx();
  const Complex* Lx = F.values();
  const Complex* x = F.forward_solution().data();
  double delta = 0;
  for (int j : order) {
    const Complex* old = Lx + Lp[j];
    const Complex* nw = vals_.data() + slot_[j];
    const int len = Lp[j + 1] - Lp[j];
    const Complex xo = x[j];
    const Complex xn = (db_[j] + old[0] * xo + acc_[j]) / nw[0].real();
    xnew_[j] = xn;
    const int* rows = Li + Lp[j];
    for (int p = 1; p < len; ++p) acc_[rows[p]] += old[p] * xo - nw[p] * xn;
    delta += std::norm(xn) - std::norm(xo);
  }
  for (int j : order) acc_[j] = 0.0;
  energy_ = F.rhs_energy() + delta;
  evaluated_ = true;
  return energy_;
}

double FactorTrial::evaluate_full(const UpdatableCholesky& F, const Eigen::VectorXcd& b_new) {
  if (!valid_) throw NumericalError("cholesky update", "trial evaluated after a failed update");
  const int n = F.size();
  const int* Lp = F.col_ptr();
  const int* Li = F.row_idx();
  const Complex* Lx = F.values();
  bfull_.resize(n);
  for (int i = 0; i < n; ++i) bfull_[i] = b_new[F.perm()[i]];
  xfull_ = bfull_;
  Complex* x = xfull_.data();
  const auto column_values = [&](int j) { return slot_[j] >= 0 ? vals_.data() + slot_[j] : Lx + Lp[j]; };
  if (!F.substitution_split().empty()) {
    forward_substitute_split(F.columns_, F.substitution_split(), column_values, x);
  } else {
    for (int j = 0; j < n; ++j) {
      const Complex* col = column_values(j);
      const Complex xj = x[j] /= col[0].real();
      for (int p = Lp[j] + 1; p < Lp[j + 1]; ++p) x[Li[p]] -= product(col[p - Lp[j]], xj);
    }
  }
  energy_ = xfull_.squaredNorm();
  evaluated_ = full_ = true;
  return energy_;
}

void FactorTrial::commit(UpdatableCholesky& F) const {
  if (!valid_ || !evaluated_) throw NumericalError("cholesky update", "commit of an invalid or unevaluated trial");
  const int* Lp = F.col_ptr();
  Complex* Lx = F.values();
  for (int j : touched_) {
    std::copy(vals_.begin() + slot_[j], vals_.begin() + slot_[j] + (Lp[j + 1] - Lp[j]), Lx + Lp[j]);
    if (!full_) {
      F.x_[j] = xnew_[j];
      F.b_[j] += db_[j];
    }
  }
  if (full_) F.x_ = xfull_, F.b_ = bfull_;
  F.x_norm2_ = F.x_.squaredNorm();
}

}  // namespace quadcover
