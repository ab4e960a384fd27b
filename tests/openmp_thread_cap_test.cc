// ScopedOpenMpThreadCap (src/openmp_thread_cap.h): the premise is checked too — without the cap
// a region that asks for four threads gets four, as CHOLMOD's supernodal regions do.
#include "src/openmp_thread_cap.h"

#include <omp.h>

#include <sstream>

#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/solver.h"

namespace dynslam {
namespace {

// The threads of a region written like CHOLMOD's: num_threads(4), whatever OMP_NUM_THREADS says.
int ThreadsInARegionAskingForFour() {
  int threads = 0;
#pragma omp parallel num_threads(4)
  {
#pragma omp single
    threads = omp_get_num_threads();
  }
  return threads;
}

TEST(OpenMpThreadCapTest, BoundsARegionThatAsksForMoreThreads) {
  ASSERT_EQ(ThreadsInARegionAskingForFour(), 4) << "premise: an uncapped region gets 4 threads";
  {
    const ScopedOpenMpThreadCap cap(1);
    ASSERT_TRUE(cap.active());
    EXPECT_EQ(ThreadsInARegionAskingForFour(), 1);
  }
  EXPECT_EQ(ThreadsInARegionAskingForFour(), 4);
}

TEST(OpenMpThreadCapTest, BoundsARegionAtTwoThreads) {
  const ScopedOpenMpThreadCap cap(2);
  ASSERT_TRUE(cap.active());
  const int threads = ThreadsInARegionAskingForFour();
  EXPECT_GE(threads, 1);
  EXPECT_LE(threads, 2);
}

TEST(OpenMpThreadCapTest, RestoresTheCallersSettings) {
  omp_set_dynamic(0);
  omp_set_num_threads(3);
  omp_set_max_active_levels(2);
  for (const int threads : {1, 2}) {
    {
      const ScopedOpenMpThreadCap cap(threads);
      if (threads == 1) {
        EXPECT_EQ(omp_get_max_active_levels(), 0);  // every region inactive: no team to wake
      } else {
        EXPECT_EQ(omp_get_max_threads(), 2);
        EXPECT_NE(omp_get_dynamic(), 0);
      }
    }
    EXPECT_EQ(omp_get_max_threads(), 3);
    EXPECT_EQ(omp_get_dynamic(), 0);
    EXPECT_EQ(omp_get_max_active_levels(), 2);
  }
}

// The cap is on while Ceres runs: the step callback runs in the thread that factors.
TEST(OpenMpThreadCapTest, SolveCapsTheThreadsItFactorsWith) {
  std::istringstream in(
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 1 1.3 0.2 0 0 0 0.3 0.95393920141694566\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
      "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n");
  Expected<Graph> graph = ReadGraph(in, "two_poses.g2o");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  omp_set_dynamic(0);
  omp_set_num_threads(4);
  SolverOptions options;
  int steps = 0;
  options.on_step = [&](const StepRecord&) {
    ++steps;
    EXPECT_EQ(ThreadsInARegionAskingForFour(), 1);
  };
  ASSERT_TRUE(Solve(options, &*graph).ok());
  EXPECT_GT(steps, 0);
  EXPECT_EQ(omp_get_max_threads(), 4);
}

}  // namespace
}  // namespace dynslam
