// Rounding of the periods together with the integers of the aligned curves (see curve_rounding.h).
#include "param/curve_rounding.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "param/disk_functions.h"

namespace quadcover {

namespace {

/// The variables: 2m real period coordinates (Re of the m free paths, then Im), then one integer per chosen line;
/// the last column is the base point (the direct rounding, every n = 0).
struct Variables {
  std::vector<int> paths;  ///< the free paths (not the dependent path of a component)
  std::vector<int> lines;  ///< the chosen lines
  int count() const { return static_cast<int>(2 * paths.size() + lines.size()); }
};

/// The jump function σ of variable `col` (a unit change of one period) or of the base (col == count()).
Eigen::MatrixX3cd jump_of(const Mesh& mesh, const CurveRoundingInputs& in, const CutFans& fans, const Variables& vars,
                          int col) {
  const int m = static_cast<int>(vars.paths.size());
  Eigen::VectorXcd d = Eigen::VectorXcd::Zero(mesh.num_edges());
  if (col == vars.count()) {
    for (int j = 0; j < in.cut.num_paths(); ++j) d[in.cut.path_edge[j]] = in.direct[j] - in.periods[j];
  } else {
    d[in.cut.path_edge[vars.paths[col % m]]] = col < m ? Complex(1) : Complex(0, 1);
  }
  complete_translations(mesh, in.cut, fans, d);
  return jump_function(mesh, in.cut, fans, d);
}

/// One column: the jump function (zero for a line), the map's corner values at u = 0 and the lines' integers.
struct Column {
  Eigen::MatrixX3cd sigma, known;
  Eigen::VectorXd n;
};

Column column(const Mesh& mesh, const CurveRoundingInputs& in, const CutFans& fans, const Variables& vars, int col) {
  Column c{Eigen::MatrixX3cd::Zero(mesh.num_faces(), 3), Eigen::MatrixX3cd(),
           Eigen::VectorXd::Zero(in.aligned.num_lines())};
  const int m2 = static_cast<int>(2 * vars.paths.size());
  if (col < m2 || col == vars.count())
    c.sigma = jump_of(mesh, in, fans, vars, col);
  else c.n[vars.lines[col - m2]] = 1;
  c.known = col == vars.count() ? Eigen::MatrixX3cd(in.known_free + c.sigma) : c.sigma;
  return c;
}

/// Per column, √A_f (Re, Im of X, then of Y) of R = Σ − ∇u for the constrained u, stacked (4F rows): ‖R‖² = |col|²;
/// and the condition residuals (rows of AlignedLines::line_residuals).
struct Responses {
  Eigen::MatrixXd G, C;
};

/// Adds s · √A_f (Re X, Im X, Re Y, Im Y) of the frame pairs Z, face by face, to column `col` of G.
void add_weighted(const Mesh& mesh, const FramePairs& Z, double s, int col, Eigen::MatrixXd& G) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double w = s * std::sqrt(mesh.face_areas()[f]);
    G.block<4, 1>(4 * f, col) += w * Eigen::Vector4d(Z(f, 0).real(), Z(f, 0).imag(), Z(f, 1).real(), Z(f, 1).imag());
  }
}

Responses responses(const Mesh& mesh, const CurveRoundingInputs& in, const Variables& vars,
                    const std::vector<char>& chosen) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces(), cols = vars.count() + 1;
  std::vector<char> fixed = in.aligned.fixed_components(chosen);
  Eigen::VectorXd pin_values = Eigen::VectorXd::Zero(2 * nv);
  pin_kernel(mesh, in.correction.kernel_pins(), fixed, pin_values);
  ConstrainedSolve solver(fixed);
  const Eigen::SparseMatrix<Complex>& L = in.correction.stiffness();
  solver.factorize(L);
  Eigen::MatrixXcd B(nv, cols);
  Eigen::MatrixXd V(2 * nv, cols);
  Responses r;
  r.G = Eigen::MatrixXd::Zero(4 * nf, cols);
  const CutFans fans = cut_fans(mesh, in.cut);
  for (int col = 0; col < cols; ++col) {  // the Σ part of R now, the ∇u part after the solve
    const Column c = column(mesh, in, fans, vars, col);
    const FramePairs Sigma = corner_gradient(mesh, c.sigma);
    add_weighted(mesh, Sigma, 1, col, r.G);
    B.col(col) = in.correction.rhs(Sigma);
    V.col(col) = in.aligned.fixed_values(c.known, c.n, chosen);
    const Eigen::VectorXd res = in.aligned.line_residuals(c.known, c.n, chosen);
    if (col == 0) r.C.resize(res.size(), cols);
    r.C.col(col) = res;
  }
  const Eigen::MatrixXcd U = solver.solve(L, B, V);
  for (int col = 0; col < cols; ++col)
    add_weighted(mesh, corner_gradient(mesh, in.correction.corner_values(U.col(col))), -1, col, r.G);
  return r;
}

