// The `quadcover` Python module: plain numpy arrays in and out (V #V×3 float, F #F×3 int, 0-based), results as
// numpy arrays and dicts with the same keys as the CLI's JSON reports.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"
#include "metrics/param_quality.h"
#include "optimize/optimize_field.h"
#include "metrics/quad_quality.h"
#include "metrics/report.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "quad/smooth_quads.h"

namespace py = pybind11;
using namespace quadcover;

namespace {

using RowMatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrixX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

Mesh make_mesh(const RowMatrixX3d& V, const RowMatrixX3i& F) {
  return build_mesh(PolygonSoup::from_triangles(Eigen::MatrixX3d(V), Eigen::MatrixX3i(F))).mesh;
}

/// Lets Ctrl-C stop long stages from Python: checks for signals (with the GIL) when a stage asks cancelled().
class PythonProgress final : public ProgressSink {
 public:
  void report(std::string_view, double, std::string_view) override {}
  bool cancelled() const override {
    if (interrupted_) return true;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) interrupted_ = true;
    return interrupted_;
  }
  /// Re-raises the KeyboardInterrupt after the stage returned.
  void raise_if_interrupted() const {
    if (interrupted_) throw py::error_already_set();
  }

 private:
  mutable std::atomic<bool> interrupted_{false};
};

FieldOptions field_options(double trusted_fraction, double lambda, int smoothing_rounds) {
  FieldOptions o;
  o.trusted_fraction = trusted_fraction;
  o.lambda = lambda;
  o.smoothing_rounds = smoothing_rounds;
  return o;
}

ParamOptions param_options(double edge_length, int quads, const std::string& lattice, const std::string& rounding,
                           int stiffening, int relaxation) {
  if (stiffening < 0) throw InputError("stiffening", 0, "must be >= 0 (0 = off)");
  if (relaxation < 0) throw InputError("relaxation", 0, "must be >= 0 (0 = off)");
  ParamOptions o;
  o.stiffening.max_iterations = stiffening;
  o.relaxation.iterations = relaxation;
  o.edge_length = edge_length;
  o.target_quads = quads;
  o.lattice = parse_lattice(lattice);
  o.rounding.strategy = parse_rounding_strategy(rounding);
  return o;
}

OptimizeOptions optimize_options(const std::string& optimize, long max_iterations, const ParamOptions& popt) {
  if (max_iterations < kAutoBudget)
    throw InputError("max_iterations", 0, "must be >= -1 (-1 = auto, 0 = until converged)");
  OptimizeOptions o;
  o.mode = parse_optimize_mode(optimize);
  o.max_evaluations = max_iterations;
  o.param = popt;
  return o;
}

/// Field (ch. 5) then the optimization of its matching (ch. 6); `report` gets the "optimize" object and
/// `original` the field before the optimization.
FrameField optimized_field(const Mesh& mesh, const std::string& style, ParamOptions& popt, OptimizeOptions oopt,
                           ProgressSink& progress, nlohmann::json& report, FrameField& original) {
  const FieldOptions fo = field_options(parse_field_style(style));
  oopt.lambda = fo.lambda;  // the re-smoothing of Algorithm 6.1 uses the field stage's λ
  const FrameFieldResult f = compute_frame_field_detailed(mesh, fo, progress);
  fix_default_density(mesh, f.field, popt);  // one scale for the optimization, keep-better and the map
  oopt.param = popt;
  original = f.field;
  OptimizeResult r = optimize_field(mesh, f, oopt, progress);
  report = to_json(r, oopt.mode);
  return std::move(r.field);
}

py::dict info(const RowMatrixX3d& V, const RowMatrixX3i& F) {
  const Mesh mesh = make_mesh(V, F);
  py::dict d;
  d["vertices"] = mesh.num_vertices();
  d["edges"] = mesh.num_edges();
  d["faces"] = mesh.num_faces();
  d["components"] = mesh.num_components();
  d["boundary_loops"] = mesh.num_boundary_loops();
  d["genus"] = mesh.genus();
  d["euler_characteristic"] = mesh.euler_characteristic();
  d["area"] = mesh.total_area();
  d["mean_edge_length"] = mesh.mean_edge_length();
  d["bounding_box_diagonal"] = mesh.bounding_box_diagonal();
  return d;
}

