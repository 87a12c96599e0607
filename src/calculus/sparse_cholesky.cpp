// Sparse Cholesky backends: CHOLMOD (supernodal) and Eigen::SimplicialLLT. See sparse_cholesky.h.
#include "calculus/sparse_cholesky.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>

#include "calculus/column_substitution.h"
#include "common/errors.h"

#ifdef QUADCOVER_HAVE_CHOLMOD
#include <cholmod.h>
#include <dlfcn.h>
#endif

#ifdef QUADCOVER_HAVE_CHOLMOD
namespace {
std::atomic<long long> regions_in_place{0};
}  // namespace

// CHOLMOD opens several OpenMP regions per supernode. libgomp sets up a team even for a region of one thread
// (max-active-levels 0, single_threaded_libraries below) and ends it at a barrier that makes a futex system call
// every time: 40 % of the wall time of a bunny_20k_holes `param` on a paravirtualized VM (BENCHMARKS.md, "OpenMP
// regions run in place"). This definition takes libgomp's place for the program it is linked into (GCC's ABI
// since 4.9): the region runs at once on the calling thread, as a team of one would (outside a team,
// omp_get_num_threads() is 1 and worksharing constructs are a team of one). quadcover has no OpenMP code itself.
extern "C" __attribute__((visibility("default"), used)) void GOMP_parallel(void (*region)(void*), void* data,
                                                                           unsigned /*num_threads*/,
                                                                           unsigned /*flags*/) {
  regions_in_place.fetch_add(1, std::memory_order_relaxed);
  region(data);
}
#endif

namespace quadcover {

long long openmp_regions_run_in_place() {
#ifdef QUADCOVER_HAVE_CHOLMOD
  return regions_in_place.load(std::memory_order_relaxed);
#else
  return 0;
#endif
}

namespace {

template <class Scalar>
constexpr bool kIsComplex = !std::is_same_v<Scalar, double>;

#ifdef QUADCOVER_HAVE_CHOLMOD
// METIS keeps its random state in globals of GKlib (seeded at the start of each ordering): two orderings at once on
// two threads disturb each other and come out different from run to run. Every CHOLMOD analysis that may call
// METIS (ours always, CHOLMOD's default choice when AMD fills too much) holds this lock.
std::mutex& metis_mutex() {
  static std::mutex m;
  return m;
}

/// CHOLMOD's view of the Hermitian `m` as `xtype`, of which CHOLMOD reads the lower triangle (stype −1) or the upper
/// one (stype 1; the other is its conjugate transpose).
template <class Scalar>
cholmod_sparse triangle_view(const Eigen::SparseMatrix<Scalar>& m, int xtype, int stype = -1) {
  cholmod_sparse A{};
  A.nrow = static_cast<size_t>(m.rows());
  A.ncol = static_cast<size_t>(m.cols());
  A.nzmax = static_cast<size_t>(m.nonZeros());
  A.p = const_cast<int*>(m.outerIndexPtr());
  A.i = const_cast<int*>(m.innerIndexPtr());
  A.x = xtype == CHOLMOD_PATTERN ? nullptr : const_cast<Scalar*>(m.valuePtr());
  A.stype = stype;
  A.itype = CHOLMOD_INT;
  A.xtype = xtype;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

// CHOLMOD's supernodal factorization calls the system BLAS. When that is a threaded OpenBLAS (Debian's
// libopenblas0-pthread, scripts/setup.sh), its own threads would compete with our TBB loops for the cores and
// make results depend on the machine: keep BLAS single-threaded. Debian's CHOLMOD also opens OpenMP regions of a
// fixed 4 threads (CHOLMOD_OMP_NUM_THREADS, which OMP_NUM_THREADS does not change) in every supernodal
// factorization: on 2 cores and beside our TBB threads they spent a quarter of a camelhead_boundary remesh waiting
// on each other (BENCHMARKS.md, "OpenMP threads of CHOLMOD"). max-active-levels 0 runs every OpenMP region on the
// calling thread. Both are found at run time (no-ops for another BLAS or a CHOLMOD without OpenMP). Called on the
// thread that factors, before each CHOLMOD factorization (the OpenMP setting belongs to the calling thread; solves
// come after a factorization).
void single_threaded_libraries() {
  using SetThreads = void (*)(int);
  static std::once_flag once;
  static SetThreads set_max_active_levels = nullptr;
  std::call_once(once, [] {
    if (void* f = dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) reinterpret_cast<SetThreads>(f)(1);
    set_max_active_levels = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  });
  thread_local bool done = false;
  if (!done && set_max_active_levels) set_max_active_levels(0);
  done = true;
}
#endif

#ifdef QUADCOVER_HAVE_CHOLMOD
/// How an ordering was made: METIS's nested dissection (nested_dissection_ordering) or CHOLMOD's own choice.
enum class OrderingKind { NestedDissection, CholmodChoice };

/// A lower-triangle pattern's fingerprint: size, entries, and a 64-bit hash of its column starts and rows.
struct PatternKey {
  OrderingKind kind{};
  long n = 0, nonzeros = 0;
  std::uint64_t hash = 0;
  bool operator==(const PatternKey&) const = default;
};

template <class Scalar>
PatternKey pattern_key(OrderingKind kind, const Eigen::SparseMatrix<Scalar>& lower) {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  const auto mix = [&h](std::uint64_t v) { h = (h ^ v) * 0x100000001b3ULL + (h >> 29); };
  for (Eigen::Index j = 0; j <= lower.cols(); ++j) mix(static_cast<std::uint64_t>(lower.outerIndexPtr()[j]));
  for (Eigen::Index k = 0; k < lower.nonZeros(); ++k) mix(static_cast<std::uint64_t>(lower.innerIndexPtr()[k]));
  return {kind, static_cast<long>(lower.rows()), static_cast<long>(lower.nonZeros()), h};
}

/// The orderings of the last few large patterns, newest last: a job factors matrices of one pattern again and again
/// (every remake of the map on the same mesh), and orders each pattern once. An ordering is a function of the
/// pattern, so a kept one gives the same factor as a new one. A hash collision could only hand over another valid
/// permutation of the same size: more fill, never a wrong factor.
class KeptOrderings {
 public:
  std::vector<int> find(const PatternKey& key) const {  ///< empty if not kept
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [k, perm] : kept_)
      if (k == key) return perm;
    return {};
  }
  void keep(const PatternKey& key, std::vector<int> perm) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (kept_.size() == kKept) kept_.erase(kept_.begin());
    kept_.emplace_back(key, std::move(perm));
  }

