// JSON at the file boundary (src/json_io.h, nlohmann-json): vertex ids above 2^53 survive
// summary.json, output does not depend on the C locale, \u escapes decode to UTF-8, and what
// JSON forbids (NaN, trailing commas) is an error naming the file and line; beside it, the
// summary `dynslam solve` prints.
#include "src/json_io.h"

#include <algorithm>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"

namespace dynslam {
namespace {

constexpr int64_t kHugeId = (int64_t{1} << 60) + 1;  // a double would round it to 2^60

// Two poses, a prior and an odometry edge, plus a pose with id 2^60 + 1 that no edge uses
// (held constant and listed in summary.json's held_constant), solved, with metrics.
struct SmallSolve {
  Graph graph;
  SolveReport report;
  std::string Summary() const {
    Metrics metrics;
    metrics.camera = {3, 0.1, 1.0 / 3};
    SolveOutputs outputs;
    outputs.input = "small.g2o";
    outputs.solved = &graph;
    outputs.report = &report;
    outputs.metrics = metrics;
    return SummaryJson(outputs);
  }
};

SmallSolve SolveSmallGraph() {
  std::istringstream in(
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 1 1.1 0.05 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT " + std::to_string(kHugeId) + " 5 0 0 0 0 0 1\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
      "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n");
  Expected<Graph> graph = ReadGraph(in, "small.g2o");
  EXPECT_TRUE(graph.ok()) << graph.error().ToString();
  Expected<SolveReport> report = Solve(SolverOptions{}, &*graph);
  EXPECT_TRUE(report.ok()) << report.error().ToString();
  return {std::move(graph).value(), std::move(report).value()};
}

TEST(JsonIoTest, VertexIdsAbove2To53RoundTripExactly) {
  Expected<JsonValue> summary = ParseJson(SolveSmallGraph().Summary(), "summary.json");
  ASSERT_TRUE(summary.ok()) << summary.error().ToString();
  const JsonValue& held = (*summary)["held_constant"];
  ASSERT_EQ(held.size(), 1u);
  ASSERT_TRUE(held[0].is_number_integer());
  EXPECT_EQ(held[0].get<int64_t>(), kHugeId);
  EXPECT_EQ(NumberAt(*summary, {"metrics", "camera", "mean_trans_m"}), 1.0 / 3);  // bit-exact
}

// A German locale writes 0,5 for 0.5 through printf and reads "0.5" as 0 through strtod. The
// locale is compiled from the system's locale sources into a temporary directory (LOCPATH), so
// the test needs no installed locale.
class GermanLocale {
 public:
  GermanLocale() {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "locales";
    std::filesystem::create_directories(dir);
    const std::string command = "localedef -i de_DE -f UTF-8 " + (dir / "de_DE.UTF-8").string() +
                                " >/dev/null 2>&1";
    if (std::system(command.c_str()) != 0 &&
        !std::filesystem::exists(dir / "de_DE.UTF-8")) {
      return;
    }
    setenv("LOCPATH", dir.c_str(), 1);
    active_ = std::setlocale(LC_ALL, "de_DE.UTF-8") != nullptr &&
              std::string(std::localeconv()->decimal_point) == ",";
  }
  ~GermanLocale() {
    std::setlocale(LC_ALL, "C");
    unsetenv("LOCPATH");
  }
  bool active() const { return active_; }

