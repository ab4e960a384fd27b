// The Python module dynslam._dynslam (python/dynslam/__init__.py re-exports it): graph files,
// formulations, the solver, metrics and the simulator, with poses and points as NumPy arrays
// and errors as dynslam.Error carrying the file and line. Thin over the library: every number
// comes from the same code as the command line.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "dynslam/compare.h"
#include "dynslam/covariance.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/gtsam_backend.h"
#include "dynslam/ground_truth.h"
#include "dynslam/kitti.h"
#include "dynslam/metrics.h"
#include "dynslam/simulate.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"
#include "arrays.h"
#include "errors.h"
#include "options.h"

namespace py = pybind11;

namespace dynslam::python {
namespace {

// A str or os.PathLike as a path (TypeError otherwise, as open() does).
std::string PathText(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

// FileNotFoundError(ENOENT, message, path) unless `path` is a file, before a reader runs.
std::string ExistingFile(const py::object& path) {
  const std::string text = PathText(path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(text, ec)) {
    py::object error = py::module_::import("builtins").attr("FileNotFoundError")(
        ENOENT, "No such file", text);
    PyErr_SetObject(PyExc_FileNotFoundError, error.ptr());
    throw py::error_already_set();
  }
  return text;
}

// GroundTruth's pickled state: ([(frame, pose)], [(object, frame, pose)]), poses as 7-tuples of
// the in-memory layout (pose.h), so that a round trip is bit-exact.
py::tuple GroundTruthState(const GroundTruth& gt) {
  py::list cameras, objects;
  for (const auto& [frame, pose] : gt.cameras) cameras.append(py::make_tuple(frame, pose.data));
  for (const auto& [key, pose] : gt.objects) {
    objects.append(py::make_tuple(key.first, key.second, pose.data));
  }
  return py::make_tuple(cameras, objects);
}

GroundTruth GroundTruthFromState(const py::tuple& state) {
  GroundTruth gt;
  for (const py::handle item : state[0].cast<py::list>()) {
    const auto [frame, data] = item.cast<std::pair<int64_t, std::array<double, kPoseSize>>>();
    gt.cameras[frame] = Pose{data};
  }
  for (const py::handle item : state[1].cast<py::list>()) {
    const auto [object, frame, data] =
        item.cast<std::tuple<int64_t, int64_t, std::array<double, kPoseSize>>>();
    gt.objects[{object, frame}] = Pose{data};
  }
  return gt;
}

Graph GraphFromText(const std::string& text) {
  std::istringstream in(text);
  return Unwrap(ReadGraph(in, "<pickled graph>"));
}

py::dict EdgesByKind(const Graph& graph) {
  py::dict out;
  const auto counts = CountEdgesByKind(graph);
  for (const EdgeKind kind : kAllEdgeKinds) out[EdgeKindName(kind)] = counts[static_cast<int>(kind)];
  return out;
}

py::object ParseJsonText(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

struct PySolveReport {
  SolveReport report;
  Graph graph;  // at the solution

  py::dict Covariance(const py::object& ids, const py::object& kinds) const {
    std::vector<VertexId> wanted;
    if (!ids.is_none()) {
      wanted = ids.cast<std::vector<VertexId>>();
    } else {
      std::vector<CovarianceKind> parsed;
      const std::string text = kinds.is_none() ? "all" : kinds.cast<std::string>();
      if (std::optional<std::string> problem = ParseCovarianceKinds(text, &parsed)) {
        throw py::value_error("kinds: " + *problem);
      }
      wanted = VerticesOfKinds(graph, parsed);
    }
    Expected<CovarianceReport> computed = [&] {
      py::gil_scoped_release release;
      return ComputeCovariances(graph, report, wanted);
    }();
    if (!computed.ok()) throw py::value_error(computed.error().ToString());
    if (!computed->held_constant.empty()) {
      throw py::value_error("vertex " + std::to_string(computed->held_constant.front()) +
                            " is held constant in this solve: it has no covariance");
    }
    if (const auto& weak = computed->weak_directions; !weak.empty()) {
      std::string names;
      for (const WeakDirection& w : weak) {
        names += (names.empty() ? "" : ", ") + std::to_string(w.id) + " " + DirectionName(graph, w);
      }
      py::object error = py::module_::import("numpy.linalg").attr("LinAlgError");
      PyErr_SetString(error.ptr(), ("the information matrix is singular along " +
                                    std::to_string(weak.size()) + " directions: " + names).c_str());
      throw py::error_already_set();
    }
    py::dict out;
    for (const MarginalCovariance& m : computed->marginals) {
      out[py::int_(m.id)] = py::array_t<double>({m.covariance.rows(), m.covariance.cols()},
                                                {sizeof(double), sizeof(double) * m.covariance.rows()},
                                                m.covariance.data());
    }
    return out;
  }

  py::dict Convergence() const {
    const py::ssize_t n = static_cast<py::ssize_t>(report.convergence.size());
    py::array_t<int64_t> step(n), iteration(n);
    py::array_t<double> lambda(n), cost(n), trial_cost(n), time_s(n);
    py::array_t<bool> accepted(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      const StepRecord& r = report.convergence[i];
      step.mutable_at(i) = r.step;
      iteration.mutable_at(i) = r.iteration;
      lambda.mutable_at(i) = r.lambda;
      cost.mutable_at(i) = r.cost;
      trial_cost.mutable_at(i) = r.trial_cost;
      accepted.mutable_at(i) = r.accepted;
      time_s.mutable_at(i) = r.time_s;
    }
    py::dict out;
    out["step"] = step;
    out["iteration"] = iteration;
    out["lambda"] = lambda;
    out["cost"] = cost;
    out["trial_cost"] = trial_cost;
    out["accepted"] = accepted;
    out["time_s"] = time_s;
    return out;
  }

  // summary.json's contents (SPEC §4), without metrics.
  py::object Summary(const std::string& input) const {
    SolveOutputs outputs;
    outputs.input = input;
    outputs.solved = &graph;
    outputs.report = &report;
    return ParseJsonText(SummaryJson(outputs));
  }
};

// Solves a copy of `graph` without holding the GIL. A Python signal handler that raises during
// the solve (Ctrl-C's KeyboardInterrupt) stops it after its step; the exception is raised again
// when the solve is over, carrying what it reached as `.report` (termination "interrupted"), so
// that a loop of solves stops and no work is lost. (Python runs signal handlers only in the main
// thread: a solve in another thread is not interrupted.)
PySolveReport SolveReleasingTheGil(SolverOptions options, Graph graph,
                                   const std::optional<GtsamProfile>& gtsam = std::nullopt) {
  std::optional<py::error_already_set> raised;
  options.should_stop = [&raised] {
    py::gil_scoped_acquire gil;
    if (!raised && PyErr_CheckSignals() != 0) raised.emplace();  // takes the pending exception
    return raised.has_value();
  };
  Expected<SolveReport> report = [&] {
    py::gil_scoped_release release;
    return gtsam ? SolveWithGtsam(*gtsam, options, &graph) : Solve(options, &graph);
  }();
  PySolveReport out{Unwrap(std::move(report)), std::move(graph)};
  if (raised) {
    raised->value().attr("report") = py::cast(std::move(out));
    throw std::move(*raised);
  }
  return out;
}

GroundTruth AsGroundTruth(const py::object& gt);

// dynslam.compare: the library's CompareFormulations with the solutions kept. Ctrl-C stops the
// running solve after its step and raises KeyboardInterrupt once the run has ended.
py::dict Compare(const Graph& front_end, const py::object& gt,
                 const std::vector<std::string>& formulations, const py::object& build_options,
                 const std::string& start, const py::kwargs& solver_options) {
  CompareOptions options;
  options.formulations.clear();
  for (const std::string& name : formulations) {
    Formulation f;
    if (!ParseFormulation(name, &f)) {
      throw py::value_error("unknown formulation '" + name + "' (" + FormulationNames() + ")");
    }
    options.formulations.push_back(f);
  }
  if (start != "frontend" && start != "wc") {
    throw py::value_error("start must be 'frontend' or 'wc', not '" + start + "'");
  }
  options.start_from_world_centric = start == "wc";
  if (options.start_from_world_centric &&
      (options.formulations.empty() || options.formulations[0] != Formulation::kWorldCentric)) {
    throw py::value_error("start='wc': wc must come first in formulations");
  }
  options.build = ToBuildOptions(build_options.is_none() ? py::kwargs() : py::kwargs(build_options));
  options.solver = ToSolverOptions(solver_options);
  options.keep_solutions = true;
  std::optional<py::error_already_set> raised;
  options.solver.should_stop = [&raised] {
    py::gil_scoped_acquire gil;
    if (!raised && PyErr_CheckSignals() != 0) raised.emplace();
    return raised.has_value();
  };
  const std::optional<GroundTruth> truth =
      gt.is_none() ? std::nullopt : std::optional<GroundTruth>(AsGroundTruth(gt));
  Expected<CompareRun> run = [&] {
    py::gil_scoped_release release;
    return CompareFormulations(front_end, truth ? &*truth : nullptr, options);
  }();
  if (raised) throw std::move(*raised);
  if (!run.ok()) throw ErrorException{run.error()};
  py::dict results;
  for (CompareRow& row : run->rows) {
    py::dict entry;
    entry["metrics"] = row.metrics ? ParseJsonText(MetricsJson(*row.metrics)) : py::none();
    entry["report"] = py::cast(PySolveReport{std::move(row.report), std::move(*row.solution)});
    results[FormulationName(row.formulation)] = entry;
  }
  return results;
}

GroundTruth AsGroundTruth(const py::object& gt) {
  if (py::isinstance<GroundTruth>(gt)) return gt.cast<GroundTruth>();
  return Unwrap(ReadGroundTruth(ExistingFile(gt)));  // a path
}

std::pair<Graph, GroundTruth> SimulateScene(const py::object& kitti_dir,
                                            const py::object& sequence, const py::kwargs& kwargs) {
  const SimulateOptions options = ToSimulateOptions(kwargs);
  Scene scene;
  if (options.synthetic) {
    scene = MakeSyntheticScene(options);
  } else {
    if (kitti_dir.is_none() || sequence.is_none()) {
      throw py::value_error("simulate: kitti_dir and sequence are required unless synthetic=True");
    }
    const KittiSequence data =
        Unwrap(ReadKittiSequence(PathText(kitti_dir), sequence.cast<std::string>()));
    scene = Unwrap(MakeKittiScene(data, options));
  }
  SimulatedScene simulated = Unwrap(Simulate(scene, options));
  return {std::move(simulated.graph), std::move(simulated.ground_truth)};
}

void DefineErrors(py::module_& m) {
  static py::exception<ErrorException> error_type(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const ErrorException& e) {
      py::object instance =
          py::reinterpret_borrow<py::object>(error_type.ptr())(e.error.ToString());
      instance.attr("file") = e.error.file;
      instance.attr("line") = e.error.line;
      PyErr_SetObject(error_type.ptr(), instance.ptr());
    }
  });
}

void DefineTypes(py::module_& m) {
  py::class_<Graph>(m, "Graph", "A graph file in memory (SPEC §1): vertices, edges, labels.")
      .def_property_readonly("num_vertices", [](const Graph& g) { return g.vertices.size(); })
      .def_property_readonly("num_edges", &Graph::NumEdges)
      .def_property_readonly("formulation", [](const Graph& g) { return g.formulation; })
      .def_property_readonly("edges_by_kind", EdgesByKind)
      .def("with_values", WithValues, py::arg("ids"), py::arg("values"),
           "a copy with the values of vertices `ids` replaced by the rows of `values` (n×7 poses "
           "[tx ty tz qx qy qz qw], quaternions normalised, or n×3 points), as vertices() gives them")
      .def("vertices", Vertices, py::arg("role"),
           "id, object, frame, tracklet, embedded (int64 arrays; -1 where the role has no such "
           "label) and value (n×7 poses [tx ty tz qx qy qz qw] or n×3 points) of the vertices "
           "with this role")
      .def("edges", Edges, py::arg("tag"),
           "the edges with this tag (e.g. 'EDGE_SE3:QUAT'), one array per field as the file "
           "lists them: vertex ids and integers (int64), flags (bool), measurement (n×7 poses "
           "[tx ty tz qx qy qz qw] or n×3) and information (n×6×6 in the file's order, "
           "translation first, or n×3×3)")
      .def("arrays", Arrays,
           "the whole graph as arrays: {'vertices': {role: columns}, 'edges': {tag: columns}, "
           "'formulation': str or None}; Graph.from_arrays(**graph.arrays()) is the same graph")
      .def_static("from_arrays", FromArrays, py::arg("vertices"), py::arg("edges"),
                  py::arg("formulation") = py::none(),
                  "a graph from arrays as arrays() gives them. vertices: {role: {'id', 'value', "
                  "and the role's label fields}}, or {'pose': …, 'point': …} for unlabelled "
                  "vertices whose roles are inferred from the edges (SPEC §1.4); edges: {tag: "
                  "{field: array}} as edges() gives them. The rows are checked as a graph file's "
                  "lines are (SPEC §1.6); a problem raises dynslam.Error naming the table and row")
      .def("__repr__", [](const Graph& g) {
        return "<dynslam.Graph " + (g.formulation ? *g.formulation + ", " : std::string()) +
               std::to_string(g.vertices.size()) + " vertices, " + std::to_string(g.NumEdges()) +
               " edges>";
      })
      .def(py::pickle([](const Graph& g) { return py::bytes(GraphText(g)); },
                      [](const py::bytes& text) { return GraphFromText(std::string(text)); }));
  py::class_<GroundTruth>(m, "GroundTruth", "A ground-truth file (SPEC §2).")
      .def_property_readonly("num_cameras", [](const GroundTruth& g) { return g.cameras.size(); })
      .def_property_readonly("num_object_poses",
                             [](const GroundTruth& g) { return g.objects.size(); })
      .def("__repr__", [](const GroundTruth& g) {
        return "<dynslam.GroundTruth " + std::to_string(g.cameras.size()) + " cameras, " +
               std::to_string(g.objects.size()) + " object poses>";
      })
      .def(py::pickle([](const GroundTruth& gt) { return GroundTruthState(gt); },
                      [](const py::tuple& state) { return GroundTruthFromState(state); }));
  py::class_<PySolveReport>(m, "SolveReport", "What a solve reached and how (SPEC §4).")
      .def_property_readonly("graph", [](const PySolveReport& r) { return r.graph; },
                             "the graph at the solution")
      .def_property_readonly("initial_cost", [](const PySolveReport& r) { return r.report.initial_cost; })
      .def_property_readonly("final_cost", [](const PySolveReport& r) { return r.report.final_cost; })
      .def_property_readonly("steps", [](const PySolveReport& r) { return r.report.steps; })
      .def_property_readonly("extrapolations",
                             [](const PySolveReport& r) { return r.report.extrapolations; })
      .def_property_readonly("gauge_moves",
                             [](const PySolveReport& r) { return r.report.gauge_moves; })
      .def_property_readonly("iterations", [](const PySolveReport& r) { return r.report.iterations; })
      .def_property_readonly("termination", [](const PySolveReport& r) { return r.report.termination; })
      .def_property_readonly("usable", [](const PySolveReport& r) { return r.report.usable; })
      .def("__repr__", [](const PySolveReport& r) {
        std::ostringstream text;
        text.precision(12);
        text << "<dynslam.SolveReport " << r.report.termination << ", " << r.report.steps
             << " steps, cost " << r.report.initial_cost << " -> " << r.report.final_cost << ">";
        return text.str();
      })
      .def_property_readonly("convergence", &PySolveReport::Convergence,
                             "convergence.csv's columns as arrays (SPEC §4)")
      .def("summary", &PySolveReport::Summary, py::arg("input") = "",
           "summary.json's contents as a dict (SPEC §4)")
      .def("covariance", &PySolveReport::Covariance, py::arg("ids") = py::none(),
           py::arg("kinds") = py::none(),
           "marginal covariances at the solution (docs/COVARIANCE.md): {vertex id: array} for "
           "the vertex ids given, or for the kinds ('cameras', 'motions', 'object_poses', "
           "'points', 'all'; default 'all'); a pose's 6x6 over [omega; rho], a point's 3x3. "
           "ValueError for an unknown kind or a vertex held constant, numpy.linalg.LinAlgError "
           "naming the weakly determined variables when the information matrix is singular");
}

void DefineFunctions(py::module_& m) {
  m.def("read_graph", [](const py::object& path, bool skip_unknown_tags, bool repair_information) {
    ReadOptions options;
    options.skip_unknown_tags = skip_unknown_tags;
    options.repair_information = repair_information;
    return Unwrap(ReadGraph(ExistingFile(path), options));
  }, py::arg("path"), py::arg("skip_unknown_tags") = false, py::arg("repair_information") = false,
     "a graph file (SPEC §1); path: str or path-like; FileNotFoundError when there is none, "
     "dynslam.Error (.file, .line) for bad content");
  m.def("write_graph", [](const Graph& graph, const py::object& path) {
    if (Status s = WriteGraph(graph, PathText(path)); !s.ok()) throw ErrorException{s.error()};
  }, py::arg("graph"), py::arg("path"));
  m.def("read_ground_truth", [](const py::object& path) {
    return Unwrap(ReadGroundTruth(ExistingFile(path)));
  }, py::arg("path"), "a ground-truth file (SPEC §2); path: str or path-like");
  static const std::string build_doc =
      "build one formulation from a front end (SPEC §3); gt: a GroundTruth or a path; start: a "
      "solved wc Graph of the same front end to take oc_a/oc_b/oc_c's initial values from "
      "(SPEC §3.5 start wc).\n\nBuild options (keyword arguments):\n" + BuildOptionsDoc();
  static const std::string solve_doc =
      "solve a copy of the graph; returns a SolveReport. backend='ceres' (the default), or "
      "'gtsam' / 'gtsam:PROFILE' (GTSAM's optimisers: released, tight, tight_exact, dogleg, "
      "gn; a build with GTSAM, scripts/build_gtsam).\n\nSolver options (keyword "
      "arguments):\n" + SolverOptionsDoc();
  m.def("build", [](const Graph& front_end, const std::string& formulation, const py::object& gt,
                    const py::object& start, const py::kwargs& options) {
    Formulation f;
    if (!ParseFormulation(formulation, &f)) {
      throw py::value_error("unknown formulation '" + formulation + "' (" +
                            FormulationNames() + ")");
    }
    const std::optional<GroundTruth> truth =
        gt.is_none() ? std::nullopt : std::optional<GroundTruth>(AsGroundTruth(gt));
    BuildReport report;
    const BuildOptions build_options = ToBuildOptions(options);
    Graph built = Unwrap(BuildFormulation(front_end, f, build_options,
                                          truth ? &*truth : nullptr, &report));
    if (!start.is_none()) {
      if (!py::isinstance<Graph>(start)) {
        throw py::type_error("start: a solved wc Graph (read_graph or solve(...).graph)");
      }
      const Status s = StartFromWorldCentric(front_end, start.cast<const Graph&>(), build_options,
                                             truth ? &*truth : nullptr, &built);
      if (!s.ok()) throw ErrorException{s.error()};
    }
    return built;
  }, py::arg("frontend"), py::arg("formulation"), py::arg("gt") = py::none(),
     py::arg("start") = py::none(), build_doc.c_str());
  m.def("solve", [](const Graph& graph, const std::string& backend, const py::kwargs& options) {
    Expected<std::optional<GtsamProfile>> gtsam = ParseBackend(backend);
    if (!gtsam.ok()) throw py::value_error(gtsam.error().message);
    return SolveReleasingTheGil(ToSolverOptions(options), graph, *gtsam);
  }, py::arg("graph"), py::arg("backend") = "ceres", solve_doc.c_str());
  static const std::string compare_doc =
      "every formulation built from one front end (identical data) and solved the same way, as "
      "`dynslam compare` does. Returns {formulation: {'report': SolveReport, 'metrics': dict or "
      "None}}; metrics need ground truth (a GroundTruth or a path). start='wc': oc_a, oc_b and "
      "oc_c start from wc's solution (SPEC §3.5; wc must come first in `formulations`); "
      "build_options: a dict of build options (help(dynslam.build)).\n\nSolver options "
      "(keyword arguments):\n" + SolverOptionsDoc();
  m.def("compare", Compare, py::arg("frontend"), py::arg("gt") = py::none(),
        py::arg("formulations") = [] {
          std::vector<std::string> names;
          for (const FormulationInfo& info : Formulations()) names.push_back(info.name);
          return names;
        }(),
        py::arg("build_options") = py::none(), py::arg("start") = "frontend",
        compare_doc.c_str());
  m.def("metrics", [](const Graph& graph, const py::object& gt) {
    return ParseJsonText(MetricsJson(ComputeMetrics(graph, AsGroundTruth(gt))));
  }, py::arg("graph"), py::arg("gt"), "SPEC §5 metrics as a dict shaped like metrics.json");
  static const std::string simulate_doc =
      "simulate(kitti_dir=None, sequence=None, **options) -> (Graph, GroundTruth)\n\n"
      "A simulated front end on KITTI sequence `sequence` (from `kitti_dir`, by default the "
      "embedded data) or, with synthetic=True, on the synthetic scene, and its ground truth "
      "(docs/SIMULATOR.md).\n\nOptions (keyword arguments, as `dynslam simulate`'s flags):\n" +
      SimulateOptionsDoc();
  m.def("simulate", SimulateScene, py::arg("kitti_dir") = py::none(),
        py::arg("sequence") = py::none(), simulate_doc.c_str());
}

}  // namespace
}  // namespace dynslam::python

PYBIND11_MODULE(_dynslam, m) {
  m.doc() = "dynslam: Dynamic SLAM back ends on Ceres Solver";
  dynslam::python::DefineErrors(m);
  dynslam::python::DefineTypes(m);
  dynslam::python::DefineFunctions(m);
  pybind11::tuple names(dynslam::Formulations().size());
  for (size_t i = 0; i < dynslam::Formulations().size(); ++i) {
    names[i] = dynslam::Formulations()[i].name;
  }
  m.attr("FORMULATIONS") = names;  // the formulation table's order (formulation.h)
}