 private:
  static constexpr std::size_t kKept = 6;
  mutable std::mutex mutex_;
  std::vector<std::pair<PatternKey, std::vector<int>>> kept_;
};

/// One store per kind: the refined meshes of the fold refinement bring new patterns that would push out the
/// nested dissection of the mesh the remakes come back to.
KeptOrderings& kept_orderings(OrderingKind kind) {
  static KeptOrderings nested_dissection, cholmod_choice;
  return kind == OrderingKind::NestedDissection ? nested_dissection : cholmod_choice;
}

/// Matrices with fewer rows are analysed anew each time (the untangling's many small regions would only push the
/// large patterns out).
constexpr Eigen::Index kKeptChoiceRows = 10000;

/// A cholmod_common for one solve: CHOLMOD keeps workspace and status in it, and only reads the factor.
struct SolveCommon {
  cholmod_common common;
  SolveCommon() {
    cholmod_start(&common);
    common.print = 0;
  }
  ~SolveCommon() { cholmod_finish(&common); }
  SolveCommon(const SolveCommon&) = delete;
  SolveCommon& operator=(const SolveCommon&) = delete;
};

// CHOLMOD state: one cholmod_common for the analysis and factorization (each solve has its own, so solves with the
// factor may run at once), the factor L, and a copy of the lower triangle it was computed from.
template <class Scalar>
class CholmodBackend {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar>;
  using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  CholmodBackend() {
    cholmod_start(&common_);
    common_.supernodal = CHOLMOD_SUPERNODAL;  // supernodal LLᴴ (BLAS-3)
    common_.print = 0;                        // the library never prints; failures become NumericalError
  }
  ~CholmodBackend() {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }
  CholmodBackend(const CholmodBackend&) = delete;
  CholmodBackend& operator=(const CholmodBackend&) = delete;

