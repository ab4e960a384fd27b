// The command's inline OpenMP regions (process/inline_openmp_regions.h). This executable links the
// same GOMP_parallel as `dynslam`, so its own `#pragma omp parallel` regions and CHOLMOD's go
// through it. omp_get_level() inside a region tells how it ran: 0 inline, 1 in a libgomp team.
#include "inline_openmp_regions.h"

#include <omp.h>

#include <string>

#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/solver.h"
#include "src/openmp_thread_cap.h"

namespace dynslam {
namespace {

struct Region {
  int level = -1;
  int threads = 0;
  long long sum = 0;  // of 0..kTerms-1, shared out among the threads like CHOLMOD's loops
};

constexpr int kTerms = 1000;
constexpr long long kFullSum = static_cast<long long>(kTerms) * (kTerms - 1) / 2;

// A region written like CHOLMOD's: num_threads(4), a static loop split by thread number.
Region RunRegionAskingFor(int threads = 4) {
  Region region;
  long long sum = 0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
  {
#pragma omp single
    {
      region.level = omp_get_level();
      region.threads = omp_get_num_threads();
    }
#pragma omp for schedule(static)
    for (int i = 0; i < kTerms; ++i) sum += i;
  }
  region.sum = sum;
  return region;
}

class InlineOpenMpRegionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    omp_set_dynamic(0);
    omp_set_max_active_levels(1);
    ASSERT_TRUE(InlineOneThreadOpenMpRegions());
  }
  void TearDown() override { StopInliningOpenMpRegions(); }
};

TEST_F(InlineOpenMpRegionsTest, RunsARegionCappedToOneThreadInline) {
  const uint64_t before = InlinedOpenMpRegions();
  const ScopedOpenMpThreadCap one_thread(1);
  const Region region = RunRegionAskingFor();
  EXPECT_EQ(region.level, 0) << "the region went through libgomp";
  EXPECT_EQ(region.threads, 1);
  EXPECT_EQ(region.sum, kFullSum);
  EXPECT_EQ(InlinedOpenMpRegions(), before + 1);
}

TEST_F(InlineOpenMpRegionsTest, LeavesTeamsOfSeveralThreadsToLibgomp) {
  const uint64_t before = InlinedOpenMpRegions();
  const Region region = RunRegionAskingFor();
  EXPECT_EQ(region.level, 1);
  EXPECT_EQ(region.threads, 4);
  EXPECT_EQ(region.sum, kFullSum);
  EXPECT_EQ(InlinedOpenMpRegions(), before);
}

// A region nested in a team gets one thread (the maximum of active levels is 1, or it asks for
// one) but must not run inline: the thread numbers its loop is split by would be the outer team's,
// and each would sum part of the loop.
TEST_F(InlineOpenMpRegionsTest, LeavesNestedRegionsToLibgomp) {
  for (const int inner_threads : {4, 1}) {
    long long sums[2] = {0, 0};
    int levels[2] = {-1, -1};
#pragma omp parallel num_threads(2)
    {
      const int outer = omp_get_thread_num();
      const Region inner = RunRegionAskingFor(inner_threads);
      sums[outer] = inner.sum;
      levels[outer] = inner.level;
    }
    for (int outer = 0; outer < 2; ++outer) {
      EXPECT_EQ(sums[outer], kFullSum) << "inner threads " << inner_threads << ", outer " << outer;
      EXPECT_EQ(levels[outer], 2) << "inner threads " << inner_threads << ", outer " << outer;
    }
  }
}

TEST_F(InlineOpenMpRegionsTest, TheSwitchSendsEveryRegionToLibgomp) {
  StopInliningOpenMpRegions();
  const ScopedOpenMpThreadCap one_thread(1);
  const Region region = RunRegionAskingFor();
  EXPECT_EQ(region.level, 1);
  EXPECT_EQ(region.threads, 1);
  EXPECT_EQ(region.sum, kFullSum);
}

// CHOLMOD's supernodal factorisation, in a solve, calls this executable's GOMP_parallel: the symbol
// is exported to the shared libraries as in the `dynslam` command (apps/CMakeLists.txt).
TEST_F(InlineOpenMpRegionsTest, CholmodsRegionsInASolveRunInline) {
  Expected<Graph> graph = ReadGraph(std::string(DYNSLAM_SOURCE_DIR) +
                                    "/data/reference/posegraph_parking-garage/graphs/pose_graph.g2o");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  SolverOptions options;
  options.max_iterations = 1;
  options.linear_solver = LinearSolverType::kSparseNormalCholesky;
  options.sparse_backend = SparseBackend::kSuiteSparse;
  const uint64_t before = InlinedOpenMpRegions();
  ASSERT_TRUE(Solve(options, &*graph).ok());
  EXPECT_GT(InlinedOpenMpRegions(), before + 1000);  // ~5 800 supernodes per factorisation
}

}  // namespace
}  // namespace dynslam
