// The `quadcover` Python module: plain numpy arrays in and out (V #V×3 float, F #F×3 int, 0-based); parameterize()
// and remesh() run the library's jobs (src/pipeline/) and return their report, the CLI's --report document.
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <climits>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/errors.h"
#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"
#include "pipeline/job_report.h"
#include "pipeline/parameterize_mesh.h"
#include "pipeline/remesh_mesh.h"

namespace py = pybind11;
using namespace quadcover;

namespace {

using RowMatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrixX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

/// V as a #V×3 float array of finite values. \throw InputError otherwise.
RowMatrixX3d vertex_array(const py::array& V) {
  if (V.ndim() != 2 || V.shape(1) != 3)
    throw InputError("V", 0, "must be a #V x 3 array of vertex positions");
  const char kind = V.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') throw InputError("V", 0, "must hold numbers (got dtype kind '" +
                                                                            std::string(1, kind) + "')");
  RowMatrixX3d M = py::cast<RowMatrixX3d>(py::array_t<double, py::array::c_style | py::array::forcecast>(V));
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    if (!M.row(i).allFinite())
      throw InputError("V", 0, "vertex " + std::to_string(i) + " has a non-finite coordinate");
  return M;
}

/// F as a #F×3 int array of vertex indices in [0, n_vertices). Floats are refused, not truncated; indices that do
/// not fit are refused, not wrapped. \throw InputError otherwise.
RowMatrixX3i face_array(const py::array& F, Eigen::Index n_vertices) {
  if (F.ndim() != 2 || F.shape(1) != 3) throw InputError("F", 0, "must be a #F x 3 array of vertex indices");
  const char kind = F.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InputError("F", 0, "must be an integer array (got dtype " + py::str(F.dtype()).cast<std::string>() + ")");
  const auto wide = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>(F);
  if (kind == 'u' && F.dtype().itemsize() == 8) {  // uint64 values above 2^63 would wrap negative in int64
    const auto u = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>(F).unchecked<2>();
    for (py::ssize_t f = 0; f < u.shape(0); ++f)
      for (py::ssize_t c = 0; c < 3; ++c)
        if (u(f, c) >= static_cast<std::uint64_t>(n_vertices))
          throw InputError("F", 0, "face " + std::to_string(f) + " has vertex index " + std::to_string(u(f, c)) +
                                       ", out of range [0, " + std::to_string(n_vertices) + ")");
  }
  const auto w = wide.unchecked<2>();
  RowMatrixX3i M(w.shape(0), 3);
  for (py::ssize_t f = 0; f < w.shape(0); ++f)
    for (py::ssize_t c = 0; c < 3; ++c) {
      if (w(f, c) < 0 || w(f, c) >= n_vertices)
        throw InputError("F", 0, "face " + std::to_string(f) + " has vertex index " + std::to_string(w(f, c)) +
                                     ", out of range [0, " + std::to_string(n_vertices) + ")");
      M(f, c) = static_cast<int>(w(f, c));
    }
  return M;
}

Mesh make_mesh(const py::array& V, const py::array& F, std::vector<int>* vertex_map = nullptr) {
  const RowMatrixX3d P = vertex_array(V);
  MeshBuildResult built =
      build_mesh(PolygonSoup::from_triangles(Eigen::MatrixX3d(P), Eigen::MatrixX3i(face_array(F, P.rows()))));
  if (vertex_map) *vertex_map = std::move(built.vertex_map);
  return std::move(built.mesh);
}

/// Progress of long stages for Python: calls `callback(stage, fraction, message)` (with the GIL) if given, whose
/// truthy return value cancels; Ctrl-C cancels too. Exceptions of the callback cancel and are re-raised.
class PythonProgress final : public ProgressSink {
 public:
  explicit PythonProgress(py::object callback = py::none()) : callback_(std::move(callback)) {}
  void report(std::string_view stage, double fraction, std::string_view message) override {
    if (callback_.is_none() || stopped_) return;
    py::gil_scoped_acquire gil;
    try {
      if (py::bool_(callback_(std::string(stage), fraction, std::string(message)))) stopped_ = cancelled_ = true;
    } catch (py::error_already_set& e) {
      error_ = std::make_unique<py::error_already_set>(std::move(e));
      stopped_ = true;
    }
  }
  bool cancelled() const override {
    if (stopped_) return true;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) stopped_ = interrupted_ = true;
    return stopped_;
  }
  /// After the job: re-raises the KeyboardInterrupt or the callback's exception, or raises Cancelled.
  void raise_if_stopped() {
    if (interrupted_) throw py::error_already_set();
    if (error_) throw std::move(*error_);
    if (cancelled_) throw Cancelled();
  }
  struct Cancelled : std::exception {
    const char* what() const noexcept override { return "cancelled by the progress callback"; }
  };

 private:
  py::object callback_;
  std::unique_ptr<py::error_already_set> error_;
  mutable std::atomic<bool> stopped_{false}, interrupted_{false};
  std::atomic<bool> cancelled_{false};
};

