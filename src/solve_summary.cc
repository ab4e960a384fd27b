// SolveSummaryText (solve_output.h): what `dynslam solve` prints after a solve.
#include <cstdarg>
#include <cstdio>

#include "dynslam/formulation.h"
#include "dynslam/solve_output.h"

namespace dynslam {
namespace {

// Appends printf's text of `format` to `out`.
__attribute__((format(printf, 2, 3))) void Appendf(std::string* out, const char* format, ...) {
  va_list args, copy;
  va_start(args, format);
  va_copy(copy, args);
  const int size = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  if (size > 0) {
    const size_t end = out->size();
    out->resize(end + static_cast<size_t>(size) + 1);
    std::vsnprintf(out->data() + end, static_cast<size_t>(size) + 1, format, args);
    out->resize(end + static_cast<size_t>(size));
  }
  va_end(args);
}

void AppendCounts(const SolveReport& r, std::string* out) {
  *out += "variables:";
  for (size_t i = 0; i < kAllRoles.size(); ++i) {
    if (r.variables_by_role[i] > 0) {
      Appendf(out, " %s %lld", RoleName(kAllRoles[i]), static_cast<long long>(r.variables_by_role[i]));
    }
  }
  if (r.unused_variables > 0) {
    Appendf(out, " (unused, held constant: %lld)", static_cast<long long>(r.unused_variables));
  }
  *out += "\nedges:";
  for (const EdgeKind kind : kAllEdgeKinds) {
    const int64_t n = r.edges_by_kind[static_cast<int>(kind)];
    if (n > 0) Appendf(out, " %s %lld", EdgeKindName(kind), static_cast<long long>(n));
  }
  *out += "\n";
}

}  // namespace

std::string MetricsText(const Metrics& m) {
  std::string text;
  Appendf(&text,
          "metrics (SPEC §5): camera %.4f deg %.4f m over %lld pairs; object motion %.4f deg %.4f "
          "m over %lld motions; object pose %.4f deg %.4f m over %lld pairs\n",
          m.camera.mean_rot_deg, m.camera.mean_trans_m, static_cast<long long>(m.camera.count),
          m.object_motion.mean_rot_deg, m.object_motion.mean_trans_m,
          static_cast<long long>(m.object_motion.count), m.object_pose.mean_rot_deg,
          m.object_pose.mean_trans_m, static_cast<long long>(m.object_pose.count));
  return text;
}

std::string SolveSummaryText(const SolveOutputs& outputs, const std::string& out_dir) {
  const SolveReport& r = *outputs.report;
  std::string text;
  Appendf(&text, "%s (%s)\n", outputs.input.c_str(), FormulationLabelOf(*outputs.solved).c_str());
  AppendCounts(r, &text);
  Appendf(&text, "cost: %.12g -> %.12g\n", r.initial_cost, r.final_cost);
  Appendf(&text, "iterations: %d accepted of %d steps, %d extrapolations and %d gauge moves; %s (%s)\n",
          r.iterations, r.steps, r.extrapolations, r.gauge_moves, r.termination.c_str(),
          r.termination_detail.c_str());
  Appendf(&text,
          "time: %.3f s total = %.3f s set-up + %.3f s minimiser (%.3f s evaluation, %.3f s linear "
          "solves)\n",
          r.time_total_s, r.time_preprocessor_s, r.time_minimizer_s, r.time_evaluation_s,
          r.time_linear_solver_s);
  for (const std::string& warning : outputs.warnings) text += "warning: " + warning + "\n";
  for (const std::string& warning : r.warnings) text += "warning: " + warning + "\n";
  if (const CovarianceReport* c = outputs.covariance; c != nullptr && c->weak_directions.empty()) {
    Appendf(&text, "covariances: %zu variables in %.3f s (covariances.csv)\n", c->marginals.size(),
            c->time_s);
  }
  text += "outputs: " + out_dir + "\n";
  if (outputs.metrics) text += MetricsText(*outputs.metrics);
  return text;
}

}  // namespace dynslam