  /// CHOLMOD's choice of ordering (kept for large patterns), or `ordering` (perm[new] = old, checked by the
  /// caller) when not empty.
  void analyze(const Matrix& lower, const std::string& stage, std::span<const int> ordering) {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_sparse A = view(lower);
    const bool keep = ordering.empty() && lower.rows() >= kKeptChoiceRows;
    const PatternKey key = keep ? pattern_key(OrderingKind::CholmodChoice, lower) : PatternKey{};
    std::vector<int> perm =
        keep ? kept_orderings(key.kind).find(key) : std::vector<int>(ordering.begin(), ordering.end());
    const bool choose = perm.empty();
    if (choose) {
      common_.nmethods = 0;  // AMD, and METIS too where AMD fills much
      const std::lock_guard<std::mutex> lock(metis_mutex());
      factor_ = cholmod_analyze(&A, &common_);
    } else {
      common_.nmethods = 1;
      common_.method[0].ordering = CHOLMOD_GIVEN;
      factor_ = cholmod_analyze_p(&A, perm.data(), nullptr, 0, &common_);
    }
    if (!factor_ || common_.status < CHOLMOD_OK)
      throw NumericalError(stage, "CHOLMOD symbolic analysis failed (status " + std::to_string(common_.status) + ")");
    if (keep && choose) {
      const int* chosen = static_cast<const int*>(factor_->Perm);
      kept_orderings(key.kind).keep(key, std::vector<int>(chosen, chosen + lower.rows()));
    }
  }

  void factorize(const Matrix& lower, const std::string& stage) {
    single_threaded_libraries();
    cholmod_sparse A = view(lower);
    const int ok = cholmod_factorize(&A, factor_, &common_);
    if (!ok || common_.status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n)
      throw NumericalError(stage, "matrix of size " + std::to_string(lower.rows()) +
                                      " is not positive definite (CHOLMOD stopped at column " +
                                      std::to_string(factor_->minor) + ")");
    if (common_.status < CHOLMOD_OK)
      throw NumericalError(stage, "CHOLMOD factorization failed (status " + std::to_string(common_.status) + ")");
  }

  /// sys = CHOLMOD_A (full solve), or CHOLMOD_P then CHOLMOD_L for the forward half. B is read in place (CHOLMOD
  /// does not write its input) and the result copied out of CHOLMOD's: besides B, two copies are held at a time.
  Dense solve(const Dense& B, bool forward_only) const {
    single_threaded_libraries();
    SolveCommon local;  // the call's own workspace and status: solves with one factor can run at once
    cholmod_common& common = local.common;
    const auto free_dense = [&common](cholmod_dense* d) { cholmod_free_dense(&d, &common); };
    std::unique_ptr<cholmod_dense, decltype(free_dense)> out(nullptr, free_dense);
    const int systems_full[] = {CHOLMOD_A};
    const int systems_forward[] = {CHOLMOD_P, CHOLMOD_L};
    const int* systems = forward_only ? systems_forward : systems_full;
    const int count = forward_only ? 2 : 1;
    cholmod_dense in = view(const_cast<Dense&>(B));
    for (int s = 0; s < count; ++s) {
      cholmod_dense* next = cholmod_solve(systems[s], factor_, out ? out.get() : &in, &common);
      if (!next)
        throw NumericalError("cholesky", "CHOLMOD solve failed (status " + std::to_string(common.status) + ")");
      out.reset(next);
    }
    return Eigen::Map<const Dense, 0, Eigen::OuterStride<>>(static_cast<const Scalar*>(out->x), B.rows(), B.cols(),
                                                            Eigen::OuterStride<>(static_cast<Eigen::Index>(out->d)));
  }

  /// The factor's columns read in place, no copy: column j of supernode k (columns super[k] .. super[k+1]-1, its rows
  /// s[pi[k] ..], a column-major block at px[k]) starts at its diagonal, row c = j - super[k] of the block.
  /// \throw NumericalError naming `stage` if the factor is not supernodal (compute() always makes it so).
  LowerColumns<Scalar> columns(const std::string& stage) const {
    const int n = static_cast<int>(factor_->n);
    if (!factor_->is_super) throw NumericalError(stage, "the CHOLMOD factor is not supernodal");
    LowerColumns<Scalar> L;
    L.rows.resize(static_cast<std::size_t>(n));
    L.values.resize(static_cast<std::size_t>(n));
    L.length.resize(static_cast<std::size_t>(n));
    const int* super = static_cast<const int*>(factor_->super);
    const int* pi = static_cast<const int*>(factor_->pi);
    const int* px = static_cast<const int*>(factor_->px);
    const int* rows = static_cast<const int*>(factor_->s);
    const Scalar* x = static_cast<const Scalar*>(factor_->x);
    for (std::size_t k = 0; k < factor_->nsuper; ++k) {
      const int height = pi[k + 1] - pi[k];
      for (int j = super[k]; j < super[k + 1]; ++j) {
        const int c = j - super[k];
        L.rows[j] = rows + pi[k] + c;
        L.values[j] = x + px[k] + static_cast<std::ptrdiff_t>(c) * height + c;
        L.length[j] = height - c;
      }
    }
    return L;
  }
  const int* permutation() const { return static_cast<const int*>(factor_->Perm); }  ///< perm[new] = old

