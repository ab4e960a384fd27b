// Every formulation built from one front end (identical data, SPEC §3), solved the same way and
// scored the same way (SPEC §5), and the paper's Tables I–III of the results: what
// `dynslam compare` and dynslam.compare() in Python do.
#ifndef DYNSLAM_COMPARE_H_
#define DYNSLAM_COMPARE_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dynslam/compat.h"
#include "dynslam/consistency.h"
#include "dynslam/covariance.h"
#include "dynslam/formulation.h"
#include "dynslam/metrics.h"
#include "dynslam/solver.h"
#include "dynslam/trajectory_export.h"

namespace dynslam {

struct CompareRow;

struct CompareOptions {
  std::vector<Formulation> formulations{std::begin(kAllFormulations), std::end(kAllFormulations)};
  BuildOptions build;
  SolverOptions solver;  // its should_stop also ends the run after the formulation it stopped
  // Solves each formulation instead of Solve (solver.h) when set: another backend, such as the
  // GTSAM backend's SolveWithGtsam (gtsam_backend.h). Covariances are still covariance.h's.
  std::function<Expected<SolveReport>(const SolverOptions&, Graph*)> solve;
  Compat compat;         // applied to `build` and, per formulation, to `solver`
  // SPEC §3.5 start wc: oc_a, oc_b and oc_c start from wc's solution (wc must come first).
  bool start_from_world_centric = false;
  // Marginal covariances of these kinds per formulation (and NEES with ground truth);
  // `covariance_kinds` is the request as given, for summary.json.
  std::vector<CovarianceKind> covariance;
  std::string covariance_kinds;
  // When set: each formulation's graph.g2o, solve outputs (SPEC §4) and build.txt in
  // out_dir/<f>/, and the trajectory files of `export_options` there.
  std::string out_dir;
  ExportOptions export_options;
  // With out_dir: a formulation whose finished solve is already there — the same built graph
  // and solver options, ended by convergence or the step limit — is read back, not solved again.
  bool resume = false;
  std::string front_end_name = "front-end";  // for the build reports
  bool keep_solutions = false;                // CompareRow::solution
  // Progress: before each formulation's solve (with the graph as built) and after it.
  std::function<void(Formulation, const Graph&)> on_solve_start;
  std::function<void(const CompareRow&)> on_row;
};

struct CompareRow {
  Formulation formulation = Formulation::kWorldCentric;
  int64_t variables = 0;  // as built
  int64_t edges = 0;
  SolveReport report;  // read back from summary.json when `reused`
  std::optional<Metrics> metrics;          // with ground truth
  std::optional<Consistency> consistency;  // with covariances and ground truth
  bool reused = false;
  std::optional<Graph> solution;  // with keep_solutions
};

struct CompareRun {
  std::vector<CompareRow> rows;  // in the order of CompareOptions::formulations
  bool stopped = false;          // should_stop ended it early
};

// An Error when a formulation cannot be built, solved or written; the rows before it are lost
// with it (their outputs, with out_dir, are not).
Expected<CompareRun> CompareFormulations(const Graph& front_end, const GroundTruth* ground_truth,
                                         const CompareOptions& options);

// tables.md and tables.csv (table,formulation,object,quantity,value): Tables I–III when the
// rows have metrics, else what each solve did; a NEES table with covariances; notes first on
// --start wc, read-back rows and --compat.
struct CompareTables {
  std::string markdown;
  std::string csv;
};
CompareTables TablesOf(const CompareRun& run, const CompareOptions& options);

}  // namespace dynslam

#endif  // DYNSLAM_COMPARE_H_