py::dict load(const std::string& path) {
  const PolygonSoup soup = read_mesh(path);
  py::dict d;
  d["V"] = RowMatrixX3d(soup.positions);
  bool triangles = true;
  py::list faces;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    triangles = triangles && soup.face_size(f) == 3;
    faces.append(std::vector<std::int64_t>(soup.face_begin(f), soup.face_begin(f) + soup.face_size(f)));
  }
  if (triangles) {
    RowMatrixX3i F(static_cast<Eigen::Index>(soup.num_faces()), 3);
    for (std::size_t f = 0; f < soup.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) F(static_cast<Eigen::Index>(f), k) = static_cast<int>(soup.face_begin(f)[k]);
    d["F"] = F;
  } else {
    d["F"] = faces;
  }
  if (soup.has_uv()) {
    d["uv"] = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>(soup.uv);
    py::list fuv;
    for (std::size_t f = 0; f < soup.num_faces(); ++f)
      fuv.append(std::vector<std::int64_t>(soup.face_uv.begin() + soup.face_offsets[f],
                                           soup.face_uv.begin() + soup.face_offsets[f + 1]));
    d["face_uv"] = fuv;
  } else {
    d["uv"] = py::none();
    d["face_uv"] = py::none();
  }
  return d;
}

py::list branch_list(const std::vector<BranchPoint>& bps) {
  py::list l;
  for (const auto& b : bps) l.append(py::make_tuple(b.vertex, b.quarter_index));
  return l;
}

py::dict field(const RowMatrixX3d& V, const RowMatrixX3i& F, double trusted_fraction, double lambda,
               int smoothing_rounds) {
  const Mesh mesh = make_mesh(V, F);
  PythonProgress progress;
  FrameFieldResult r;
  {
    py::gil_scoped_release release;
    r = compute_frame_field_detailed(mesh, field_options(trusted_fraction, lambda, smoothing_rounds), progress);
  }
  progress.raise_if_interrupted();
  py::dict d;
  d["X"] = Eigen::VectorXcd(r.field.X);
  d["Y"] = Eigen::VectorXcd(r.field.Y);
  d["matching"] = Eigen::VectorXi(r.field.matching);
  d["edges"] = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>(mesh.E());
  d["branch_points"] = branch_list(r.branch_points);
  // Tangent basis of each face, so X can be turned into 3D vectors: X3 = Re(X)·b1 + Im(X)·b2.
  d["basis1"] = RowMatrixX3d(mesh.face_basis1());
  d["basis2"] = RowMatrixX3d(mesh.face_basis2());
  d["energy_smooth"] = r.energy_smooth;
  d["energy_align"] = r.energy_align;
  return d;
}

// Per-corner UVs as a #F×3×2 float array.
py::array_t<double> corner_uv_array(const Eigen::MatrixX3cd& uv) {
  py::array_t<double> a({static_cast<py::ssize_t>(uv.rows()), py::ssize_t{3}, py::ssize_t{2}});
  auto m = a.mutable_unchecked<3>();
  for (Eigen::Index f = 0; f < uv.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      m(f, c, 0) = uv(f, c).real();
      m(f, c, 1) = uv(f, c).imag();
    }
  return a;
}

py::tuple parameterize_py(const RowMatrixX3d& V, const RowMatrixX3i& F, double edge_length, int quads,
                          const std::string& lattice, const std::string& optimize, const std::string& rounding,
                          long max_iterations, bool keep_better, int stiffening, int relaxation,
                          const std::string& field) {
  const Mesh mesh = make_mesh(V, F);
  ParamOptions popt = param_options(edge_length, quads, lattice, rounding, stiffening, relaxation);
  const OptimizeOptions oopt = optimize_options(optimize, max_iterations, popt);
  PythonProgress progress;
  Parameterization p;
  ParamQuality q;
  nlohmann::json optimize_report;
  {
    py::gil_scoped_release release;
    FrameField original;
    const FrameField f = optimized_field(mesh, field, popt, oopt, progress, optimize_report, original);
    p = parameterize_keep_better(mesh, original, f, popt, oopt.mode, keep_better, progress, optimize_report);
    q = param_quality(mesh, p);
  }
  progress.raise_if_interrupted();
  nlohmann::json report = to_json(q);
  report["faces"] = mesh.num_faces();
  report["lattice"] = to_string(popt.lattice);
  report["edge_length"] = target_edge_length(mesh, popt);
  report["optimize"] = optimize_report;
  report["rounding"] = rounding_to_json(popt, p);
  report["relaxation"] = relaxation_to_json(p);
  report["stiffening"] = stiffening_to_json(p);
  return py::make_tuple(corner_uv_array(p.uv), to_python(report));
}