 private:
  static int xtype() { return kIsComplex<Scalar> ? CHOLMOD_COMPLEX : CHOLMOD_REAL; }  // interleaved re/im

  // Non-owning views of Eigen storage (column-major, int indices, compressed).
  static cholmod_sparse view(const Matrix& m) { return triangle_view(m, xtype()); }
  static cholmod_dense view(Dense& m) {
    cholmod_dense B{};
    B.nrow = static_cast<size_t>(m.rows());
    B.ncol = static_cast<size_t>(m.cols());
    B.nzmax = static_cast<size_t>(m.size());
    B.d = static_cast<size_t>(m.rows());
    B.x = m.data();
    B.xtype = xtype();
    B.dtype = CHOLMOD_DOUBLE;
    return B;
  }

  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
};
#endif

}  // namespace

template <class Scalar>
struct SparseCholesky<Scalar>::Impl {
  CholeskyBackend backend = CholeskyBackend::Eigen;
  std::string stage = "cholesky";
  Eigen::Index n = -1;  ///< -1 until compute()
  Eigen::Index lower_nnz = 0;
  Eigen::SimplicialLLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> eigen;
#ifdef QUADCOVER_HAVE_CHOLMOD
  std::optional<CholmodBackend<Scalar>> cholmod;
#endif
  /// Set by prepare_sparse_solves(), cleared by every factorization: the factor's columns (read in place), its order
  /// both ways and the split of its back substitution.
  LowerColumns<Scalar> columns;
  std::vector<int> old_of_new, new_of_old;
  SubstitutionSplit substitution_split;

  void check_posdef() const {
    if (eigen.info() != Eigen::Success)
      throw NumericalError(stage, "matrix of size " + std::to_string(n) + " is not positive definite (Eigen LLT)");
  }
};

template <class Scalar>
SparseCholesky<Scalar>::SparseCholesky() : SparseCholesky(CholeskyBackend::Automatic) {}

template <class Scalar>
SparseCholesky<Scalar>::SparseCholesky(CholeskyBackend backend) : impl_(std::make_unique<Impl>()) {
  if (backend == CholeskyBackend::Automatic)
    backend = cholmod_available() ? CholeskyBackend::Cholmod : CholeskyBackend::Eigen;
  if (backend == CholeskyBackend::Cholmod && !cholmod_available())
    throw NumericalError("cholesky", "the CHOLMOD backend was requested but quadcover was built without CHOLMOD");
  impl_->backend = backend;
}

template <class Scalar>
SparseCholesky<Scalar>::~SparseCholesky() = default;
template <class Scalar>
SparseCholesky<Scalar>::SparseCholesky(SparseCholesky&&) noexcept = default;
template <class Scalar>
SparseCholesky<Scalar>& SparseCholesky<Scalar>::operator=(SparseCholesky&&) noexcept = default;