FieldOptions field_options(double trusted_fraction, double lambda, int smoothing_rounds) {
  FieldOptions o;
  o.trusted_fraction = trusted_fraction;
  o.lambda = lambda;
  o.smoothing_rounds = smoothing_rounds;
  return o;
}

/// feature_angle= as degrees: a number, or "off" (= 0, no sharp features). \throw InputError otherwise (the range
/// is checked by validate()).
double feature_angle_degrees(const py::object& value) {
  if (py::isinstance<py::str>(value)) {
    if (value.cast<std::string>() == "off") return 0;
  } else if (!py::isinstance<py::bool_>(value) && py::hasattr(value, "__float__")) {
    return value.cast<double>();
  }
  throw InputError("feature_angle", 0,
                   "expected a number of degrees in [0, 180] or 'off', got " + py::repr(value).cast<std::string>());
}

/// features= as vertex pairs: None, or a #E×2 integer array of indices into V. \throw InputError otherwise.
std::optional<std::vector<std::pair<int, int>>> feature_edge_pairs(const py::object& value) {
  if (value.is_none()) return std::nullopt;
  Eigen::Matrix<long long, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> E;
  try {
    E = value.cast<Eigen::Matrix<long long, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>();
  } catch (const py::cast_error&) {
    throw InputError("features", 0, "expected None or a #E×2 integer array of vertex indices");
  }
  if (E.size() > 0 && E.cols() != 2)
    throw InputError("features", 0,
                     "expected a #E×2 array of vertex indices, got " + std::to_string(E.cols()) + " columns");
  std::vector<std::pair<int, int>> pairs;
  for (Eigen::Index r = 0; r < E.rows() && E.cols() == 2; ++r) {
    if (E(r, 0) < 0 || E(r, 1) < 0 || E(r, 0) > INT_MAX || E(r, 1) > INT_MAX)
      throw InputError("features", r + 1, "vertex index out of range");
    pairs.emplace_back(static_cast<int>(E(r, 0)), static_cast<int>(E(r, 1)));
  }
  return pairs;
}

/// FeatureOptions::given from features= on the mesh built from V (vertex_map: V's row -> mesh vertex, -1 unused).
/// \throw InputError naming the row (1-based) of a pair that is not an edge of the mesh.
void set_given_features(const Mesh& mesh, const std::vector<int>& vertex_map,
                        const std::optional<std::vector<std::pair<int, int>>>& pairs, PipelineOptions& options) {
  if (!pairs) return;
  RefusedFeatureEdge refused;
  options.param.features.given = feature_segments(mesh, vertex_map, *pairs, refused);
  if (refused.why == RefusedFeatureEdge::Why::kNone) return;
  const auto [a, b] = (*pairs)[static_cast<std::size_t>(refused.position)];
  throw InputError(
      "features", refused.position + 1,
      refused.why == RefusedFeatureEdge::Why::kNotAnEdge
          ? "vertices " + std::to_string(a) + " and " + std::to_string(b) + " are not joined by an edge of F"
          : "vertex " + std::to_string(refused.vertex) + " is not a vertex of a face of F");
}

/// The keyword arguments shared by parameterize() and remesh(), as pipeline options.
struct JobArgs {
  double edge_length = 0;
  int quads = 0, faces = 0;
  std::string lattice, optimize, rounding, field, fill;
  long max_iterations = kAutoBudget;
  bool keep_better = true;
  int stiffening = 0, relaxation = 0;
  double feature_angle = FeatureOptions{}.sharp_angle_degrees;
  bool align_curves = true;
  int fold_refinement_rounds = PipelineOptions{}.fold_refinement_rounds;
  int validity_retries = PipelineOptions{}.validity_retries;
  bool round_curves = ParamOptions{}.alignment.round_with_periods;
  bool merge_cones = PipelineOptions{}.merge_coincident_cones, move_cones = PipelineOptions{}.move_wound_cones;
  bool separate_cones = PipelineOptions{}.separate_coincident_cones;
  int split_cones = PipelineOptions{}.split_min_quarters;
  bool cancel_close_cones = PipelineOptions{}.cancel_close_cones;
  double square_holes = PipelineOptions{}.square_hole_grid_units;
  std::optional<std::vector<std::pair<int, int>>> feature_edges;  ///< features=: given sharp edges (indices into V)
};

