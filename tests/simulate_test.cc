// The front-end simulator (include/dynslam/simulate.h). Residuals are computed here by hand
// with Eigen from SPEC §1.2's equations, not with the project's cost functions.
#include "dynslam/simulate.h"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <set>
#include <sstream>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/se3.h"

namespace dynslam {
namespace {

const std::string kData = std::string(DYNSLAM_SOURCE_DIR) + "/data/kitti_tracking";

Eigen::Isometry3d Iso(const std::array<double, kPoseSize>& value) {
  return Pose{value}.ToIsometry();
}
Eigen::Vector3d Point(const std::array<double, kPoseSize>& value) {
  return Eigen::Vector3d(value[0], value[1], value[2]);
}
// Angle and translation of a pose that should be the identity.
double Deviation(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(T.linear()).angle() + T.translation().norm();
}

SimulatedScene MustSimulate(const Scene& scene, const SimulateOptions& options) {
  Expected<SimulatedScene> simulated = Simulate(scene, options);
  EXPECT_TRUE(simulated.ok()) << simulated.error().ToString();
  return std::move(simulated).value();
}

Scene KittiScene(const std::string& name, const SimulateOptions& options) {
  Expected<KittiSequence> seq = ReadKittiSequence(kData, name);
  EXPECT_TRUE(seq.ok()) << seq.error().ToString();
  Expected<Scene> scene = MakeKittiScene(*seq, options);
  EXPECT_TRUE(scene.ok()) << scene.error().ToString();
  return std::move(scene).value();
}

// Values of every vertex: the graph's initial values or the simulator's true values.
using Values = std::map<VertexId, std::array<double, kPoseSize>>;
Values InitialValues(const Graph& graph) {
  Values values;
  for (const auto& [id, vertex] : graph.vertices) values[id] = vertex.value;
  return values;
}

// Largest residual of each measured edge kind (SPEC §1.2), at `values`:
// prior Log(Z⁻¹X) → Z⁻¹X = I; between Log(Z⁻¹A⁻¹B) → Z⁻¹A⁻¹B = I; point X⁻¹m − z;
// motion m_curr − H·m_prev − z. Smoothing edges are excluded: at the truth their residual is the
// true change of motion between frames, not zero.
struct MaxResiduals {
  double prior = 0, odometry = 0, point = 0, motion = 0;
};
MaxResiduals Residuals(const Graph& graph, const Values& v) {
  MaxResiduals r;
  for (const PriorEdge& e : graph.Edges<PriorEdge>()) {
    r.prior = std::max(r.prior, Deviation(e.measurement.ToIsometry().inverse() * Iso(v.at(e.pose))));
  }
  for (const BetweenEdge& e : graph.Edges<BetweenEdge>()) {
    if (graph.vertices.at(e.from).label.role != Role::kCamera) continue;
    r.odometry = std::max(r.odometry, Deviation(e.measurement.ToIsometry().inverse() *
                                                Iso(v.at(e.from)).inverse() * Iso(v.at(e.to))));
  }
  for (const PointEdge& e : graph.Edges<PointEdge>()) {
    r.point = std::max(
        r.point, (Iso(v.at(e.pose)).inverse() * Point(v.at(e.point)) - e.measurement).norm());
  }
  for (const MotionEdge& e : graph.Edges<MotionEdge>()) {
    r.motion = std::max(r.motion, (Point(v.at(e.curr)) - Iso(v.at(e.motion)) * Point(v.at(e.prev)) -
                                   e.measurement).norm());
  }
  return r;
}

// χ² = Σ rᵀ·I·r and degrees of freedom over the noisy measurement edges (points and odometry),
// at `values`. Odometry residuals use the SE(3) Log of se3.h (tested in se3_test).
std::pair<double, int64_t> ChiSquared(const Graph& graph, const Values& v, bool points,
                                      bool odometry) {
  double chi2 = 0;
  int64_t dof = 0;
  if (points) {
    for (const PointEdge& e : graph.Edges<PointEdge>()) {
      const Eigen::Vector3d r = Iso(v.at(e.pose)).inverse() * Point(v.at(e.point)) - e.measurement;
      chi2 += r.dot(e.information * r);
      dof += 3;
    }
  }
  if (odometry) {
    for (const BetweenEdge& e : graph.Edges<BetweenEdge>()) {
      if (graph.vertices.at(e.from).label.role != Role::kCamera) continue;
      const Pose E = Compose(Inverse(e.measurement),
                             Compose(Inverse(Pose{v.at(e.from)}), Pose{v.at(e.to)}));
      const Vector6d r = Log(E);
      chi2 += r.dot(e.information * r);
      dof += 6;
    }
  }
  return {chi2, dof};
}

// With noise off, every dynamic point at k is H_gt = L_k·L_{k−1}⁻¹ (from the ground-truth
// object poses) applied to its point at k−1, and every measured edge is exact at the initial
// values, which equal the truth.
void CheckNoiseFree(const Scene& scene) {
  SimulateOptions options;
  options.noise = false;
  const SimulatedScene sim = MustSimulate(scene, options);
  const Graph& g = sim.graph;
  ASSERT_GT(g.Edges<MotionEdge>().size(), 50u);
  for (const MotionEdge& e : g.Edges<MotionEdge>()) {
    const Pose* L_prev = sim.ground_truth.Object(e.object, e.frame - 1);
    const Pose* L_curr = sim.ground_truth.Object(e.object, e.frame);
    ASSERT_TRUE(L_prev && L_curr);
    const Eigen::Isometry3d H_gt = L_curr->ToIsometry() * L_prev->ToIsometry().inverse();
    const Eigen::Vector3d predicted = H_gt * g.vertices.at(e.prev).point();
    EXPECT_LT((g.vertices.at(e.curr).point() - predicted).norm(), 1e-9)
        << "object " << e.object << " frame " << e.frame;
    EXPECT_LT(Deviation(H_gt.inverse() * g.vertices.at(e.motion).pose().ToIsometry()), 1e-9);
  }
  for (const auto& [id, vertex] : g.vertices) {
    if (vertex.label.role != Role::kCamera) continue;
    const Pose* X = sim.ground_truth.Camera(vertex.label.frame);
    ASSERT_NE(X, nullptr);
    EXPECT_LT(Deviation(X->ToIsometry().inverse() * vertex.pose().ToIsometry()), 1e-9);
  }
  const MaxResiduals at_initial = Residuals(g, InitialValues(g));
  const MaxResiduals at_truth = Residuals(g, sim.true_values);
  for (const MaxResiduals& r : {at_initial, at_truth}) {
    EXPECT_LT(r.prior, 1e-12);
    EXPECT_LT(r.odometry, 1e-9);
    EXPECT_LT(r.point, 1e-9);
    EXPECT_LT(r.motion, 1e-9);
  }
}

TEST(Simulate, NoiseFreeSyntheticIsExact) {
  CheckNoiseFree(MakeSyntheticScene(SimulateOptions()));
}

TEST(Simulate, NoiseFreeKittiIsExact) {
  SimulateOptions options;
  options.first_frame = 20;
  options.last_frame = 100;
  CheckNoiseFree(KittiScene("0003", options));
}

// At the truth, measured edges carry exactly the drawn noise: χ²/dof ≈ 1 (for N dof its
// standard deviation is √(2/N); here N > 60000, so ±0.6 %). Motion edges are exact at the truth.
TEST(Simulate, ChiSquaredAtTruthIsOne) {
  for (const uint64_t seed : {0ull, 7ull}) {
    SimulateOptions options;
    options.seed = seed;
    const SimulatedScene sim = MustSimulate(KittiScene("0003", options), options);
    const auto [chi2, dof] = ChiSquared(sim.graph, sim.true_values, true, true);
    ASSERT_GT(dof, 60000);
    std::printf("seed %llu: chi2/dof at truth %.4f over %lld dof\n",
                static_cast<unsigned long long>(seed), chi2 / static_cast<double>(dof),
                static_cast<long long>(dof));
    EXPECT_NEAR(chi2 / static_cast<double>(dof), 1.0, 0.05) << "seed " << seed;
    const auto [chi2_points, dof_points] = ChiSquared(sim.graph, sim.true_values, true, false);
    EXPECT_NEAR(chi2_points / static_cast<double>(dof_points), 1.0, 0.05) << "seed " << seed;
    // Odometry alone has 6·143 dof (σ of χ²/dof ≈ 5 %): 4σ.
    const auto [chi2_odo, dof_odo] = ChiSquared(sim.graph, sim.true_values, false, true);
    EXPECT_NEAR(chi2_odo / static_cast<double>(dof_odo), 1.0, 4 * std::sqrt(2.0 / dof_odo))
        << "seed " << seed;
    EXPECT_LT(Residuals(sim.graph, sim.true_values).motion, 1e-9);
    // The initial values are not the truth: the chained odometry drifts.
    const Pose* X_last = sim.ground_truth.Camera(sim.statistics.frames - 1);
    const Vertex* last = nullptr;
    for (const auto& [id, vertex] : sim.graph.vertices) {
      if (vertex.label.role == Role::kCamera && vertex.label.frame == sim.statistics.frames - 1) {
        last = &vertex;
      }
    }
    ASSERT_NE(last, nullptr);
    EXPECT_GT((last->pose().translation() - X_last->translation()).norm(), 0.05);
  }
}

std::string Written(const SimulatedScene& sim) {
  std::ostringstream out;
  WriteGraph(sim.graph, out);
  return out.str();
}

TEST(Simulate, SameSeedSameBytes) {
  SimulateOptions options;
  options.seed = 42;
  options.outlier_fraction = 0.05;
  const Scene scene = KittiScene("0005", options);
  const std::string a = Written(MustSimulate(scene, options));
  const std::string b = Written(MustSimulate(KittiScene("0005", options), options));
  EXPECT_EQ(a, b);
  options.seed = 43;
  EXPECT_NE(a, Written(MustSimulate(scene, options)));
  // Synthetic too.
  SimulateOptions synthetic;
  synthetic.seed = 3;
  EXPECT_EQ(Written(MustSimulate(MakeSyntheticScene(synthetic), synthetic)),
            Written(MustSimulate(MakeSyntheticScene(synthetic), synthetic)));
}

// Noise comes from its own random stream: switching it off keeps every point, track and edge.
TEST(Simulate, NoiseDoesNotChangeTheLayout) {
  SimulateOptions noisy, exact;
  exact.noise = false;
  const Scene scene = MakeSyntheticScene(noisy);
  const SimulatedScene a = MustSimulate(scene, noisy), b = MustSimulate(scene, exact);
  ASSERT_EQ(a.graph.vertices.size(), b.graph.vertices.size());
  EXPECT_EQ(a.graph.Edges<PointEdge>().size(), b.graph.Edges<PointEdge>().size());
  EXPECT_EQ(a.graph.Edges<MotionEdge>().size(), b.graph.Edges<MotionEdge>().size());
  EXPECT_EQ(a.true_values, b.true_values);
}

// FNV-1a, 64 bits: a digest that is the same with every standard library.
uint64_t Fnv1a(const std::string& bytes) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (const unsigned char c : bytes) hash = (hash ^ c) * 0x100000001b3ull;
  return hash;
}

// The options added since (noise_every_edge) change nothing when off: the files are byte for
// byte those of the simulator before them. The digests are of the graph part of files written by
// that earlier build (`dynslam simulate --synthetic --seed 1` and `--seq 0003 --frames 0:60
// --seed 1`, the lines after the '#' header).
TEST(Simulate, DefaultFilesAreThoseOfTheEarlierSimulator) {
  SimulateOptions synthetic;
  synthetic.seed = 1;
  const std::string a = Written(MustSimulate(MakeSyntheticScene(synthetic), synthetic));
  EXPECT_EQ(a.size(), 1712503u);
  EXPECT_EQ(Fnv1a(a), 0xc37419e0cd6fc464ull);
  SimulateOptions kitti;
  kitti.seed = 1;
  kitti.last_frame = 60;
  const std::string b = Written(MustSimulate(KittiScene("0003", kitti), kitti));
  EXPECT_EQ(b.size(), 2863986u);
  EXPECT_EQ(Fnv1a(b), 0x89bf4f0b285e537eull);
}

// noise_every_edge: the prior, motion and smoothing edges become measurements of the truth
// drawn from their information (χ²/dof ≈ 1 at the truth, as for points and odometry), from a
// stream of their own: every point and odometry measurement is the same as without it.
TEST(Simulate, NoiseOnEveryEdgeIsDrawnFromItsInformation) {
  SimulateOptions off, on;
  on.noise_every_edge = true;
  const Scene scene = KittiScene("0003", off);
  const SimulatedScene a = MustSimulate(scene, off), b = MustSimulate(scene, on);
  ASSERT_EQ(a.graph.Edges<PointEdge>().size(), b.graph.Edges<PointEdge>().size());
  for (size_t i = 0; i < a.graph.Edges<PointEdge>().size(); ++i) {
    ASSERT_EQ(a.graph.Edges<PointEdge>()[i].measurement, b.graph.Edges<PointEdge>()[i].measurement);
  }
  const auto [chi2_odo_a, dof_odo_a] = ChiSquared(a.graph, a.true_values, false, true);
  const auto [chi2_odo_b, dof_odo_b] = ChiSquared(b.graph, b.true_values, false, true);
  EXPECT_EQ(chi2_odo_a, chi2_odo_b);
  EXPECT_EQ(a.true_values, b.true_values);

  double chi2_motion = 0, chi2_smoothing = 0;
  int64_t dof_motion = 0, dof_smoothing = 0;
  const Values& v = b.true_values;
  for (const MotionEdge& e : b.graph.Edges<MotionEdge>()) {
    const Eigen::Vector3d r =
        Point(v.at(e.curr)) - Iso(v.at(e.motion)) * Point(v.at(e.prev)) - e.measurement;
    chi2_motion += r.dot(e.information * r);
    dof_motion += 3;
  }
  for (const BetweenEdge& e : b.graph.Edges<BetweenEdge>()) {
    if (b.graph.vertices.at(e.from).label.role != Role::kMotion) continue;
    const Vector6d r = Log(Compose(Inverse(e.measurement),
                                   Compose(Inverse(Pose{v.at(e.from)}), Pose{v.at(e.to)})));
    chi2_smoothing += r.dot(e.information * r);
    dof_smoothing += 6;
  }
  ASSERT_GT(dof_motion, 10000);
  ASSERT_GT(dof_smoothing, 600);
  // χ²/dof has standard deviation √(2/dof): 4σ.
  EXPECT_NEAR(chi2_motion / dof_motion, 1.0, 4 * std::sqrt(2.0 / dof_motion));
  EXPECT_NEAR(chi2_smoothing / dof_smoothing, 1.0, 4 * std::sqrt(2.0 / dof_smoothing));
  // Without the option the motion edges are exact and the prior sits at the truth.
  EXPECT_LT(Residuals(a.graph, a.true_values).motion, 1e-9);
  EXPECT_LT(Residuals(a.graph, a.true_values).prior, 1e-12);
  EXPECT_GT(Residuals(b.graph, b.true_values).prior, 1e-5);
}

TEST(Simulate, WrittenFileReadsBackLabelled) {
  SimulateOptions options;
  const SimulatedScene sim = MustSimulate(MakeSyntheticScene(options), options);
  std::istringstream in(Written(sim));
  Expected<Graph> read = ReadGraph(in, "synthetic.g2o");
  ASSERT_TRUE(read.ok()) << read.error().ToString();
  EXPECT_TRUE(read->labelled);
  EXPECT_EQ(read->formulation, std::optional<std::string>("frontend"));
  EXPECT_EQ(read->vertices.size(), sim.graph.vertices.size());
  EXPECT_EQ(read->NumEdges(), sim.graph.NumEdges());
  EXPECT_TRUE(UnusedVertices(*read).empty());
  const auto counts = CountEdgesByKind(*read);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kPrior)], 1);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kOdometry)], sim.statistics.frames - 1);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kSmoothing)], sim.statistics.smoothing_edges);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kMotion)], sim.statistics.motion_edges);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kDynamicPoint)], sim.statistics.dynamic_observations);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kPoint)], sim.statistics.static_observations);
}