 private:
  bool active_ = false;
};

// The same solve written in both locales. (Ceres formats its own termination message with
// printf, so a solve run in a German locale has commas in termination_detail: the command line
// never leaves the C locale.)
TEST(JsonIoTest, OutputAndParsingDoNotDependOnTheLocale) {
  const SmallSolve solve = SolveSmallGraph();
  const std::string in_c_locale = solve.Summary();
  const GermanLocale german;
  ASSERT_TRUE(german.active()) << "could not compile and select de_DE.UTF-8 (Debian: locales)";
  EXPECT_EQ(solve.Summary(), in_c_locale);
  Expected<JsonValue> parsed = ParseJson("{\"x\": 0.5, \"y\": 1e-3}", "t.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error().ToString();
  EXPECT_EQ(NumberAt(*parsed, {"x"}), 0.5);
  EXPECT_EQ(NumberAt(*parsed, {"y"}), 1e-3);
}

TEST(JsonIoTest, UnicodeEscapesDecodeToUtf8AndUtf8IsWrittenAsIs) {
  Expected<JsonValue> parsed =
      ParseJson(R"({"name": "Gr\u00fc\u00dfe \ud83d\ude97"})", "t.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error().ToString();
  EXPECT_EQ((*parsed)["name"].get<std::string>(), "Grüße 🚗");
  EXPECT_EQ(DumpJson(*parsed), "{\n  \"name\": \"Grüße 🚗\"\n}");
}

TEST(JsonIoTest, WhatJsonForbidsIsAnErrorWithFileAndLine) {
  for (const char* text : {"{\n  \"x\": NaN\n}", "{\n  \"x\": nan\n}", "{\n  \"x\": 1,\n}",
                           "{\n  \"x\": Infinity\n}"}) {
    Expected<JsonValue> parsed = ParseJson(text, "bad.json");
    ASSERT_FALSE(parsed.ok()) << text;
    EXPECT_EQ(parsed.error().file, "bad.json");
    EXPECT_GE(parsed.error().line, 2) << parsed.error().ToString();
    EXPECT_LE(parsed.error().line, 3) << parsed.error().ToString();
  }
}

TEST(JsonIoTest, ANumberBeyondADoubleIsAnErrorNotACrash) {
  Expected<JsonValue> parsed = ParseJson("{\"final_cost\": 1e400}", "summary.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().file, "summary.json");
}

TEST(JsonIoTest, NonFiniteNumbersAreWrittenAsNull) {
  JsonValue json = {{"inf", std::numeric_limits<double>::infinity()},
                    {"nan", std::numeric_limits<double>::quiet_NaN()}};
  EXPECT_EQ(DumpJson(json), "{\n  \"inf\": null,\n  \"nan\": null\n}");
}

TEST(JsonIoTest, NumberAtIsNanForMissingKeysAndNonNumbers) {
  const JsonValue json = {{"a", {{"b", 2}}}, {"s", "text"}};
  EXPECT_EQ(NumberAt(json, {"a", "b"}), 2);
  EXPECT_TRUE(std::isnan(NumberAt(json, {"a", "c"})));
  EXPECT_TRUE(std::isnan(NumberAt(json, {"s"})));
  EXPECT_TRUE(std::isnan(NumberAt(json, {"s", "deeper"})));
}

// compare --resume reads a finished solve's summary.json back: what it keeps of the report is
// bit-exact, and the options text is what SolverOptionsJson writes for the options used.
TEST(JsonIoTest, ASummaryReadsBackItsReportAndOptions) {
  const SmallSolve solve = SolveSmallGraph();
  const std::string path = (std::filesystem::path(::testing::TempDir()) / "summary.json").string();
  ASSERT_TRUE(WriteFileAtomically(path, solve.Summary()).ok());
  Expected<SolveSummary> read = ReadSolveSummary(path);
  ASSERT_TRUE(read.ok()) << read.error().ToString();
  const SolveReport& r = read->report;
  EXPECT_EQ(r.termination, solve.report.termination);
  EXPECT_EQ(r.termination_detail, solve.report.termination_detail);
  EXPECT_EQ(r.usable, solve.report.usable);
  EXPECT_EQ(r.final_cost, solve.report.final_cost);
  EXPECT_EQ(r.initial_cost, solve.report.initial_cost);
  EXPECT_EQ(r.iterations, solve.report.iterations);
  EXPECT_EQ(r.steps, solve.report.steps);
  EXPECT_EQ(r.time_total_s, solve.report.time_total_s);
  EXPECT_EQ(read->solver_options_json, SolverOptionsJson(solve.report.options_used));
  SolverOptions other = solve.report.options_used;
  other.max_iterations += 1;
  EXPECT_NE(read->solver_options_json, SolverOptionsJson(other));
}

// What `dynslam solve` prints: the counts by kind and the costs of the report, the output
// directory, and the metrics line only when there are metrics.
TEST(SolveSummaryTextTest, NamesTheCountsCostsOutputsAndMetricsOfTheSolve) {
  const SmallSolve solve = SolveSmallGraph();
  SolveOutputs outputs;
  outputs.input = "small.g2o";
  outputs.solved = &solve.graph;
  outputs.report = &solve.report;
  const std::string text = SolveSummaryText(outputs, "out/dir");
  EXPECT_EQ(text.rfind("small.g2o (", 0), 0u) << text;
  EXPECT_NE(text.find("(unused, held constant: 1)\nedges: prior 1 odometry 1\n"), std::string::npos)
      << text;
  double initial = 0, final = 0;
  ASSERT_EQ(std::sscanf(text.c_str() + text.find("cost: "), "cost: %lf -> %lf", &initial, &final), 2);
  EXPECT_NEAR(initial, solve.report.initial_cost, 1e-11 * solve.report.initial_cost);
  EXPECT_NEAR(final, solve.report.final_cost, 1e-11 * std::max(solve.report.final_cost, 1e-300));
  const std::string last_line = "outputs: out/dir\n";
  EXPECT_EQ(text.substr(text.size() - last_line.size()), last_line);
  outputs.metrics = Metrics{};
  outputs.metrics->camera.count = 3;
  const std::string with_metrics = SolveSummaryText(outputs, "out/dir");
  EXPECT_EQ(with_metrics.rfind(text, 0), 0u);
  EXPECT_EQ(with_metrics.substr(text.size()), MetricsText(*outputs.metrics));
  EXPECT_NE(MetricsText(*outputs.metrics).find("over 3 pairs"), std::string::npos);
}

TEST(JsonIoTest, ASummaryWithoutItsFieldsIsAnErrorNamingTheFile) {
  const std::string path = (std::filesystem::path(::testing::TempDir()) / "partial.json").string();
  for (const char* text : {"{\"termination\": \"convergence\"}", "[1, 2]", "{\"steps\": \"3\"}"}) {
    ASSERT_TRUE(WriteFileAtomically(path, text).ok());
    Expected<SolveSummary> read = ReadSolveSummary(path);
    ASSERT_FALSE(read.ok()) << text;
    EXPECT_EQ(read.error().file, path);
  }
  EXPECT_FALSE(ReadSolveSummary(path + ".missing").ok());
}

}  // namespace
}  // namespace dynslam