PipelineOptions pipeline_options(const JobArgs& a) {
  if (a.quads > 0 && a.faces > 0 && a.quads != a.faces)
    throw InputError("faces/quads", 0, "give the target quad count once (faces= or its alias quads=)");
  PipelineOptions o;
  o.param.density.edge_length = a.edge_length;
  o.param.density.target_quads = a.faces > 0 ? a.faces : a.quads;
  o.param.lattice = parse_lattice(a.lattice);
  o.param.rounding.strategy = parse_rounding_strategy(a.rounding);
  o.field_style = parse_field_style(a.field);
  o.fill = parse_fill(a.fill);
  o.optimize = parse_optimize_mode(a.optimize);
  o.max_evaluations = a.max_iterations;
  o.keep_better = a.keep_better;
  o.param.stiffening.max_iterations = a.stiffening;
  o.param.relaxation.iterations = a.relaxation;
  o.param.features.sharp_angle_degrees = a.feature_angle;
  o.param.alignment.enabled = a.align_curves;
  o.param.alignment.round_with_periods = a.round_curves;
  o.fold_refinement_rounds = a.fold_refinement_rounds;
  o.validity_retries = a.validity_retries;
  o.merge_coincident_cones = a.merge_cones;
  o.move_wound_cones = a.move_cones;
  o.separate_coincident_cones = a.separate_cones;
  o.split_min_quarters = a.split_cones;
  o.cancel_close_cones = a.cancel_close_cones;
  o.square_hole_grid_units = a.square_holes;
  validate(o);  // ValueError naming the keyword before any work
  return o;
}