template <class Scalar>
bool SparseCholesky<Scalar>::cholmod_available() {
#ifdef QUADCOVER_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

template <class Scalar>
CholeskyBackend SparseCholesky<Scalar>::backend() const {
  return impl_->backend;
}

namespace {

/// True iff `perm` holds each of 0 .. n-1 once.
bool is_permutation_of(std::span<const int> perm, Eigen::Index n) {
  if (static_cast<Eigen::Index>(perm.size()) != n) return false;
  std::vector<char> seen(perm.size(), 0);
  for (const int k : perm) {
    if (k < 0 || k >= n || seen[k]) return false;
    seen[k] = 1;
  }
  return true;
}

}  // namespace

template <class Scalar>
void SparseCholesky<Scalar>::compute(const Matrix& A, const char* stage, std::span<const int> ordering) {
  Impl& im = *impl_;
  im.stage = stage ? stage : "cholesky";
  if (A.rows() != A.cols())
    throw NumericalError(im.stage,
                         "matrix is " + std::to_string(A.rows()) + " by " + std::to_string(A.cols()) + ", not square");
  if (!ordering.empty() && !is_permutation_of(ordering, A.rows()))
    throw NumericalError(
        im.stage, "the given ordering is not a permutation of the matrix's " + std::to_string(A.rows()) + " rows");
  im.n = -1;
  im.columns = {};
  im.substitution_split = {};
  Matrix lower = A.template triangularView<Eigen::Lower>();
  lower.makeCompressed();
  im.lower_nnz = lower.nonZeros();
  if (A.rows() > 0) {
#ifdef QUADCOVER_HAVE_CHOLMOD
    if (im.backend == CholeskyBackend::Cholmod) {
      im.cholmod.emplace();
      im.cholmod->analyze(lower, im.stage, ordering);
      im.cholmod->factorize(lower, im.stage);
    }
#endif
    if (im.backend == CholeskyBackend::Eigen) {
      im.eigen.compute(lower);
      im.check_posdef();
    }
  }
  im.n = A.rows();
}

template <class Scalar>
void SparseCholesky<Scalar>::refactorize(const Matrix& A) {
  Impl& im = *impl_;
  if (im.n < 0) throw NumericalError(im.stage, "refactorize() called before compute()");
  Matrix lower = A.template triangularView<Eigen::Lower>();
  lower.makeCompressed();
  if (A.rows() != im.n || A.cols() != im.n || lower.nonZeros() != im.lower_nnz)
    throw NumericalError(im.stage, "refactorize(): the sparsity pattern differs from the analyzed one");
  if (im.n == 0) return;
  const Eigen::Index n = im.n;
  im.n = -1;  // a failed refactorization leaves no usable factor
  im.columns = {};
  im.substitution_split = {};
#ifdef QUADCOVER_HAVE_CHOLMOD
  if (im.backend == CholeskyBackend::Cholmod) im.cholmod->factorize(lower, im.stage);
#endif
  if (im.backend == CholeskyBackend::Eigen) {
    im.eigen.factorize(lower);
    im.check_posdef();
  }
  im.n = n;
}

template <class Scalar>
void SparseCholesky<Scalar>::factorize(const Matrix& A, const char* stage, std::span<const int> ordering) {
  if (impl_->n >= 0 && A.rows() == impl_->n && A.cols() == impl_->n) {
    try {
      refactorize(A);
      return;
    } catch (const NumericalError&) {  // another pattern (or not definite: compute() says so with its stage)
    }
  }
  compute(A, stage, ordering);
}

template <class Scalar>
typename SparseCholesky<Scalar>::Dense SparseCholesky<Scalar>::solve(const Dense& B) const {
  const Impl& im = *impl_;
  if (im.n < 0) throw NumericalError(im.stage, "solve() called before compute()");
  if (B.rows() != im.n)
    throw NumericalError(
        im.stage, "solve(): right-hand side has " + std::to_string(B.rows()) + " rows, matrix " + std::to_string(im.n));
  if (im.n == 0 || B.cols() == 0) return Dense(B.rows(), B.cols());
#ifdef QUADCOVER_HAVE_CHOLMOD
  if (im.backend == CholeskyBackend::Cholmod) return im.cholmod->solve(B, false);
#endif
  return im.eigen.solve(B);
}

template <class Scalar>
typename SparseCholesky<Scalar>::Vector SparseCholesky<Scalar>::solve(const Vector& b) const {
  return solve(Dense(b)).col(0);
}

template <class Scalar>
typename SparseCholesky<Scalar>::Vector SparseCholesky<Scalar>::forward_solve(const Vector& b) const {
  const Impl& im = *impl_;
  if (im.n < 0) throw NumericalError(im.stage, "forward_solve() called before compute()");
  if (b.rows() != im.n) throw NumericalError(im.stage, "forward_solve(): right-hand side has the wrong size");
  if (im.n == 0) return Vector(0);
#ifdef QUADCOVER_HAVE_CHOLMOD
  if (im.backend == CholeskyBackend::Cholmod) return im.cholmod->solve(Dense(b), true).col(0);
#endif
  // Eigen: P A Pᵀ = L Lᴴ, so y = L⁻¹ P b.
  Vector pb = im.eigen.permutationP() * b;
  return im.eigen.matrixL().solve(pb);
}

template <class Scalar>
void SparseCholesky<Scalar>::prepare_sparse_solves() {
  Impl& im = *impl_;
  if (im.n < 0) throw NumericalError(im.stage, "prepare_sparse_solves() called before compute()");
  const int n = static_cast<int>(im.n);
  if (im.columns.size() == n && im.new_of_old.size() == static_cast<std::size_t>(n)) return;  // since the factorization
  im.old_of_new.resize(static_cast<std::size_t>(n));
  im.new_of_old.resize(static_cast<std::size_t>(n));
  im.columns = {};
  if (n == 0) return;
#ifdef QUADCOVER_HAVE_CHOLMOD
  if (im.backend == CholeskyBackend::Cholmod) {
    im.columns = im.cholmod->columns(im.stage);
    std::copy(im.cholmod->permutation(), im.cholmod->permutation() + n, im.old_of_new.begin());
  }
#endif
  if (im.backend == CholeskyBackend::Eigen) {
    const Matrix& L = im.eigen.matrixL().nestedExpression();  // compressed, the diagonal first in each column
    const auto& to_new = im.eigen.permutationP().indices();   // (P b)[to_new[k]] = b[k]
    for (int k = 0; k < n; ++k) im.old_of_new[static_cast<std::size_t>(to_new[k])] = k;
    im.columns = LowerColumns<Scalar>::compressed(n, L.outerIndexPtr(), L.innerIndexPtr(), L.valuePtr());
  }
  for (int k = 0; k < n; ++k) im.new_of_old[static_cast<std::size_t>(im.old_of_new[static_cast<std::size_t>(k)])] = k;
  for (int j = 0; j < n; ++j)
    if (im.columns.length[j] < 1 || im.columns.rows[j][0] != j)
      throw NumericalError(im.stage, "the factor's column " + std::to_string(j) + " does not start at its diagonal");
  im.substitution_split = split_substitution(im.columns, kSplitSubstitutionMinColumns);
}

template <class Scalar>
typename SparseCholesky<Scalar>::Vector SparseCholesky<Scalar>::solve_sparse(std::span<const int> rows,
                                                                             std::span<const Scalar> values) const {
  const Impl& im = *impl_;
  if (im.n < 0 || im.new_of_old.size() != static_cast<std::size_t>(im.n) || im.columns.size() != im.n)
    throw NumericalError(im.stage, "solve_sparse() called without prepare_sparse_solves() after the factorization");
  if (rows.size() != values.size())
    throw NumericalError(im.stage, "solve_sparse(): " + std::to_string(rows.size()) + " rows but " +
                                       std::to_string(values.size()) + " values");
  Vector y = Vector::Zero(im.n);
  int first = static_cast<int>(im.n);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (rows[k] < 0 || rows[k] >= im.n)
      throw NumericalError(im.stage, "solve_sparse(): row " + std::to_string(rows[k]) + " is out of range");
    const int j = im.new_of_old[static_cast<std::size_t>(rows[k])];
    y[j] += values[k];
    first = std::min(first, j);
  }
  forward_substitute(im.columns, first, y.data());
  back_substitute(im.columns, im.substitution_split, y.data());
  Vector x(im.n);
  for (Eigen::Index k = 0; k < im.n; ++k) x[im.old_of_new[static_cast<std::size_t>(k)]] = y[k];
  return x;
}