py::tuple remesh_py(const RowMatrixX3d& V, const RowMatrixX3i& F, double edge_length, int quads,
                    const std::string& lattice, const std::string& optimize, const std::string& rounding,
                    long max_iterations, bool keep_better, int stiffening, int relaxation, const std::string& field,
                    int smooth_quads_rounds, double smooth_rigidity) {
  if (smooth_quads_rounds < 0) throw InputError("smooth_quads", 0, "must be >= 0 (0 = off)");
  if (!(smooth_rigidity >= 0 && smooth_rigidity <= 1)) throw InputError("smooth_rigidity", 0, "must be in [0, 1]");
  QuadSmoothingOptions sopt;
  sopt.iterations = smooth_quads_rounds;
  sopt.rigidity = smooth_rigidity;
  const Mesh mesh = make_mesh(V, F);
  ParamOptions popt = param_options(edge_length, quads, lattice, rounding, stiffening, relaxation);
  const OptimizeOptions oopt = optimize_options(optimize, max_iterations, popt);
  PythonProgress progress;
  ExtractionResult ex;
  Report report;
  nlohmann::json optimize_report, rounding_report, relaxation_report, stiffening_report, smoothing_report;
  {
    py::gil_scoped_release release;
    FrameField original;
    const FrameField f = optimized_field(mesh, field, popt, oopt, progress, optimize_report, original);
    const Parameterization p =
        parameterize_keep_better(mesh, original, f, popt, oopt.mode, keep_better, progress, optimize_report);
    rounding_report = rounding_to_json(popt, p);
    relaxation_report = relaxation_to_json(p);
    stiffening_report = stiffening_to_json(p);
    ex = extract_quads(mesh, p, {}, progress);
    smoothing_report = quad_smoothing_to_json(sopt, smooth_quads(ex.mesh, mesh, p, sopt, progress));
    report.parameterization = param_quality(mesh, p);
    report.extraction = ex.report;
    report.quad_mesh = quad_quality(ex.mesh);
  }
  progress.raise_if_interrupted();
  py::list faces;
  bool all_quads = true;
  for (const auto& face : ex.mesh.faces) {
    all_quads = all_quads && face.size() == 4;
    faces.append(face);
  }
  py::object Q = faces;
  if (all_quads) {
    Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor> M(static_cast<Eigen::Index>(ex.mesh.faces.size()), 4);
    for (std::size_t i = 0; i < ex.mesh.faces.size(); ++i)
      for (int k = 0; k < 4; ++k) M(static_cast<Eigen::Index>(i), k) = ex.mesh.faces[i][static_cast<std::size_t>(k)];
    Q = py::cast(M);
  }
  nlohmann::json j = to_json(report);
  j["optimize"] = optimize_report;
  j["rounding"] = rounding_report;
  j["relaxation"] = relaxation_report;
  j["stiffening"] = stiffening_report;
  j["quad_smoothing"] = smoothing_report;
  return py::make_tuple(RowMatrixX3d(ex.mesh.V), Q, to_python(j));
}

}  // namespace

