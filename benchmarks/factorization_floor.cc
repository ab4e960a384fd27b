// The floor of a solver step (issue 13, docs/BENCHMARKS.md): the time of one numeric sparse
// Cholesky factorisation of the damped normal matrix JᵀJ + λ·diag(JᵀJ) of a graph at its initial
// values, and of the reduced camera matrix the Schur solvers factor (the points dynslam
// eliminates first, SolveReport::eliminated_first, removed by the Schur complement). Each matrix
// is factored by CHOLMOD simplicial, CHOLMOD supernodal and Eigen's SimplicialLDLT, after a
// fill-reducing analysis that is not timed: a solver analyses once and factors every step.
// The analysis is AMD on the scalar matrix (Ceres 2.1 runs AMD on the variable blocks instead)
// unless --orderings names others for CHOLMOD: metis (METIS on the matrix) or nesdis (CHOLMOD's
// nested dissection); Eigen's rows are always AMD.
//
//   factorization_floor GRAPH [--repeat N] [--lambda X] [--orderings amd,metis,nesdis]
//
// Prints one CSV row per (matrix, method, ordering): graph, matrix, method, ordering, n,
// nnz_lower, nnz_factor, flops (CHOLMOD's count for its factorisation; -1 for Eigen), seconds
// (the median of N factorisations). CHOLMOD runs with one thread, its regions inline as in the
// `dynslam` command (process/inline_openmp_regions.h; DYNSLAM_INLINE_OPENMP=0 for libgomp's).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cholmod.h>

#include "dynslam/graph_io.h"
#include "dynslam/solver.h"
#include "src/openmp_thread_cap.h"
#ifdef DYNSLAM_INLINE_OPENMP_REGIONS
#include "inline_openmp_regions.h"
#endif

namespace dynslam {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column major, as CHOLMOD and Eigen factor

template <typename F>
double MedianSeconds(int repeat, F&& f) {
  std::vector<double> seconds;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

struct Ordering {
  const char* name;
  int cholmod_code;
};
constexpr Ordering kOrderings[] = {
    {"amd", CHOLMOD_AMD}, {"metis", CHOLMOD_METIS}, {"nesdis", CHOLMOD_NESDIS}};

struct Row {
  const char* method;
  const char* ordering;
  int64_t nnz_factor;
  double flops;  // -1 where the factoriser does not count them
  double seconds;
};

Row FactorEigen(const SparseMatrix& a, int repeat) {
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  ldlt.analyzePattern(a);
  const double seconds = MedianSeconds(repeat, [&] { ldlt.factorize(a); });
  if (ldlt.info() != Eigen::Success) std::fprintf(stderr, "warning: Eigen LDLT failed\n");
  return {"eigen_simplicial_ldlt", "amd", ldlt.matrixL().nestedExpression().nonZeros(), -1,
          seconds};
}

Row FactorCholmod(const SparseMatrix& a, bool supernodal, const Ordering& ordering, int repeat) {
  const char* method = supernodal ? "cholmod_supernodal" : "cholmod_simplicial";
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  common.nmethods = 1;
  common.method[0].ordering = ordering.cholmod_code;
  // A view of the lower triangle (stype = -1) of `a`.
  SparseMatrix lower = a.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<size_t>(lower.rows());
  view.nzmax = static_cast<size_t>(lower.nonZeros());
  view.p = lower.outerIndexPtr();
  view.i = lower.innerIndexPtr();
  view.x = lower.valuePtr();
  view.stype = -1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  cholmod_factor* factor = cholmod_analyze(&view, &common);
  if (factor == nullptr) {  // e.g. a CHOLMOD built without METIS
    std::fprintf(stderr, "warning: CHOLMOD's %s analysis failed (status %d)\n", ordering.name,
                 common.status);
    cholmod_finish(&common);
    return {method, ordering.name, -1, -1, -1};
  }
  const ScopedOpenMpThreadCap one_thread(1);  // as `dynslam solve` runs CHOLMOD
  const double seconds =
      MedianSeconds(repeat, [&] { cholmod_factorize(&view, factor, &common); });
  if (common.status != CHOLMOD_OK) std::fprintf(stderr, "warning: CHOLMOD status %d\n", common.status);
  const Row row{method, ordering.name, static_cast<int64_t>(common.lnz), common.fl, seconds};
  cholmod_free_factor(&factor, &common);
  cholmod_finish(&common);
  return row;
}

// S = A_ff − A_fe·A_ee⁻¹·A_ef, with A_ee block diagonal (one 3×3 block per eliminated point).
SparseMatrix SchurComplement(const SparseMatrix& a, const SystemJacobian& system) {
  std::vector<int> eliminated_columns, kept_columns;
  for (size_t g = 0; g < system.variables.size(); ++g) {
    auto& columns = system.eliminated_first[g] ? eliminated_columns : kept_columns;
    for (int c = system.first_column[g]; c < system.first_column[g + 1]; ++c) columns.push_back(c);
  }
  auto select = [&](const std::vector<int>& rows, const std::vector<int>& cols) {
    std::vector<int> row_index(a.rows(), -1), col_index(a.cols(), -1);
    for (size_t i = 0; i < rows.size(); ++i) row_index[rows[i]] = static_cast<int>(i);
    for (size_t j = 0; j < cols.size(); ++j) col_index[cols[j]] = static_cast<int>(j);
    std::vector<Eigen::Triplet<double>> triplets;
    for (int k = 0; k < a.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
        if (row_index[it.row()] >= 0 && col_index[it.col()] >= 0) {
          triplets.emplace_back(row_index[it.row()], col_index[it.col()], it.value());
        }
      }
    }
    SparseMatrix out(static_cast<int>(rows.size()), static_cast<int>(cols.size()));
    out.setFromTriplets(triplets.begin(), triplets.end());
    return out;
  };
  const SparseMatrix a_ee = select(eliminated_columns, eliminated_columns);
  const SparseMatrix a_fe = select(kept_columns, eliminated_columns);
  const SparseMatrix a_ff = select(kept_columns, kept_columns);
  std::vector<Eigen::Triplet<double>> inverse;
  for (int b = 0; b < a_ee.rows(); b += kPointSize) {
    const Eigen::Matrix3d block_inverse = Eigen::Matrix3d(a_ee.block(b, b, 3, 3)).inverse();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) inverse.emplace_back(b + i, b + j, block_inverse(i, j));
    }
  }
  SparseMatrix a_ee_inverse(a_ee.rows(), a_ee.cols());
  a_ee_inverse.setFromTriplets(inverse.begin(), inverse.end());
  SparseMatrix s = a_ff - SparseMatrix(a_fe * a_ee_inverse * SparseMatrix(a_fe.transpose()));
  s.makeCompressed();
  return s;
}