template <class Scalar>
Eigen::Index SparseCholesky<Scalar>::rows() const {
  return impl_->n < 0 ? 0 : impl_->n;
}

#ifdef QUADCOVER_HAVE_CHOLMOD
namespace {
struct CholmodFactorStorage {
  cholmod_common c{};
  cholmod_factor* L = nullptr;
  CholmodFactorStorage() { cholmod_start(&c); }
  ~CholmodFactorStorage() {
    if (L) cholmod_free_factor(&L, &c);
    cholmod_finish(&c);
  }
};
}  // namespace
#endif

bool factor_in_given_order(const Eigen::SparseMatrix<Complex>& C, ColumnFactor& out) {
  out = ColumnFactor{};
#ifdef QUADCOVER_HAVE_CHOLMOD
  const int n = static_cast<int>(C.rows());
  if (C.cols() != n || !C.isCompressed()) return false;
  single_threaded_libraries();
  auto st = std::make_shared<CholmodFactorStorage>();
  cholmod_common& c = st->c;
  c.print = 0;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 1;  // C's own order, not postordered: the factor of exactly C
  c.method[0].ordering = CHOLMOD_NATURAL;
  c.postorder = 0;
  // The supernodal factor is only a step to the simplicial one, so its padding (explicit zeros merged into
  // supernodes) only costs memory, at the conversion's peak beside the simplicial copy: merge less than CHOLMOD's
  // default zrelax 0.8 / 0.1 / 0.05 (BENCHMARKS.md, "Under 3 KB per face").
  c.zrelax[0] = 0.2;
  c.zrelax[1] = 0.025;
  c.zrelax[2] = 0.0125;
  // The upper triangle read in place: in its natural order CHOLMOD factors it without a permuted copy.
  cholmod_sparse S = triangle_view(C, CHOLMOD_COMPLEX, 1);
  cholmod_factor*& L = st->L;
  L = cholmod_analyze(&S, &c);
  bool ok = L && c.status == CHOLMOD_OK && cholmod_factorize(&S, L, &c) && L->minor == L->n && c.status == CHOLMOD_OK;
  // Simplicial LLᴴ with packed, monotonic columns, then the supernodal padding pruned (exact symbolic pattern).
  ok = ok && cholmod_change_factor(CHOLMOD_COMPLEX, 1, 0, 1, 1, L, &c) && cholmod_resymbol(&S, nullptr, 0, 1, L, &c);
  const int* kept = static_cast<const int*>(L->Perm);
  for (int j = 0; ok && j < n; ++j) ok = kept[j] == j;
  if (!ok) return false;
  int* Lp = static_cast<int*>(L->p);
  int* Li = static_cast<int*>(L->i);
  auto* Lx = static_cast<Complex*>(L->x);
  std::vector<std::pair<int, Complex>> col;
  for (int j = 0; j < n; ++j) {
    int* rows = Li + Lp[j];
    Complex* vals = Lx + Lp[j];
    const int len = Lp[j + 1] - Lp[j];
    if (!std::is_sorted(rows, rows + len)) {  // CHOLMOD's conversion keeps them sorted; sort if it did not
      col.clear();
      for (int q = 0; q < len; ++q) col.emplace_back(rows[q], vals[q]);
      std::sort(col.begin(), col.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (int q = 0; q < len; ++q) rows[q] = col[q].first, vals[q] = col[q].second;
    }
    if (len == 0 || rows[0] != j) return false;  // diagonal first
  }
  out.n = n;
  out.p = Lp;
  out.i = Li;
  out.x = Lx;
  out.storage = std::move(st);
  return true;
#else
  (void)C;
  return false;
#endif
}

std::vector<int> nested_dissection_ordering(const Eigen::SparseMatrix<Complex>& A, int min_size) {
#ifdef QUADCOVER_HAVE_CHOLMOD
  const int n = static_cast<int>(A.rows());
  if (n < min_size || A.cols() != n) return {};
  Eigen::SparseMatrix<Complex> pattern = A.triangularView<Eigen::Lower>();
  pattern.makeCompressed();
  const PatternKey key = pattern_key(OrderingKind::NestedDissection, pattern);
  const std::lock_guard<std::mutex> lock(metis_mutex());
  if (std::vector<int> kept = kept_orderings(key.kind).find(key); !kept.empty()) return kept;
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  // METIS, then the elimination tree postordered: every subtree's columns adjacent in L, so the paths the updates
  // walk stay in few cache lines.
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  c.postorder = 1;
  c.supernodal = CHOLMOD_SIMPLICIAL;
  cholmod_sparse S = triangle_view(pattern, CHOLMOD_PATTERN);
  cholmod_factor* L = cholmod_analyze(&S, &c);
  std::vector<int> perm;
  if (L && c.status == CHOLMOD_OK) perm.assign(static_cast<const int*>(L->Perm), static_cast<const int*>(L->Perm) + n);
  if (L) cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
  if (!perm.empty()) kept_orderings(key.kind).keep(key, perm);
  return perm;
#else
  (void)A;
  (void)min_size;
  return {};
#endif
}

template class SparseCholesky<double>;
template class SparseCholesky<Complex>;

}  // namespace quadcover