PYBIND11_MODULE(_quadcover, m) {
  m.doc() = "quadcover: seamless quad-aligned parameterization (QuadCover) and quad remeshing";
  m.attr("__version__") = QUADCOVER_PY_VERSION;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const TopologyError& e) {
      std::string msg = e.what();
      for (const auto& s : e.problems()) msg += "\n  " + s;
      PyErr_SetString(PyExc_ValueError, msg.c_str());
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const NumericalError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });
  m.def("info", &info, py::arg("V"), py::arg("F"),
        "Counts and topology of a triangle mesh: dict with vertices, edges, faces, components, boundary_loops, genus, "
        "euler_characteristic, area, mean_edge_length, bounding_box_diagonal. Raises ValueError (listing every "
        "problem) if the mesh is not a valid manifold triangle mesh.");
  m.def("load", &load, py::arg("path"),
        "Reads a mesh file (.obj .off .ply .stl): dict with V (#V×3), F (#F×3 int array for triangle meshes, else a "
        "list of polygons), uv (#UV×2 or None) and face_uv (per-face lists of uv indices, -1 = none, or None).");
  m.def("field", &field, py::arg("V"), py::arg("F"), py::arg("trusted_fraction") = 0.2, py::arg("lambda_") = 0.5,
        py::arg("smoothing_rounds") = 2,
        "Curvature-guided cross field (thesis Chapter 5): dict with X, Y (#F complex, face basis basis1/basis2), "
        "matching (#E int, on edges `edges`), branch_points [(vertex, quarter_index)], energy_smooth, energy_align.");
  m.def("parameterize", &parameterize_py, py::arg("V"), py::arg("F"), py::arg("edge_length") = 0.0,
        py::arg("quads") = 0, py::arg("lattice") = "rotated", py::arg("optimize") = "relocate",
        py::arg("rounding") = "search3", py::arg("max_iterations") = kAutoBudget, py::arg("keep_better") = true,
        py::arg("stiffening") = StiffeningOptions{}.max_iterations,
        py::arg("relaxation") = RelaxationOptions{}.iterations, py::arg("field") = "curvature",
        "Seamless QuadCover parameterization: returns (uv, report) with uv #F×3×2 per-corner coordinates in grid "
        "units (integer iso-lines are quad edges) and the report dict (E_D, E_H, flips, ARAP, branch points, ...). "
        "Density: edge_length h, or quads N, or by default twice the mean edge length (finer where needed for 30 "
        "quads per branch point). optimize: none, relocate "
        "(Algorithm 6.1 moving/cancelling branch points) or full (with creation and balancing, 6.4), at most "
        "max_iterations E_D evaluations (-1 = auto: the budget grows with the mesh, plus a time limit for full; 0 = "
        "until converged); report['optimize'] has E_D and branch points before "
        "and after and the per-iteration log. rounding of the periods (6.3): direct, greedy, search1, search2, "
        "search3 or exact; report['rounding'] has the strategy and E_H. keep_better: also parameterize the original "
        "field and keep the map with the lower E_D + E_H (report['optimize']['kept']). stiffening: re-solves of the "
        "final correction against flipped triangles (0 = off); report['stiffening'] has the flips before and after "
        "and the price E_S. relaxation: ARAP local/global rounds of the final map (0 = off); report['relaxation'] "
        "has the ARAP distortion before and after and the price E_R. field: 'curvature' (thesis ch. 5) or "
        "'smooth' (smoothest cross field, lower distortion on organic shapes). Ctrl-C stops the optimization early.");
  m.def("remesh", &remesh_py, py::arg("V"), py::arg("F"), py::arg("edge_length") = 0.0, py::arg("quads") = 0,
        py::arg("lattice") = "rotated", py::arg("optimize") = "relocate", py::arg("rounding") = "search3",
        py::arg("max_iterations") = kAutoBudget, py::arg("keep_better") = true,
        py::arg("stiffening") = StiffeningOptions{}.max_iterations,
        py::arg("relaxation") = RelaxationOptions{}.iterations, py::arg("field") = "curvature",
        py::arg("smooth_quads") = QuadSmoothingOptions{}.iterations,
        py::arg("smooth_rigidity") = QuadSmoothingOptions{}.rigidity,
        "Quad remeshing (field -> optimization -> parameterization -> extraction -> smoothing): returns (QV #Q×3, "
        "faces, report) where faces is a #faces×4 int array when every face is a quad, else a list of polygons. "
        "optimize, rounding, max_iterations, keep_better, stiffening, relaxation and field as in parameterize(); "
        "smooth_quads rounds of tangential smoothing on the input surface (0 = off: vertices at the integer points) "
        "with target squares of the mean edge length (smooth_rigidity 1) or of each quad's own size (0). The report "
        "has the same 'optimize', 'rounding', 'relaxation' and 'stiffening' objects and 'quad_smoothing'.");
}
