#include "dynslam/consistency.h"

#include <cmath>

#include <Eigen/Cholesky>

#include "dynslam/se3.h"

namespace dynslam {
namespace {

// The standard normal's p-quantile (Acklam's rational approximation, relative error < 1.2e-9).
double NormalQuantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double low = 0.02425;
  if (p < low) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > 1 - low) return -NormalQuantile(1 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

class Accumulator {
 public:
  void Add(const Pose& estimate, const Pose& truth, const Eigen::MatrixXd& covariance) {
    const Vector6d delta = Log(Compose(Inverse(estimate), truth));
    sum_ += delta.dot(covariance.ldlt().solve(delta));
    ++count_;
  }
  NeesMean Finish() const {
    NeesMean out;
    out.count = count_;
    if (count_ == 0) return out;
    out.mean = sum_ / count_;
    const double k = static_cast<double>(out.dim * count_);
    out.band_low = ChiSquaredQuantile(0.025, k) / count_;
    out.band_high = ChiSquaredQuantile(0.975, k) / count_;
    return out;
  }

 private:
  double sum_ = 0;
  int64_t count_ = 0;
};

}  // namespace

double ChiSquaredQuantile(double p, double k) {
  const double s = 2.0 / (9.0 * k);
  return k * std::pow(1 - s + NormalQuantile(p) * std::sqrt(s), 3);
}

Consistency ComputeConsistency(const Graph& solved, const CovarianceReport& covariance,
                               const GroundTruth& ground_truth) {
  Accumulator cameras, motions, object_poses;
  for (const MarginalCovariance& m : covariance.marginals) {
    const Vertex& v = solved.vertices.at(m.id);
    const Label& label = v.label;
    if (label.role == Role::kCamera) {
      if (const Pose* truth = ground_truth.Camera(label.frame)) {
        cameras.Add(v.pose(), *truth, m.covariance);
      }
    } else if (label.role == Role::kMotion) {
      const Pose* now = ground_truth.Object(label.object, label.frame);
      const Pose* before = ground_truth.Object(label.object, label.frame - 1);
      if (now != nullptr && before != nullptr) {
        motions.Add(v.pose(), Compose(*now, Inverse(*before)), m.covariance);
      }
    } else if (label.role == Role::kObjectPose) {
      if (const Pose* truth = ground_truth.Object(label.object, label.frame)) {
        object_poses.Add(v.pose(), *truth, m.covariance);
      }
    }
  }
  return {cameras.Finish(), motions.Finish(), object_poses.Finish()};
}

}  // namespace dynslam
