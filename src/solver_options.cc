#include "dynslam/solver_options.h"

#include "src/number_text.h"

namespace dynslam {

const char* Name(MinimizerType type) {
  switch (type) {
    case MinimizerType::kLevenbergMarquardt: return "lm";
    case MinimizerType::kDogleg: return "dogleg";
    case MinimizerType::kDynslamLm: return "dynslam_lm";
    case MinimizerType::kAuto: return "auto";
  }
  return "?";
}

const char* Name(LinearSolverType type) {
  switch (type) {
    case LinearSolverType::kSparseSchur: return "sparse_schur";
    case LinearSolverType::kSparseNormalCholesky: return "sparse_normal_cholesky";
    case LinearSolverType::kIterativeSchur: return "iterative_schur";
    case LinearSolverType::kDenseSchur: return "dense_schur";
    case LinearSolverType::kAuto: return "auto";
  }
  return "?";
}

const char* Name(SparseBackend backend) {
  switch (backend) {
    case SparseBackend::kSuiteSparse: return "suitesparse";
    case SparseBackend::kEigen: return "eigen";
    case SparseBackend::kAuto: return "auto";
  }
  return "?";
}

const char* Name(Frame frame) { return frame == Frame::kWorld ? "world" : "object"; }

std::string RobustText(const RobustKernels& kernels) {
  std::string text;
  for (const EdgeKind kind : kAllEdgeKinds) {
    const RobustKernel& kernel = kernels[static_cast<int>(kind)];
    if (kernel.type == RobustKernel::Type::kNone) continue;
    text += (text.empty() ? "" : ",") + std::string(EdgeKindName(kind)) + "=" +
            (kernel.type == RobustKernel::Type::kHuber ? "huber:" : "cauchy:") +
            NumberText(kernel.threshold);
  }
  return text;
}

std::optional<std::string> ParseRobust(const std::string& text, RobustKernels* kernels) {
  RobustKernels parsed{};
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    begin = comma + 1;
    if (item.empty()) continue;
    const size_t eq = item.find('=');
    const size_t colon = item.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos) {
      return "'" + item + "' is not KIND=huber:K or KIND=cauchy:K";
    }
    const std::string kind_name = item.substr(0, eq);
    const std::string type = item.substr(eq + 1, colon - eq - 1);
    int kind = -1;
    for (const EdgeKind k : kAllEdgeKinds) {
      if (kind_name == EdgeKindName(k)) kind = static_cast<int>(k);
    }
    if (kind < 0) return "unknown edge kind '" + kind_name + "'";
    RobustKernel& kernel = parsed[kind];
    if (type == "huber") {
      kernel.type = RobustKernel::Type::kHuber;
    } else if (type == "cauchy") {
      kernel.type = RobustKernel::Type::kCauchy;
    } else {
      return "unknown kernel '" + type + "' (huber or cauchy)";
    }
    const std::string threshold = item.substr(colon + 1);
    if (ParseReal(threshold, 0, 1e300, &kernel.threshold) || !(kernel.threshold > 0)) {
      return "threshold '" + threshold + "' is not a positive number";
    }
  }
  *kernels = parsed;
  return std::nullopt;
}

std::string RobustKindNames() {
  std::string names;
  for (const EdgeKind kind : kAllEdgeKinds) {
    names += std::string(names.empty() ? "" : " ") + EdgeKindName(kind);
  }
  return names;
}

}  // namespace dynslam
