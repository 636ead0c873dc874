// The `fuzzygait walk` and `fuzzygait eval` commands as a user runs them: the files walk writes,
// the figures eval prints (table and JSON), and clear errors for bad options and bad files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzzygait/io/walk_csv.hpp"
#include "support/program.hpp"
#include "support/text.hpp"

namespace fuzzygait {
namespace {

using test::read_text;
using test::run_program;
using ::testing::HasSubstr;

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "fuzzygait_cli";
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string shell_quoted(const std::filesystem::path& p) {
  return "\"" + p.string() + "\"";
}

TEST(WalkCommand, WritesEveryFileAndTheSummary) {
  const std::filesystem::path prefix = scratch("short");
  for (const char* ext : {".csv", ".terrain.csv", ".bvh", ".svg", ".poses.svg"})
    std::filesystem::remove(prefix.string() + ext);
  const auto run =
      run_program("walk --cycles 3 --step 0.6 --stature 1.6 --fps 60 -o " + shell_quoted(prefix));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("with controller set 'default'"));
  EXPECT_THAT(run.output, HasSubstr("thigh RMSE"));
  for (const char* ext : {".csv", ".terrain.csv", ".bvh", ".svg", ".poses.svg"}) {
    EXPECT_TRUE(std::filesystem::exists(prefix.string() + ext)) << ext;
  }
  std::ifstream csv(prefix.string() + ".csv");
  const gait::Motion m = io::read_walk_csv(csv, "short.csv");
  EXPECT_NEAR(m.fps, 60.0, 1e-3);
  // The options took effect: a 1.6 m body (thigh 0.245 H).
  EXPECT_NEAR(m.segments.thigh, 0.245 * 1.6, 1e-5);
  EXPECT_THAT(read_text(prefix.string() + ".bvh"), HasSubstr("ROOT Hips"));
  EXPECT_EQ(read_text(prefix.string() + ".terrain.csv").substr(0, 4), "x,y\n");
}

TEST(WalkCommand, SameOptionsSameBytes) {
  const std::filesystem::path a = scratch("same_a");
  const std::filesystem::path b = scratch("same_b");
  for (const auto& p : {a, b}) {
    const auto run =
        run_program("walk --duration 2 --start-pose random:7 --style heavy -o " + shell_quoted(p));
    ASSERT_EQ(run.status, 0) << run.output;
  }
  EXPECT_EQ(read_text(a.string() + ".csv"), read_text(b.string() + ".csv"));
  EXPECT_EQ(read_text(a.string() + ".bvh"), read_text(b.string() + ".bvh"));
}

TEST(WalkCommand, BadOptionsAreRefusedWithTheReason) {
  const std::filesystem::path prefix = scratch("bad");
  auto refused = [&](const std::string& options, const std::string& reason) {
    const auto run = run_program("walk " + options + " -o " + shell_quoted(prefix));
    EXPECT_NE(run.status, 0) << options;
    EXPECT_THAT(run.output, HasSubstr(reason)) << options;
  };
  refused("--step 3", "step length must be between 0.05 m and");
  refused("--step nan", "step");
  refused("--stature 0", "stature must be between 0.5 and 3.0 m");
  refused("--thigh -0.1 --stature 1.7", "segment 'thigh'");
  refused("--shank 0", "segment 'shank'");
  refused("--duration -2", "duration");
  refused("--style sprightly", "sprightly");
  refused("--start-pose random:x", "random:");
  refused("--start-pose random:-5", "random:");
  refused("--start-pose random:99999999999999999999999", "random:");
  refused("--cycles 1", "cycles");
}

TEST(EvalCommand, PrintsTheTableAndWritesTheJson) {
  const std::filesystem::path prefix = scratch("for_eval");
  ASSERT_EQ(run_program("walk --cycles 4 -o " + shell_quoted(prefix)).status, 0);
  const std::filesystem::path json = scratch("for_eval.json");
  std::filesystem::remove(json);
  const auto run =
      run_program("eval " + shell_quoted(prefix.string() + ".csv") +
                  " --step 0.70 --reference schwartz2008_free --json " + shell_quoted(json));
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* row :
       {"reference: schwartz2008_free", "cadence", "stance", "step error", "max foot slip",
        "max penetration", "min toe clearance", "max velocity jump", "knee   acceleration RMS",
        "thigh RMSE", "knee RMSE", "ankle RMSE"}) {
    EXPECT_THAT(run.output, HasSubstr(row));
  }
  const nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("cycles").get<int>(), 4);
  EXPECT_NEAR(j.at("step_length_m").get<double>(), 0.70, 0.021);
  EXPECT_LT(j.at("knee").at("rmse_deg").get<double>(), 8.0);
  EXPECT_GT(j.at("smoothness").at("knee").at("rms_jerk_deg_per_s3").get<double>(), 0.0);
  EXPECT_EQ(j.at("mean_cycle").at("knee").size(), 51u);
  // --json - prints only the JSON.
  const auto to_stdout =
      run_program("eval " + shell_quoted(prefix.string() + ".csv") + " --json -");
  ASSERT_EQ(to_stdout.status, 0);
  const nlohmann::json printed = nlohmann::json::parse(to_stdout.output);
  EXPECT_EQ(printed.at("cycles"), j.at("cycles"));
}

TEST(EvalCommand, BadFilesNameTheFileAndLine) {
  const std::filesystem::path good = scratch("good");
  ASSERT_EQ(run_program("walk --cycles 3 -o " + shell_quoted(good)).status, 0);
  const std::filesystem::path csv = scratch("broken.csv");
  std::ofstream(csv) << "time,pelvis_x\n0,0\n";
  auto run = run_program("eval " + shell_quoted(csv));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("broken.csv:1"));
  EXPECT_THAT(run.output, HasSubstr("missing column 'pelvis_y'"));
  run = run_program("eval " + shell_quoted(scratch("absent.csv")));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("absent.csv"));
  run = run_program("eval " + shell_quoted(good.string() + ".csv") + " --reference nobody");
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("nobody"));
}

}  // namespace
}  // namespace fuzzygait