py::dict info(const py::array& V, const py::array& F) {
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

py::dict field(const py::array& V, const py::array& F, double trusted_fraction, double lambda,
               int smoothing_rounds) {
  const Mesh mesh = make_mesh(V, F);
  PythonProgress progress;
  FrameFieldResult r;
  {
    py::gil_scoped_release release;
    r = compute_frame_field_detailed(mesh, field_options(trusted_fraction, lambda, smoothing_rounds), progress);
  }
  progress.raise_if_stopped();
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

/// Each of the report's warnings as a Python UserWarning (a degraded result is never only in the dict).
void warn(const nlohmann::json& report) {
  for (const auto& w : report["warnings"])
    if (PyErr_WarnEx(PyExc_UserWarning, w.get<std::string>().c_str(), 1) != 0) throw py::error_already_set();
}

py::tuple parameterize_py(const py::array& V, const py::array& F, const JobArgs& args, py::object progress_callback) {
  std::vector<int> vertex_map;
  const Mesh mesh = make_mesh(V, F, &vertex_map);
  PipelineOptions options = pipeline_options(args);
  set_given_features(mesh, vertex_map, args.feature_edges, options);
  PythonProgress progress(std::move(progress_callback));
  nlohmann::json report;
  Eigen::MatrixX3cd uv;
  RowMatrixX3d map_V;  // the triangulation of uv: the input's, or its refinement for the curve constraints
  RowMatrixX3i map_F;
  {
    py::gil_scoped_release release;
    const ParamJob job = parameterize_mesh(mesh, options, progress);
    report = param_report(mesh, job, job.map.uv);
    uv = job.map.uv;
    map_V = job.mesh(mesh).V();
    map_F = job.mesh(mesh).F();
  }
  progress.raise_if_stopped();
  warn(report);
  return py::make_tuple(corner_uv_array(uv), to_python(report), map_V, map_F);
}

/// Faces as a #faces×4 int array when every face is a quad, else a list of polygons.
py::object face_list(const std::vector<std::vector<int>>& faces) {
  bool all_quads = true;
  for (const auto& face : faces) all_quads = all_quads && face.size() == 4;
  if (!all_quads) return py::cast(faces);
  Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor> M(static_cast<Eigen::Index>(faces.size()), 4);
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 4; ++k) M(static_cast<Eigen::Index>(i), k) = faces[i][static_cast<std::size_t>(k)];
  return py::cast(M);
}

py::tuple remesh_py(const py::array& V, const py::array& F, const JobArgs& args, int smooth_quads_rounds,
                    double smooth_rigidity, bool boundary_quads, py::object progress_callback) {
  std::vector<int> vertex_map;
  const Mesh mesh = make_mesh(V, F, &vertex_map);
  PipelineOptions options = pipeline_options(args);
  set_given_features(mesh, vertex_map, args.feature_edges, options);
  options.smoothing.iterations = smooth_quads_rounds;
  options.smoothing.rigidity = smooth_rigidity;
  options.extraction.quadrangulate_boundary = boundary_quads;
  PythonProgress progress(std::move(progress_callback));
  nlohmann::json report;
  RemeshJob job;
  {
    py::gil_scoped_release release;
    job = remesh_mesh(mesh, options, progress);
    report = remesh_report(mesh, job);
  }
  progress.raise_if_stopped();
  warn(report);
  const QuadMesh& q = job.extraction.mesh;
  return py::make_tuple(RowMatrixX3d(q.V), face_list(q.faces), to_python(report));
}

/// Errors of the library as Python exceptions: bad input or options ValueError, numerical failures RuntimeError.
void register_exceptions() {
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
}

constexpr const char* kParameterizeDoc =
    "Seamless QuadCover parameterization: returns (uv, report) with uv #F×3×2 per-corner coordinates in grid "
    "units (integer iso-lines are quad edges) and the report dict: the same document as the CLI's `param --report` "
    "JSON (schema_version, parameterization, field, optimize, rounding, relaxation, stiffening, ...). "
    "Density: edge_length h, or faces N (target quad count; quads is its old name), or by default twice the mean "
    "edge length (finer where needed for 30 quads per branch point and 4 quad edges around every hole). optimize: "
    "none, relocate (Algorithm 6.1 moving/cancelling branch points) or full (with creation and balancing, 6.4), at "
    "most max_iterations E_D evaluations (-1 = auto, 0 = until converged). rounding of the periods (6.3): direct, "
    "greedy, search1, "
    "search2, search3 or exact. keep_better: also parameterize the original field and keep the map with the lower "
    "E_D + E_H. stiffening: re-solves of the final correction against flipped triangles (0 = off). relaxation: "
    "ARAP local/global rounds of the final map (0 = off). field: 'curvature' (the trusted principal curvature "
    "directions, filled and smoothed, thesis ch. 5), 'smooth' (the "
    "smoothest cross field, weakly pulled to them) or 'auto' (smooth on a closed surface, curvature on one with a "
    "boundary; when the smooth field's result is not valid the curvature field's is made too and the more valid "
    "kept; the report's options.field says which ran). "
    "fill: frames of the untrusted faces, 'smooth' (power-field solve) or 'propagate' (the thesis's trusted "
    "propagation, 5.1.2). "
    "feature_angle: interior edges whose dihedral angle exceeds this many degrees (on curves of at least 8 such "
    "edges, or shorter creases between flat sides and between corners) are sharp features the field follows, 0 or "
    "'off' = none (boundaries are always followed), in [0, 180]. "
    "features: None, or a #E×2 integer array of vertex pairs (indices into V), edges of F given as the sharp "
    "features instead of detecting them (the CLI's --features; feature_angle is then not used). "
    "align_curves: put the boundary and sharp feature curves on integer iso-lines (quad edges). "
    "round_curves: with align_curves, round the periods and the curves' integers together (the CLI's "
    "--round-curves; the curves through wrong windings are freed, and it falls back to the map without when "
    "that one is more valid). "
    "fold_refinement_rounds: rounds of edge splits around triangles left flipped or collapsed (the CLI's "
    "--refine-folds; 0 = off). "
    "validity_retries: runs of the job at nearby densities while the result is not valid (the CLI's --retries; "
    "0 = off, see the report's validity_retries). "
    "merge_cones / move_cones: the cone merges and fake-pair moves that make the map again from a changed field "
    "while it is not valid (the CLI's --merge-cones / --move-cones). "
    "separate_cones: when the result is not valid beside cones the rounding put on one lattice point, make the map "
    "again with them set apart by re-rounded periods (the CLI's --separate-cones). "
    "split_cones: split every interior singularity of the field of index at least split_cones/4 in absolute value "
    "into ±1/4 ones (2, 3 or 4 = whole turns only; the CLI's --split-cones). "
    "cancel_close_cones: before the map, cancel the branch point pairs of opposite index less than one quad edge "
    "apart (the CLI's --cancel-close-cones; report field.cancelled_close_pairs). square_holes: closed crease loops "
    "shorter than this many quad edges that run straight on one side (the rim of a small hole through a part) are "
    "followed on that side only, so the hole comes out square in an even grid (the CLI's --square-holes; 0 = off). "
    "progress: optional callable(stage, fraction, message) called during the run; a truthy return cancels "
    "(RuntimeError 'cancelled by the progress callback'); Ctrl-C raises KeyboardInterrupt. V must be a #V×3 array "
    "of finite numbers and F a #F×3 integer array of indices into V, else ValueError.";

constexpr const char* kRemeshDoc =
    "Quad remeshing (field -> optimization -> parameterization -> extraction -> smoothing), the same job as the "
    "CLI's `remesh`: returns (QV #Q×3, faces, report) where faces is a #faces×4 int array when every face is a "
    "quad, else a list of polygons, and report the same document as `remesh --report`. Options as in "
    "parameterize(); smooth_quads rounds of tangential smoothing on the input surface (0 = off: vertices at the "
    "integer points) with target squares of the mean edge length (smooth_rigidity 1) or of each quad's own size "
    "(0); boundary_quads makes the polygons the boundary clips out of grid cells into quads (the CLI's "
    "--boundary-quads). Raises ValueError for invalid input or options (the CLI's checks), RuntimeError if the job "
    "fails.";

JobArgs job_args(double edge_length, int quads, int faces, const std::string& lattice, const std::string& optimize,
                 const std::string& rounding, long max_iterations, bool keep_better, int stiffening, int relaxation,
                 const std::string& field, const std::string& fill, const py::object& feature_angle, bool align_curves,
                 int fold_refinement_rounds, int validity_retries, bool round_curves, bool merge_cones, bool move_cones,
                 bool separate_cones, int split_cones, bool cancel_close_cones, double square_holes,
                 const py::object& features) {
  const double angle = feature_angle_degrees(feature_angle);
  return JobArgs{edge_length,
                 quads,
                 faces,
                 lattice,
                 optimize,
                 rounding,
                 field,
                 fill,
                 max_iterations,
                 keep_better,
                 stiffening,
                 relaxation,
                 angle,
                 align_curves,
                 fold_refinement_rounds,
                 validity_retries,
                 round_curves,
                 merge_cones,
                 move_cones,
                 separate_cones,
                 split_cones,
                 cancel_close_cones,
                 square_holes,
                 feature_edge_pairs(features)};
}

/// parameterize() and remesh(): the keywords of JobArgs, in this order, then the job's own.
void def_jobs(py::module_& m) {
  m.def(
      "parameterize",
      [](const py::array& V, const py::array& F, double edge_length, int quads, int faces, const std::string& lattice,
         const std::string& optimize, const std::string& rounding, long max_iterations, bool keep_better,
         int stiffening, int relaxation, const std::string& field, const std::string& fill,
         const py::object& feature_angle, bool align_curves, int fold_refinement_rounds, int validity_retries,
         bool round_curves, bool merge_cones, bool move_cones, bool separate_cones, int split_cones,
         bool cancel_close_cones, double square_holes, const py::object& features, py::object progress) {
        return parameterize_py(V, F,
                               job_args(edge_length, quads, faces, lattice, optimize, rounding, max_iterations,
                                        keep_better, stiffening, relaxation, field, fill, feature_angle, align_curves,
                                        fold_refinement_rounds, validity_retries, round_curves, merge_cones, move_cones,
                                        separate_cones, split_cones, cancel_close_cones, square_holes, features),
                               std::move(progress));
      },
      py::arg("V"), py::arg("F"), py::arg("edge_length") = 0.0, py::arg("quads") = 0, py::arg("faces") = 0,
      py::arg("lattice") = "rotated", py::arg("optimize") = "relocate", py::arg("rounding") = "search3",
      py::arg("max_iterations") = kAutoBudget, py::arg("keep_better") = true,
      py::arg("stiffening") = StiffeningOptions{}.max_iterations,
      py::arg("relaxation") = RelaxationOptions{}.iterations, py::arg("field") = "auto", py::arg("fill") = "smooth",
      py::arg("feature_angle") = py::float_(FeatureOptions{}.sharp_angle_degrees), py::arg("align_curves") = true,
      py::arg("fold_refinement_rounds") = PipelineOptions{}.fold_refinement_rounds,
      py::arg("validity_retries") = PipelineOptions{}.validity_retries,
      py::arg("round_curves") = ParamOptions{}.alignment.round_with_periods,
      py::arg("merge_cones") = PipelineOptions{}.merge_coincident_cones,
      py::arg("move_cones") = PipelineOptions{}.move_wound_cones,
      py::arg("separate_cones") = PipelineOptions{}.separate_coincident_cones,
      py::arg("split_cones") = PipelineOptions{}.split_min_quarters,
      py::arg("cancel_close_cones") = PipelineOptions{}.cancel_close_cones,
      py::arg("square_holes") = PipelineOptions{}.square_hole_grid_units, py::arg("features") = py::none(),
      py::arg("progress") = py::none(), kParameterizeDoc);
  m.def(
      "remesh",
      [](const py::array& V, const py::array& F, double edge_length, int quads, int faces, const std::string& lattice,
         const std::string& optimize, const std::string& rounding, long max_iterations, bool keep_better,
         int stiffening, int relaxation, const std::string& field, const std::string& fill,
         const py::object& feature_angle, bool align_curves, int fold_refinement_rounds, int validity_retries,
         bool round_curves, bool merge_cones, bool move_cones, bool separate_cones, int split_cones,
         bool cancel_close_cones, double square_holes, int smooth_quads, double smooth_rigidity, bool boundary_quads,
         const py::object& features, py::object progress) {
        return remesh_py(V, F,
                         job_args(edge_length, quads, faces, lattice, optimize, rounding, max_iterations, keep_better,
                                  stiffening, relaxation, field, fill, feature_angle, align_curves,
                                  fold_refinement_rounds, validity_retries, round_curves, merge_cones, move_cones,
                                  separate_cones, split_cones, cancel_close_cones, square_holes, features),
                         smooth_quads, smooth_rigidity, boundary_quads, std::move(progress));
      },
      py::arg("V"), py::arg("F"), py::arg("edge_length") = 0.0, py::arg("quads") = 0, py::arg("faces") = 0,
      py::arg("lattice") = "rotated", py::arg("optimize") = "relocate", py::arg("rounding") = "search3",
      py::arg("max_iterations") = kAutoBudget, py::arg("keep_better") = true,
      py::arg("stiffening") = StiffeningOptions{}.max_iterations,
      py::arg("relaxation") = RelaxationOptions{}.iterations, py::arg("field") = "auto", py::arg("fill") = "smooth",
      py::arg("feature_angle") = py::float_(FeatureOptions{}.sharp_angle_degrees), py::arg("align_curves") = true,
      py::arg("fold_refinement_rounds") = PipelineOptions{}.fold_refinement_rounds,
      py::arg("validity_retries") = PipelineOptions{}.validity_retries,
      py::arg("round_curves") = ParamOptions{}.alignment.round_with_periods,
      py::arg("merge_cones") = PipelineOptions{}.merge_coincident_cones,
      py::arg("move_cones") = PipelineOptions{}.move_wound_cones,
      py::arg("separate_cones") = PipelineOptions{}.separate_coincident_cones,
      py::arg("split_cones") = PipelineOptions{}.split_min_quarters,
      py::arg("cancel_close_cones") = PipelineOptions{}.cancel_close_cones,
      py::arg("square_holes") = PipelineOptions{}.square_hole_grid_units,
      py::arg("smooth_quads") = QuadSmoothingOptions{}.iterations,
      py::arg("smooth_rigidity") = QuadSmoothingOptions{}.rigidity,
      py::arg("boundary_quads") = ExtractOptions{}.quadrangulate_boundary, py::arg("features") = py::none(),
      py::arg("progress") = py::none(), kRemeshDoc);
}

}  // namespace

PYBIND11_MODULE(_quadcover, m) {
  m.doc() = "quadcover: seamless quad-aligned parameterization (QuadCover) and quad remeshing";
  m.attr("__version__") = QUADCOVER_PY_VERSION;
  register_exceptions();
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
  def_jobs(m);
}
