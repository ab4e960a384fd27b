// The same input and options with one thread give byte-identical outputs (issue: embeddable).
// convergence.csv and summary.json carry wall-clock times, so only their other columns and keys
// count.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"

namespace dynslam {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path SolveInto(const std::string& name) {
  const fs::path graph_path =
      fs::path(DYNSLAM_SOURCE_DIR) / "data" / "reference" / "synthetic" / "graphs" / "oc_b.g2o";
  Expected<Graph> graph = ReadGraph(graph_path.string());
  EXPECT_TRUE(graph.ok());
  SolverOptions options;
  options.threads = 1;
  Expected<SolveReport> report = Solve(options, &*graph);
  EXPECT_TRUE(report.ok());
  SolveOutputs outputs;
  outputs.input = graph_path.string();
  outputs.solved = &*graph;
  outputs.report = &*report;
  // The pid keeps concurrent runs of the suite (release and sanitizer builds) apart.
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  EXPECT_TRUE(WriteSolveOutputs(dir.string(), outputs).ok());
  return dir;
}

TEST(DeterminismTest, OneThreadGivesByteIdenticalOutputs) {
  const fs::path first = SolveInto("dynslam_determinism_1");
  const fs::path second = SolveInto("dynslam_determinism_2");
  for (const char* file : {"solution.g2o", "cameras.csv", "motions.csv", "object_poses.csv"}) {
    EXPECT_EQ(Slurp(first / file), Slurp(second / file)) << file;
  }
  // convergence.csv without its last column (time_s).
  auto without_times = [](const std::string& csv) {
    return std::regex_replace(csv, std::regex(",[^,\n]*\n"), "\n");
  };
  EXPECT_EQ(without_times(Slurp(first / "convergence.csv")),
            without_times(Slurp(second / "convergence.csv")));
  // summary.json without its "time_s" object (phase timings, SPEC §4).
  auto without_time_object = [](const std::string& json) {
    return std::regex_replace(json, std::regex("\"time_s\": *\\{[^}]*\\}"), "\"time_s\": {}");
  };
  const std::string summary = Slurp(first / "summary.json");
  ASSERT_NE(summary.find("\"time_s\""), std::string::npos);
  EXPECT_EQ(without_time_object(summary), without_time_object(Slurp(second / "summary.json")));
  EXPECT_FALSE(Slurp(first / "solution.g2o").empty());
  fs::remove_all(first);
  fs::remove_all(second);
}

}  // namespace
}  // namespace dynslam