// The synthetic scene has what it promises: three moving cars seen, one parked car as static
// scenery, an oncoming car that leaves view before the end.
TEST(Simulate, SyntheticScene) {
  SimulateOptions options;
  const SimulatedScene sim = MustSimulate(MakeSyntheticScene(options), options);
  EXPECT_EQ(sim.statistics.frames, 30);
  EXPECT_EQ(sim.statistics.moving_objects, 3);
  EXPECT_EQ(sim.statistics.moving_objects_observed, 3);
  EXPECT_EQ(sim.statistics.parked_objects, 1);
  std::map<int64_t, int64_t> last_frame;
  for (const MotionEdge& e : sim.graph.Edges<MotionEdge>()) {
    last_frame[e.object] = std::max(last_frame[e.object], e.frame);
  }
  EXPECT_EQ(last_frame.size(), 3u);
  EXPECT_LT(last_frame[2], 25);
  EXPECT_EQ(last_frame[1], 29);
  EXPECT_GT(sim.statistics.static_breaks, 0);
  EXPECT_GT(sim.statistics.dynamic_breaks, 0);
}

// Sequence 0003: an independent simulator (the GTSAM reference set's kitti_0003 scene: its
// simulate.txt and the header of its gt.txt) found cars 0, 1 and van 5 moving and objects 2, 3,
// 4, 6, 7, 8 parked.
TEST(Simulate, MovingAndParkedObjectsOf0003) {
  SimulateOptions options;
  const Scene scene = KittiScene("0003", options);
  std::set<int64_t> moving, parked;
  for (const SceneObject& object : scene.objects) (object.moving ? moving : parked).insert(object.id);
  EXPECT_EQ(moving, (std::set<int64_t>{0, 1, 5}));
  EXPECT_EQ(parked, (std::set<int64_t>{2, 3, 4, 6, 7, 8}));
}