/// The lines to pin: usable, at least min_length grid units long and not left free.
std::vector<int> chosen_lines(const CurveRoundingInputs& in, double min_length) {
  std::vector<int> lines;
  const std::vector<double> lengths = in.aligned.line_lengths(in.face_density);
  for (int k = 0; k < in.aligned.num_lines(); ++k)
    if (in.aligned.line_usable()[k] && lengths[k] / in.edge_length >= min_length &&
        (in.left_free.empty() || !in.left_free[k]))
      lines.push_back(k);
  return lines;
}

}  // namespace

CurveRounding round_with_curves(const Mesh& mesh, const CurveRoundingInputs& in, Lattice lattice,
                                const RoundingOptions& options, double min_length, double max_response_bytes) {
  CurveRounding out;
  Variables vars;
  for (int j = 0; j < in.cut.num_paths(); ++j)
    if (in.cut.dependent_path[in.cut.path_component[j]] != j) vars.paths.push_back(j);
  vars.lines = chosen_lines(in, min_length);
  const int m = static_cast<int>(vars.paths.size()), K = static_cast<int>(vars.lines.size()), J = vars.count();
  const double bytes = 8.0 * (J + 1) * (4.0 * mesh.num_faces() + 6.0 * mesh.num_vertices());
  if (K == 0 || bytes > max_response_bytes) return out;
  out.lines.assign(static_cast<std::size_t>(in.aligned.num_lines()), 0);
  for (const int k : vars.lines) out.lines[k] = 1;
  const Responses r = responses(mesh, in, vars, out.lines);
  // E(y) = |g0 + G y|² + W |c0 + C y|² for the offset y from the base point; W: ten times the dearest single unit
  // step, so that a condition missed by one grid unit costs more than any one move.
  const Eigen::MatrixXd G = r.G.leftCols(J), C = r.C.leftCols(J);
  const Eigen::VectorXd g0 = r.G.col(J), c0 = r.C.col(J);
  Eigen::MatrixXd Q = G.transpose() * G;
  const double W = 10 * std::max(Q.diagonal().maxCoeff(), 1e-300);
  Q += W * C.transpose() * C;
  Q.diagonal().array() += 1e-9 * Q.diagonal().maxCoeff();  // a line free to slide (no cost) stays definite
  const Eigen::VectorXd q = G.transpose() * g0 + W * C.transpose() * c0;
  const Eigen::VectorXd y_star = -Q.ldlt().solve(q);
  // In lattice coordinates: x = T z for the periods, n = z for the lines; the base point is (x_direct, 0).
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(J, J);
  T.topLeftCorner(2 * m, 2 * m) = lattice_basis(lattice, m);
  Eigen::VectorXd base = Eigen::VectorXd::Zero(J);
  for (int a = 0; a < m; ++a) base[a] = in.direct[vars.paths[a]].real(), base[m + a] = in.direct[vars.paths[a]].imag();
  out.search = round_periods(T.transpose() * Q * T, T.partialPivLu().solve(base + y_star), options);
  const Eigen::VectorXd y = T * out.search.c.cast<double>() - base;
  const auto energy = [&](const Eigen::VectorXd& v) { return (g0 + G * v).squaredNorm(); };
  Eigen::VectorXd y_direct = Eigen::VectorXd::Zero(J);
  y_direct.tail(K) = y_star.tail(K).array().round().matrix();
  out.energy_direct = energy(y_direct);
  out.energy_rounded = energy(y);
  const Eigen::VectorXd residual = c0 + C * y;
  out.conditions = static_cast<int>(residual.size());
  out.conditions_met = static_cast<int>((residual.array().abs() < 1e-6).count());
  out.paths = vars.paths;
  for (int a = 0; a < m; ++a) out.periods.push_back(Complex(base[a] + y[a], base[m + a] + y[m + a]));
  out.line_values = Eigen::VectorXd::Zero(in.aligned.num_lines());
  for (int k = 0; k < K; ++k) out.line_values[vars.lines[k]] = y[2 * m + k];
  out.variables = J;
  out.active = true;
  return out;
}

}  // namespace quadcover
