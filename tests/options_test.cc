// The option tables (options.h): one spelling per option, values that read back, presets that
// refuse a contradiction, and summary.json's solver block made from the table.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "dynslam/compat.h"
#include "dynslam/formulation.h"
#include "dynslam/simulate.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver_options.h"
#include "dynslam/trajectory_export.h"
#include "src/json_io.h"

namespace dynslam {
namespace {

std::string Plain(const std::string& name) { return name; }

template <typename Options>
void ExpectOneSpellingEach(const OptionTable<Options>& table) {
  std::set<std::string> seen;
  for (const Option<Options>& option : table) {
    for (const std::string& name : [&] {
           std::vector<std::string> all = option.aliases;
           all.push_back(option.name);
           return all;
         }()) {
      EXPECT_TRUE(seen.insert(name).second) << name << " twice";
      EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_"), std::string::npos)
          << name << " is not snake_case";
    }
    EXPECT_FALSE(option.help.empty()) << option.name;
    EXPECT_FALSE(option.group.empty()) << option.name;
  }
}

TEST(OptionsTest, EveryNameIsOneSnakeCaseSpelling) {
  ExpectOneSpellingEach(SolverOptionTable());
  ExpectOneSpellingEach(BuildOptionTable());
  ExpectOneSpellingEach(SimulateOptionTable());
  ExpectOneSpellingEach(ExportOptionTable());
  ExpectOneSpellingEach(CompatOptionTable());
}

// Every option, written as text and read back, is the same value.
TEST(OptionsTest, TextReadsBackToTheSameValue) {
  SolverOptions changed;
  changed.remaining_chi2 = 0.1 + 0.2;  // not a short decimal
  changed.linear_solver = LinearSolverType::kSparseSchur;
  changed.extrapolation = false;
  changed.object_point_variables = Frame::kObject;
  changed.robust[static_cast<int>(EdgeKind::kPoint)] = {RobustKernel::Type::kHuber, 1.345};
  for (const SolverOptions& options : {SolverOptions{}, changed}) {
    for (const Option<SolverOptions>& option : SolverOptionTable()) {
      SolverOptions read;
      ASSERT_EQ(option.set(option.get(options), &read), std::nullopt) << option.name;
      EXPECT_EQ(option.get(read), option.get(options)) << option.name;
    }
  }
  EXPECT_EQ(FindOption(SolverOptionTable(), "remaining_chi2")->get(changed), "0.30000000000000004");
  EXPECT_EQ(FindOption(SolverOptionTable(), "robust")->get(changed), "point=huber:1.345");
  BuildOptions sigmas;
  ASSERT_EQ(ParseHybridSmoothingInfo("0.01,0.1", &sigmas), std::nullopt);
  for (const BuildOptions& options : {BuildOptions{}, sigmas}) {
    for (const Option<BuildOptions>& option : BuildOptionTable()) {
      BuildOptions read;
      ASSERT_EQ(option.set(option.get(options), &read), std::nullopt) << option.name;
      EXPECT_EQ(option.get(read), option.get(options)) << option.name;
    }
  }
}

// `value`'s text of every option in `table`, set on default options and read back, is the same.
template <typename Options>
void ExpectEachReadsBack(const OptionTable<Options>& table, const Options& value) {
  for (const Option<Options>& option : table) {
    Options read;
    ASSERT_EQ(option.set(option.get(value), &read), std::nullopt) << option.name;
    EXPECT_EQ(option.get(read), option.get(value)) << option.name;
  }
}

TEST(OptionsTest, ExportAndCompatibilityOptionsReadBackAndNameBadValues) {
  ExportOptions exported;
  ASSERT_EQ(ApplyOptions(ExportOptionTable(), {{"export", "tum,kitti"}, {"export_rate", "2.5"}},
                         Plain, &exported),
            std::nullopt);
  EXPECT_EQ(exported.formats, (std::vector<TrajectoryFormat>{TrajectoryFormat::kTum,
                                                             TrajectoryFormat::kKitti}));
  EXPECT_EQ(exported.rate_hz, 2.5);
  ExpectEachReadsBack(ExportOptionTable(), ExportOptions{});
  ExpectEachReadsBack(ExportOptionTable(), exported);
  EXPECT_EQ(ApplyOptions(ExportOptionTable(), {{"export", "tum,png"}}, Plain, &exported),
            "export: unknown format 'png' (tum, kitti)");
  for (const char* text : {"none", "dsc", "1,3", "dynosam", "dynosam:2,4"}) {
    Compat compat;
    ASSERT_EQ(ApplyOptions(CompatOptionTable(), {{"compat", text}}, Plain, &compat), std::nullopt);
    ExpectEachReadsBack(CompatOptionTable(), compat);
  }
  Compat compat;
  EXPECT_NE(ApplyOptions(CompatOptionTable(), {{"compat", "9"}}, Plain, &compat), std::nullopt);
}

TEST(OptionsTest, BadValuesNameTheProblem) {
  SolverOptions options;
  const auto apply = [&](const std::string& name, const std::string& text) {
    return ApplyOptions(SolverOptionTable(), {{name, text}}, Plain, &options).value_or("");
  };
  EXPECT_EQ(apply("linear_solver", "cholmod"),
            "linear_solver: 'cholmod' is not one of auto|sparse_schur|sparse_normal_cholesky|"
            "iterative_schur|dense_schur");
  EXPECT_EQ(apply("threads", "0"), "threads: '0' is not a whole number from 1 to 256");
  EXPECT_EQ(apply("max_iterations", "5.5"),
            "max_iterations: '5.5' is not a whole number from 0 to 1000000");
  EXPECT_EQ(apply("remaining_chi2", "nan"), "remaining_chi2: 'nan' is not a number from 0 to 1e+300");
  EXPECT_EQ(apply("extrapolation", "maybe"), "extrapolation: 'maybe' is not on or off");
  EXPECT_EQ(apply("robust", "point=huber:-1"),
            "robust: threshold '-1' is not a positive number");
  EXPECT_EQ(apply("robust", "pointy=huber:1"), "robust: unknown edge kind 'pointy'");
  EXPECT_EQ(apply("no_such_option", "1"), "unknown option no_such_option");
  EXPECT_EQ(options.linear_solver, LinearSolverType::kAuto);  // nothing applied
}

TEST(OptionsTest, AliasesAreEarlierSpellings) {
  SolverOptions options;
  ASSERT_EQ(ApplyOptions(SolverOptionTable(),
                         {{"extrapolate", "off"}, {"max-time-s", "5"}, {"snap_segment_gauges", "on"}},
                         Plain, &options),
            std::nullopt);
  EXPECT_FALSE(options.extrapolation);
  EXPECT_EQ(options.max_time, 5);
  EXPECT_TRUE(options.gauge_moves);
}

TEST(OptionsTest, SimulationFramesAreARangeWithBExclusive) {
  const auto frames = [](const std::string& text) {
    SimulateOptions options;
    const std::optional<std::string> problem =
        ApplyOptions(SimulateOptionTable(), {{"frames", text}}, Plain, &options);
    return problem ? *problem
                   : std::to_string(options.first_frame) + "," + std::to_string(options.last_frame);
  };
  EXPECT_EQ(frames("0:60"), "0,60");
  EXPECT_EQ(frames("5:"), "5,-1");
  EXPECT_EQ(frames(":30"), "0,30");
  EXPECT_EQ(frames(":"), "0,-1");
  for (const std::string bad : {"30:5", "5:5", "60", "a:b", "-1:5", "0:-1"}) {
    EXPECT_EQ(frames(bad), "frames: '" + bad + "' is not A:B with A < B (A: and :B allowed)");
  }
}

TEST(OptionsTest, SimulationOptionsReadBackAndKeepTheirEarlierSpellings) {
  SimulateOptions changed;
  ASSERT_EQ(ApplyOptions(SimulateOptionTable(),
                         {{"frames", "3:40"}, {"static_points_per_frame", "80"},
                          {"dynamic-break", "0.25"}, {"object_types", "Car,Van"}, {"noise", "off"}},
                         Plain, &changed),
            std::nullopt);
  EXPECT_EQ(changed.static_points_per_frame, 80);
  EXPECT_EQ(changed.dynamic_break_probability, 0.25);
  EXPECT_EQ(changed.object_types, (std::vector<std::string>{"Car", "Van"}));
  EXPECT_FALSE(changed.noise);
  for (const SimulateOptions& options : {SimulateOptions{}, changed}) {
    for (const Option<SimulateOptions>& option : SimulateOptionTable()) {
      SimulateOptions read;
      ASSERT_EQ(option.set(option.get(options), &read), std::nullopt) << option.name;
      EXPECT_EQ(option.get(read), option.get(options)) << option.name;
    }
  }
}

// Every compatibility item is also an option of its own (docs/OPTIONS.md); `--compat none`, the
// default, must not switch off one that was given by itself (`--dsc-released-lm on`).
TEST(OptionsTest, CompatNoneKeepsTheItemsSwitchedOnOneByOne) {
  SolverOptions solver;
  solver.dsc_object_motion_residual = solver.dsc_released_lm = true;
  ApplyCompat(Compat{}, false, &solver);
  EXPECT_TRUE(solver.dsc_object_motion_residual);
  EXPECT_TRUE(solver.dsc_released_lm);

  BuildOptions build;
  build.dsc_object_centric_noise = build.dynosam_smoothing = build.dynosam_embedded_frame =
      build.dynosam_points_from_measurements = true;
  ApplyCompat(Compat{}, &build);
  EXPECT_TRUE(build.dsc_object_centric_noise);
  EXPECT_TRUE(build.dynosam_smoothing);
  EXPECT_TRUE(build.dynosam_embedded_frame);
  EXPECT_TRUE(build.dynosam_points_from_measurements);

  ReadOptions read;
  read.information_in_tangent_order = true;
  ApplyCompat(Compat{}, &read);
  EXPECT_TRUE(read.information_in_tangent_order);
}

TEST(OptionsTest, APresetRefusesAnOptionThatUndoesIt) {
  SolverOptions options;
  ASSERT_EQ(ApplyOptions(SolverOptionTable(), {{"tolerances", "tight"}}, Plain, &options),
            std::nullopt);
  EXPECT_EQ(options.remaining_chi2, 0);
  EXPECT_FALSE(options.extrapolation);
  // Given beside it, in either order, an option that agrees is fine; one that disagrees is not.
  options = {};
  EXPECT_EQ(ApplyOptions(SolverOptionTable(), {{"extrapolation", "off"}, {"tolerances", "tight"}},
                         Plain, &options),
            std::nullopt);
  options = {};
  EXPECT_EQ(ApplyOptions(SolverOptionTable(), {{"remaining_chi2", "0.1"}, {"tolerances", "tight"}},
                         Plain, &options),
            "tolerances tight sets remaining_chi2 0; give one of them");
  options = {};
  EXPECT_EQ(ApplyOptions(SolverOptionTable(), {{"tolerances", "default"}, {"remaining_chi2", "0.5"}},
                         Plain, &options),
            std::nullopt);
  EXPECT_EQ(options.remaining_chi2, 0.5);
}

TEST(OptionsTest, TheGtsamPresetIsGtsamsLevenbergMarquardtStop) {
  SolverOptions options;
  ASSERT_EQ(ApplyOptions(SolverOptionTable(), {{"tolerances", "gtsam"}}, Plain, &options),
            std::nullopt);
  EXPECT_EQ(options.function_tolerance, 1e-5);
  EXPECT_EQ(options.absolute_decrease, 1e-5);
  EXPECT_EQ(options.max_iterations, 100);
  EXPECT_EQ(options.remaining_chi2, 0);
  EXPECT_FALSE(options.extrapolation);
  options = {};
  EXPECT_EQ(ApplyOptions(SolverOptionTable(), {{"tolerances", "gtsam"}, {"max_iterations", "50"}},
                         Plain, &options),
            "tolerances gtsam sets max_iterations 100; give one of them");
}

// summary.json's "solver" block: every option of the table but the presets, under its name, with
// the JSON type of its kind.
TEST(OptionsTest, TheSummarysSolverBlockIsTheTable) {
  SolverOptions options;
  options.robust[static_cast<int>(EdgeKind::kPoint)] = {RobustKernel::Type::kCauchy, 2};
  const JsonValue json = JsonValue::parse(SolverOptionsJson(options));
  size_t expected = 1;  // "library"
  for (const Option<SolverOptions>& option : SolverOptionTable()) {
    if (option.type == OptionType::kPreset) {
      EXPECT_FALSE(json.contains(option.name)) << option.name;
      continue;
    }
    ++expected;
    ASSERT_TRUE(json.contains(option.name)) << option.name;
    const JsonValue& value = json.at(option.name);
    switch (option.type) {
      case OptionType::kSwitch: EXPECT_EQ(value.get<bool>(), option.get(options) == "on"); break;
      case OptionType::kInteger: EXPECT_EQ(std::to_string(value.get<int64_t>()), option.get(options)); break;
      case OptionType::kReal: EXPECT_EQ(RealText(value.get<double>()), option.get(options)); break;
      default: EXPECT_EQ(value.get<std::string>(), option.get(options)); break;
    }
  }
  EXPECT_EQ(json.size(), expected);
  EXPECT_EQ(json.at("robust"), "point=cauchy:2");
  EXPECT_EQ(json.at("object_point_variables"), "world");
}

}  // namespace
}  // namespace dynslam