TEST(Simulate, OutlierFraction) {
  SimulateOptions options;
  options.outlier_fraction = 0.1;
  const SimulatedScene sim = MustSimulate(KittiScene("0003", options), options);
  const double observations =
      static_cast<double>(sim.statistics.static_observations + sim.statistics.dynamic_observations);
  // Binomial: σ = √(n·0.1·0.9) ≈ 50 for n ≈ 25000; 5σ.
  EXPECT_NEAR(sim.statistics.outliers, 0.1 * observations, 5 * std::sqrt(observations * 0.09));
  const auto [chi2, dof] = ChiSquared(sim.graph, sim.true_values, true, false);
  EXPECT_GT(chi2 / static_cast<double>(dof), 10.0);  // gross errors of metres
}

// ASan + UBSan builds (scripts/sanitize) run several times slower; the bound is for real builds.
#ifdef __SANITIZE_ADDRESS__
constexpr double kEmbeddedSequenceSeconds = 60.0;
#else
constexpr double kEmbeddedSequenceSeconds = 10.0;
#endif

// Every embedded sequence simulates, quickly; the range is reflected in the frames.
TEST(Simulate, EmbeddedSequencesAreFast) {
  for (const char* name : {"0000", "0001", "0002", "0003", "0004", "0005", "0006", "0018", "0020"}) {
    const auto start = std::chrono::steady_clock::now();
    SimulateOptions options;
    const Scene scene = KittiScene(name, options);
    const SimulatedScene sim = MustSimulate(scene, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(sim.statistics.frames, static_cast<int64_t>(scene.cameras.size()));
    EXPECT_GT(sim.statistics.static_observations, 0) << name;
    EXPECT_LT(seconds, kEmbeddedSequenceSeconds) << name;  // a few seconds even when loaded
  }
}

TEST(Simulate, BadRangesAndOptionsAreErrors) {
  Expected<KittiSequence> seq = ReadKittiSequence(kData, "0003");
  ASSERT_TRUE(seq.ok());
  SimulateOptions options;
  options.first_frame = 140;
  options.last_frame = 200;
  EXPECT_FALSE(MakeKittiScene(*seq, options).ok());
  options.first_frame = 10;
  options.last_frame = 11;
  EXPECT_FALSE(MakeKittiScene(*seq, options).ok());
  SimulateOptions bad;
  bad.pixel_sigma = 0;
  EXPECT_FALSE(Simulate(MakeSyntheticScene(bad), bad).ok());
  bad = SimulateOptions();
  bad.outlier_fraction = 1.5;
  EXPECT_FALSE(Simulate(MakeSyntheticScene(bad), bad).ok());
}

}  // namespace
}  // namespace dynslam