// "amd,nesdis" → those orderings; nothing for an unknown name.
std::optional<std::vector<Ordering>> ParseOrderings(const std::string& list) {
  std::vector<Ordering> out;
  size_t begin = 0;
  while (begin <= list.size()) {
    const size_t end = std::min(list.find(',', begin), list.size());
    const std::string name = list.substr(begin, end - begin);
    const auto* found = std::find_if(std::begin(kOrderings), std::end(kOrderings),
                                     [&](const Ordering& o) { return name == o.name; });
    if (found == std::end(kOrderings)) return std::nullopt;
    out.push_back(*found);
    begin = end + 1;
  }
  return out;
}

int Run(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: factorization_floor GRAPH [--repeat N] [--lambda X] "
                         "[--orderings amd,metis,nesdis]\n");
    return 2;
  }
  const std::string path = argv[1];
  int repeat = 5;
  double lambda = 1e-6;  // dynslam's first LM damping on graphs with points (solver.h)
  std::vector<Ordering> orderings = {kOrderings[0]};
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--repeat") {
      repeat = std::max(1, std::atoi(argv[i + 1]));
    } else if (flag == "--lambda") {
      lambda = std::atof(argv[i + 1]);
    } else if (flag == "--orderings") {
      std::optional<std::vector<Ordering>> parsed = ParseOrderings(argv[i + 1]);
      if (!parsed) {
        std::fprintf(stderr, "--orderings takes a comma-separated list of amd, metis, nesdis\n");
        return 2;
      }
      orderings = *parsed;
    } else {
      std::fprintf(stderr, "unknown option %s\n", flag.c_str());
      return 2;
    }
  }
  Expected<Graph> graph = ReadGraph(path);
  if (!graph.ok()) {
    std::fprintf(stderr, "error: %s\n", graph.error().ToString().c_str());
    return 1;
  }
  Expected<SystemJacobian> system = EvaluateJacobian(*graph);
  if (!system.ok()) {
    std::fprintf(stderr, "error: %s\n", system.error().ToString().c_str());
    return 1;
  }
  const SparseMatrix jacobian = system->jacobian;
  SparseMatrix normal = SparseMatrix(jacobian.transpose()) * jacobian;
  for (int i = 0; i < normal.rows(); ++i) {
    normal.coeffRef(i, i) += lambda * std::clamp(normal.coeff(i, i), 1e-6, 1e32);
  }
  normal.makeCompressed();
  const SparseMatrix reduced = SchurComplement(normal, *system);

  std::printf("graph,matrix,method,ordering,n,nnz_lower,nnz_factor,flops,seconds\n");
  for (const auto& [name, matrix] : {std::pair<const char*, const SparseMatrix&>{"normal", normal},
                                     {"reduced", reduced}}) {
    const int64_t nnz_lower = SparseMatrix(matrix.triangularView<Eigen::Lower>()).nonZeros();
    std::vector<Row> rows;
    for (const Ordering& ordering : orderings) {
      rows.push_back(FactorCholmod(matrix, false, ordering, repeat));
      rows.push_back(FactorCholmod(matrix, true, ordering, repeat));
      if (ordering.cholmod_code == CHOLMOD_AMD) rows.push_back(FactorEigen(matrix, repeat));
    }
    for (const Row& row : rows) {
      std::printf("%s,%s,%s,%s,%lld,%lld,%lld,%.6g,%.6g\n", path.c_str(), name, row.method,
                  row.ordering, static_cast<long long>(matrix.rows()),
                  static_cast<long long>(nnz_lower), static_cast<long long>(row.nnz_factor),
                  row.flops, row.seconds);
    }
  }
  return 0;
}

}  // namespace
}  // namespace dynslam

int main(int argc, char** argv) {
#ifdef DYNSLAM_INLINE_OPENMP_REGIONS
  dynslam::InlineOneThreadOpenMpRegions();  // CHOLMOD's regions as `dynslam solve` runs them
#endif
  return dynslam::Run(argc, argv);
}
