// `fuzzygait train` end to end on a CMU clip with a small budget: the set, the report and the
// pictures are written, `fuzzygait walk --controllers` walks the clip's body and step from the
// manifest (options still override), Ctrl-C (SIGINT) stops it writing the best set so far, and bad
// input is refused before anything is written.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "fuzzygait/gait/controllers.hpp"
#include "fuzzygait/learn/tune.hpp"
#include "support/program.hpp"

extern char** environ;

namespace fuzzygait {
namespace {

namespace fs = std::filesystem;

const fs::path kClip = fs::path(FUZZYGAIT_SOURCE_DIR) / "data" / "mocap" / "cmu" / "07_01.bvh";

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("fuzzygait_train_cli_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(TrainCommand, WritesTheSetItsReportAndTheClipsCurves) {
  const fs::path out = scratch("files");
  const test::ProgramRun run = test::run_program(
      "train \"" + kClip.string() + "\" -o \"" + out.string() +
      "\" --generations 8 --polish 2 --name mine --check-starts 10 --fit-iterations 3");
  ASSERT_EQ(run.status, 0) << run.output;
  // Progress: stages, iterations, errors per joint.
  EXPECT_NE(run.output.find("commands iteration 0"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("polish generation"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("| thigh "), std::string::npos) << run.output;
  for (const char* file : {"manifest.json", "swing_knee.fll", "stance_ankle.fll", "report.txt",
                           "report.json", "07_01.svg", "stairs_swing_knee_up.fll"}) {
    EXPECT_TRUE(fs::exists(out / file)) << file;
  }
  const gait::ControllerSet set = gait::ControllerSet::load(out);
  EXPECT_EQ(set.name, "mine");
  ASSERT_TRUE(set.body.has_value());
  EXPECT_NEAR(set.body->thigh, 0.397, 0.001);
  EXPECT_NEAR(set.body_step_length.value_or(0.0), 0.733, 0.001);
  EXPECT_EQ(learn::word_penalty(set), 0.0);
  const nlohmann::json report = nlohmann::json::parse(text_of(out / "report.json"));
  ASSERT_EQ(report["clips"].size(), 1u);
  const nlohmann::json& clip = report["clips"][0];
  EXPECT_EQ(clip["clip"], "07_01");
  EXPECT_GT(clip["before"]["knee_rmse_deg"].get<double>(),
            clip["after"]["knee_rmse_deg"].get<double>());
  EXPECT_FALSE(report["stopped"].get<bool>());
  EXPECT_EQ(report["terrain_walks"].get<int>(), 4);
  EXPECT_EQ(report["terrain_misses"].size(),
            4u - report["terrain_within_bounds"].get<std::size_t>());
  const std::string text = text_of(out / "report.txt");
  EXPECT_NE(text.find("before: thigh"), std::string::npos) << text;
  EXPECT_NE(text.find("after:  thigh"), std::string::npos) << text;
  EXPECT_NE(text.find("stairs and ramps at the clips' body and step"), std::string::npos) << text;
  const std::string svg = text_of(out / "07_01.svg");
  EXPECT_NE(svg.find("before: default"), std::string::npos);
  EXPECT_NE(svg.find("after: mine"), std::string::npos);
  EXPECT_NE(svg.find("clip 07_01"), std::string::npos);

  // `walk --controllers` takes the body and step from the manifest; options override them.
  struct Walked {
    double pelvis_height;  // at the first frame: the leg's length shows
    double step;           // as `fuzzygait eval` measures it
  };
  auto walk = [&](const std::string& options) {
    const fs::path prefix = out / "walk";
    const test::ProgramRun walked =
        test::run_program("walk --controllers \"" + out.string() + "\" --cycles 3 " + options +
                          " -o \"" + prefix.string() + "\"");
    EXPECT_EQ(walked.status, 0) << walked.output;
    std::ifstream csv(prefix.string() + ".csv");
    std::string header;
    std::string row;
    std::getline(csv, header);
    std::getline(csv, row);
    const double pelvis_y = std::stod(row.substr(row.find(',', row.find(',') + 1) + 1));
    const nlohmann::json measured = nlohmann::json::parse(
        test::run_program("eval \"" + prefix.string() + ".csv\" --json -").output);
    return Walked{pelvis_y, measured["step_length_m"].get<double>()};
  };
  const Walked own = walk("");
  EXPECT_NEAR(own.pelvis_height, 0.77, 0.07);  // legs of 0.836 m, knees bent a little
  EXPECT_NEAR(own.step, 0.733, 0.733 * 0.05);
  EXPECT_GT(walk("--stature 1.9").pelvis_height, 0.9);
  EXPECT_LT(walk("--step 0.62").step, own.step - 0.05);
  fs::remove_all(out);
}

TEST(TrainCommand, CtrlCStopsItWritingTheBestSetSoFar) {
  const fs::path out = scratch("interrupted");
  fs::create_directories(out.parent_path());
  const fs::path log = out.string() + ".log";
  const std::string program = FUZZYGAIT_CLI;
  const std::string clip = kClip.string();
  const std::string folder = out.string();
  const char* argv[] = {program.c_str(),
                        "train",
                        clip.c_str(),
                        "-o",
                        folder.c_str(),
                        "--generations",
                        "1000000",
                        "--check-starts",
                        "10",
                        "--fit-iterations",
                        "3",
                        nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  ASSERT_EQ(
      posix_spawn(&pid, program.c_str(), &actions, nullptr, const_cast<char**>(argv), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Interrupted once the polish is under way (or after 200 s at most).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(200);
  while (text_of(log).find("polish generation") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string output = text_of(log);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 0) << output;
  EXPECT_NE(output.find("stopped: writing the best set found so far"), std::string::npos) << output;
  const gait::ControllerSet set = gait::ControllerSet::load(out);
  EXPECT_TRUE(set.body.has_value());
  const nlohmann::json report = nlohmann::json::parse(text_of(out / "report.json"));
  EXPECT_TRUE(report["stopped"].get<bool>());
  EXPECT_LE(report["cost_after"].get<double>(), report["cost_before"].get<double>());
  fs::remove_all(out);
  fs::remove(log);
}

TEST(TrainCommand, RefusesBadInputBeforeWritingAnything) {
  const fs::path out = scratch("refused");
  const std::string clip = "\"" + kClip.string() + "\"";
  struct Case {
    std::string arguments;
    std::string expected;
  };
  const Case cases[] = {
      {"train missing.bvh -o \"" + out.string() + "\"", "missing.bvh"},
      {"train " + clip + " -o \"" + out.string() + "\" --base nonesuch", "nonesuch"},
      {"train " + clip + " -o \"" + out.string() + "\" --up x", "--up must be y or z"},
      {"train " + clip + " -o \"" + out.string() + "\" --unit 0", "--unit"},
      {"train " + clip + " -o \"" + out.string() + "\" --base default --controllers somewhere",
       "--base and --controllers"},
  };
  for (const Case& c : cases) {
    const test::ProgramRun run = test::run_program(c.arguments);
    EXPECT_NE(run.status, 0) << c.arguments;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.arguments << "\n" << run.output;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
  }
}

}  // namespace
}  // namespace fuzzygait
