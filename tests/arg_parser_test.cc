// The command-line parser (cli/arg_parser.h): values spelled `--name value` and `--name=value`,
// switches with and without on/off, positionals, and each usage error an exit code of 2 with
// the option named; an option table's flags (TableFlags) apply given values over the defaults.
#include "arg_parser.h"

#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynslam/solver_options.h"

namespace dynslam::cli {
namespace {

// Parses `args` (after a program name and a command) with `parser`.
std::optional<int> ParseAll(ArgParser* parser, std::vector<std::string> args) {
  args.insert(args.begin(), {"dynslam", "command"});
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  return parser->Parse(static_cast<int>(argv.size()), argv.data(), 2);
}

struct Declared {
  std::string input, name = "default";
  bool flag = false;
  double ratio = 0.5;
  ArgParser parser{"command INPUT [options]", "what it does"};
  Declared() {
    parser.AddPositional("INPUT", &input, "the input");
    parser.AddString("name", &name, "a name", "NAME");
    parser.AddFlag("flag", &flag, "a flag");
    parser.AddDouble("ratio", &ratio, "a ratio", 0, 1);
    parser.AddAlias("ratio", "fraction");
  }
};

TEST(ArgParserTest, ValuesInBothSpellingsFlagsAliasesAndPositionals) {
  Declared d;
  EXPECT_EQ(ParseAll(&d.parser, {"in.g2o", "--name", "x", "--flag", "--fraction=0.25"}), std::nullopt);
  EXPECT_EQ(d.input, "in.g2o");
  EXPECT_EQ(d.name, "x");
  EXPECT_TRUE(d.flag);
  EXPECT_EQ(d.ratio, 0.25);
  EXPECT_TRUE(d.parser.Given("ratio"));
  EXPECT_FALSE(Declared().parser.Given("ratio"));
}

TEST(ArgParserTest, EachUsageErrorIsExitTwo) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"in", "--unknown", "1"},
                                             {"in", "--name"},
                                             {"in", "--flag=on"},
                                             {"in", "--ratio", "2"},
                                             {"in", "--ratio", "half"},
                                             {"in", "extra"},
                                             {}}) {
    Declared d;
    testing::internal::CaptureStderr();
    EXPECT_EQ(ParseAll(&d.parser, args), kExitBadInput) << testing::PrintToString(args);
    EXPECT_NE(testing::internal::GetCapturedStderr().find("error: "), std::string::npos);
  }
}

TEST(ArgParserTest, HelpListsEveryOptionWithItsDefaultAndExitsZero) {
  Declared d;
  testing::internal::CaptureStdout();
  EXPECT_EQ(ParseAll(&d.parser, {"--help"}), kExitOk);
  const std::string help = testing::internal::GetCapturedStdout();
  for (const char* text : {"--name NAME", "(default: default)", "--flag", "(default: off)",
                           "--ratio X", "(default: 0.5)"}) {
    EXPECT_NE(help.find(text), std::string::npos) << text;
  }
}

TEST(TableFlagsTest, GivenValuesApplyOverTheDefaultsAndSwitchesTakeOnOrOff) {
  ArgParser parser("command", "");
  TableFlags<SolverOptions> flags(&parser, SolverOptionTable());
  EXPECT_EQ(ParseAll(&parser, {"--max-iterations", "7", "--fix-first", "off"}), std::nullopt);
  SolverOptions options;
  EXPECT_EQ(flags.Finish(&options), std::nullopt);
  EXPECT_EQ(options.max_iterations, 7);
  EXPECT_FALSE(options.fix_first);
  EXPECT_EQ(options.remaining_chi2, SolverOptions{}.remaining_chi2);
}

TEST(TableFlagsTest, APresetContradictedByAnOptionBesideItIsAProblem) {
  ArgParser parser("command", "");
  TableFlags<SolverOptions> flags(&parser, SolverOptionTable());
  EXPECT_EQ(ParseAll(&parser, {"--tolerances", "tight", "--remaining-chi2", "0.5"}), std::nullopt);
  SolverOptions options;
  const std::optional<std::string> problem = flags.Finish(&options);
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("--tolerances tight"), std::string::npos) << *problem;
}

}  // namespace
}  // namespace dynslam::cli
