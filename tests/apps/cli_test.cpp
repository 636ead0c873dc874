// The `fuzzygait walk` and `fuzzygait eval` commands as a user runs them: the files walk writes,
// the figures eval prints (table and JSON), and clear errors for bad options and bad files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzzygait/eval/terrain_report.hpp"
#include "fuzzygait/io/terrain_spec.hpp"
#include "fuzzygait/io/walk_csv.hpp"
#include "support/program.hpp"
#include "support/text.hpp"

namespace fuzzygait {
namespace {

using test::read_text;
using test::run_program;
using ::testing::HasSubstr;
using ::testing::Not;

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
  const eval::Motion m = io::read_walk_csv(csv, "short.csv");
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
  refused("--step 3", "step length must be between 0.427 m (0.46 leg lengths, the shortest");
  refused("--style heavy --step 0.5", "(0.62 leg lengths, the shortest 'heavy' walks)");
  refused("--step 0.3", "got 0.3 m");
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
  // CLI11's own range checks let NaN through.
  refused("--duration nan", "--duration must be more than 0 and at most 36000 s, got nan");
  refused("--duration 0", "--duration must be more than 0 and at most 36000 s, got 0");
  refused("--duration 36001", "--duration must be more than 0 and at most 36000 s, got 36001");
  refused("--fps nan", "--fps must be between 10 and 2000, got nan");
  // One frame a second cannot see the feet strike (a cycle takes about one second).
  refused("--fps 1", "--fps must be between 10 and 2000, got 1");
  refused("--speed 0", "--speed must be a speed above 0 m/s, got 0");
  refused("--speed nan", "--speed must be a speed above 0 m/s, got nan");
  refused("--speed 9", "speed must be between");
  refused("--speed 1.2 --step 0.7", "give --speed or --step, not both");
}

// Asked for a speed, the walk takes it, with the step and cadence of the set's stride relation.
TEST(WalkCommand, WalksAtTheSpeedAsked) {
  const std::filesystem::path prefix = scratch("speed");
  const auto run = run_program("walk --cycles 6 --speed 1.5 -o " + shell_quoted(prefix));
  ASSERT_EQ(run.status, 0) << run.output;
  const std::size_t at = run.output.find("\nspeed ");
  ASSERT_NE(at, std::string::npos) << run.output;
  const double speed = std::stod(run.output.substr(run.output.find_first_of("0123456789", at)));
  EXPECT_NEAR(speed, 1.5, 0.03 * 1.5) << run.output;
  EXPECT_THAT(run.output, HasSubstr("pelvis speed, lowest"));
}

TEST(WalkCommand, RefusesBeforeWritingAnything) {
  const std::filesystem::path folder = scratch("prefix_folder");
  std::filesystem::create_directories(folder);
  for (const std::string& prefix : {folder.string(), folder.string() + "/"}) {
    const auto run = run_program("walk --cycles 2 -o " + shell_quoted(prefix));
    EXPECT_NE(run.status, 0) << prefix;
    EXPECT_THAT(run.output, HasSubstr("names a folder, not a file prefix")) << prefix;
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "hidden files such as '.csv' were written";
  const auto run = run_program("walk --cycles 2 --reference no_such_curves -o " +
                               shell_quoted((folder / "walk").string()));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("no_such_curves"));
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "files written before the refusal";
}

TEST(WalkCommand, WarnsWhenTheWalkMissesTheContactBounds) {
  // The default set meets them; the heavy style at 0.67 m steps lands its heel skimming the
  // ground, about 2 mm a frame within the last 2 mm (docs/walk.md, "Step lengths"). Both write
  // their files.
  const auto sound = run_program("walk --cycles 3 -o " + shell_quoted(scratch("sound")));
  ASSERT_EQ(sound.status, 0) << sound.output;
  EXPECT_THAT(sound.output, Not(HasSubstr("warning")));
  const std::filesystem::path skims = scratch("skims");
  const auto run =
      run_program("walk --cycles 3 --style heavy --step 0.67 -o " + shell_quoted(skims));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("warning: this walk misses the contact bounds: foot slip"));
  EXPECT_TRUE(std::filesystem::exists(skims.string() + ".bvh"));
}

// A full disk is an error, not a success with the output cut short: in a small file (written
// only when closed) and on standard output. Linux's /dev/full refuses every write.
TEST(WalkCommand, AFullDiskIsAnError) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  const std::filesystem::path prefix = scratch("full");
  const std::filesystem::path terrain = prefix.string() + ".terrain.csv";
  std::filesystem::remove(terrain);
  std::filesystem::create_symlink("/dev/full", terrain);
  const auto run = run_program("walk --cycles 2 -o " + shell_quoted(prefix));
  std::filesystem::remove(terrain);
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr(terrain.string() + ": cannot write (No space left on device)"));
  const std::filesystem::path errors = scratch("full_stdout.err");
  for (const std::string& arguments :
       {"walk --cycles 2 -o " + shell_quoted(prefix), std::string("--help"),
        "eval " + shell_quoted(prefix.string() + ".csv")}) {
    const int status = std::system(("\"" + std::string(FUZZYGAIT_CLI) + "\" " + arguments +
                                    " > /dev/full 2> " + shell_quoted(errors))
                                       .c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << arguments;
    EXPECT_EQ(read_text(errors), "fuzzygait: error: cannot write to standard output\n")
        << arguments;
  }
}

// The BVH root's height (the second channel, cm) in the first and last frames.
std::pair<double, double> bvh_root_heights(const std::string& bvh) {
  std::istringstream in(bvh.substr(bvh.find("Frame Time:")));
  std::string line;
  std::getline(in, line);
  std::vector<double> heights;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    double x = 0.0;
    double y = 0.0;
    if (row >> x >> y) heights.push_back(y);
  }
  return {heights.front(), heights.back()};
}

TEST(WalkCommand, WalksTheTerrainAndWritesTheGroundWalked) {
  const std::filesystem::path prefix = scratch("stairs");
  const std::string spec = "stairs:0.17:0.28:4";
  const auto run =
      run_program("walk --terrain " + spec + " --cycles 6 --fps 60 -o " + shell_quoted(prefix));
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* ext : {".csv", ".terrain.csv", ".bvh", ".poses.svg"}) {
    EXPECT_TRUE(std::filesystem::exists(prefix.string() + ext)) << ext;
  }
  std::ifstream csv(prefix.string() + ".csv");
  const eval::Motion motion = io::read_walk_csv(csv, "stairs.csv");
  std::ifstream terrain_csv(prefix.string() + ".terrain.csv");
  const terrain::Terrain written = io::read_terrain_csv(terrain_csv, "stairs.terrain.csv");
  const terrain::Terrain ground = io::terrain_from_spec(spec);
  // The ground from before the first frame to after the last, corners and all: the same heights.
  double low = motion.frames.front().pose.pelvis.x;
  double high = low;
  for (const eval::Frame& f : motion.frames) {
    for (const rig::LegPoints& p : f.points) {
      for (const rig::Point& q : {p.hip, p.knee, p.ankle, p.heel, p.ball, p.tip}) {
        low = std::min(low, q.x);
        high = std::max(high, q.x);
      }
    }
  }
  EXPECT_LT(written.points().front().x, low - 0.5);
  EXPECT_GT(written.points().back().x, high + 0.5);
  for (double x = low - 0.5; x < high + 0.5; x += 0.0037) {
    EXPECT_NEAR(written.height(x), ground.height(x), 2e-6) << x;
  }
  EXPECT_EQ(written.runs().size(), ground.runs().size());
  // The walk climbed: the pelvis and the BVH's root end 0.68 m higher, give or take a bob.
  EXPECT_NEAR(motion.frames.back().pose.pelvis.y - motion.frames.front().pose.pelvis.y, 0.68, 0.1);
  const auto [first, last] = bvh_root_heights(read_text(prefix.string() + ".bvh"));
  EXPECT_NEAR(last - first, 68.0, 10.0);
  // The pictures show the ground: risers are vertical strokes of the ground line.
  EXPECT_THAT(read_text(prefix.string() + ".poses.svg"), HasSubstr("The whole walk"));

  // eval reads the files back with the same terrain: the same steps as measured on the spec.
  const auto evaluated =
      run_program("eval " + shell_quoted(prefix.string() + ".csv") + " --json -");
  ASSERT_EQ(evaluated.status, 0) << evaluated.output;
  const nlohmann::json j = nlohmann::json::parse(evaluated.output);
  const nlohmann::json& t = j.at("terrain");
  const eval::TerrainReport direct = eval::evaluate_terrain(motion, ground);
  ASSERT_EQ(t.at("steps").size(), direct.steps.size());
  for (std::size_t k = 0; k < direct.steps.size(); ++k) {
    EXPECT_EQ(t.at("steps")[k].at("ground"), eval::name(direct.steps[k].footing)) << k;
    EXPECT_EQ(t.at("steps")[k].at("run").get<std::size_t>(), direct.steps[k].run) << k;
  }
  EXPECT_EQ(t.at("runs").get<std::size_t>(), 5u);  // the ground, 3 treads, the landing
  bool stairs_up = false;
  for (const nlohmann::json& g : t.at("groups"))
    stairs_up = stairs_up || g.at("ground") == "stairs up";
  EXPECT_TRUE(stairs_up) << t.at("groups").dump();
  // The table follows the level report; --terrain names the file.
  const auto table = run_program("eval " + shell_quoted(prefix.string() + ".csv") + " --terrain " +
                                 shell_quoted(prefix.string() + ".terrain.csv"));
  ASSERT_EQ(table.status, 0) << table.output;
  EXPECT_THAT(table.output, HasSubstr("On terrain:"));
  EXPECT_THAT(table.output, HasSubstr("stairs up"));
  EXPECT_THAT(table.output, HasSubstr("leg points against the ground"));
  EXPECT_LT(table.output.find("cadence"), table.output.find("On terrain:"));
}

TEST(WalkCommand, TerrainWalksStopAndRepeat) {
  // Stairs that end in a landing: --cycles still stops; --duration as before; the same bytes.
  const std::filesystem::path a = scratch("ramp_a");
  const std::filesystem::path b = scratch("ramp_b");
  for (const auto& p : {a, b}) {
    const auto run = run_program(
        "walk --terrain slope:-8:2+stairs:0.15:0.3:2+flat --duration 4 "
        "--fps 50 -o " +
        shell_quoted(p));
    ASSERT_EQ(run.status, 0) << run.output;
  }
  EXPECT_EQ(read_text(a.string() + ".csv"), read_text(b.string() + ".csv"));
  EXPECT_EQ(read_text(a.string() + ".terrain.csv"), read_text(b.string() + ".terrain.csv"));
  std::ifstream csv(a.string() + ".csv");
  EXPECT_NEAR(io::read_walk_csv(csv, "a.csv").frames.back().time, 4.0, 1e-6);
  const auto cycles = run_program("walk --terrain stairs:0.15:0.3:2 --cycles 3 --fps 50 -o " +
                                  shell_quoted(scratch("short_stairs")));
  EXPECT_EQ(cycles.status, 0) << cycles.output;
}

TEST(WalkCommand, ABadTerrainIsRefusedBeforeWritingAnything) {
  const std::filesystem::path folder = scratch("bad_terrain");
  std::filesystem::create_directories(folder);
  for (const auto& [spec, reason] : std::vector<std::pair<std::string, std::string>>{
           {"stairs:0.3:0.28:6", "--terrain: 'stairs:0.3:0.28:6': rise must be between 0.05"},
           {"slope:40", "--terrain: 'slope:40': angle must be between -25 and 25 deg, got 40"},
           {"hill:3", "--terrain: 'hill:3': unknown kind 'hill'"},
           {"stairs:0.17:0.28", "missing COUNT"},
           {"slope:nan", "angle 'nan' is not a finite number"},
           {"profile:no_such_file.csv", "no_such_file.csv: cannot open the file"}}) {
    const auto run = run_program("walk --cycles 2 --terrain " + spec + " -o " +
                                 shell_quoted((folder / "walk").string()));
    EXPECT_NE(run.status, 0) << spec;
    EXPECT_THAT(run.output, HasSubstr(reason)) << spec;
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "files written before the refusal";
}

// Legs of a 1.00 m body (0.53 m) take stairs of at most 0.40 leg lengths, 0.212 m: a 0.23 m
// descent is refused before anything is written, naming the rise and where it is. (It froze at
// the top edge for the whole walk, with exit status 0.)
TEST(WalkCommand, AStairTallerThanTheLegsTakeIsRefusedNamingTheRise) {
  const std::filesystem::path folder = scratch("tall_stairs");
  std::filesystem::create_directories(folder);
  const auto run =
      run_program("walk --stature 1.0 --step 0.4 --duration 20 --terrain stairs:-0.23:0.28:6 -o " +
                  shell_quoted((folder / "walk").string()));
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("the ground has a stair 0.23 m down at x = 1"));
  EXPECT_THAT(run.output, HasSubstr("taller than these legs take one stair a step: 0.212 m"));
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "files written before the refusal";
}

// Stairs the legs take but the walker does not yet (0.10 m down at 1.75 m: it steps in place
// at the top) end in a failure naming when and where the walk stopped, its files written for a
// look. (The walk exited with status 0.)
TEST(WalkCommand, AWalkThatStallsFailsNamingWhenAndWhere) {
  const std::filesystem::path prefix = scratch("stalled");
  const auto run = run_program("walk --duration 20 --fps 60 --terrain stairs:-0.10:0.28:6 -o " +
                               shell_quoted(prefix));
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("fuzzygait: error: the walk stalled at "));
  EXPECT_THAT(run.output, HasSubstr("with the pelvis at x = "));
  EXPECT_THAT(run.output, HasSubstr("the front foot on run "));
  EXPECT_THAT(run.output, HasSubstr("of 0-6 (before the 0.100 m drop at x = "));
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + ".csv"));
  // A walk that goes on exits 0, as the stairs up above.
  const auto going = run_program("walk --duration 20 --fps 60 --terrain stairs:-0.17:0.28:6 -o " +
                                 shell_quoted(scratch("going")));
  EXPECT_EQ(going.status, 0) << going.output;
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

// `fuzzygait fuzzy check` flags a term whose points are out of order (which fuzzylite reads as
// a shape other than its name says), naming the file, the line and the term.
TEST(FuzzyCheckCommand, FlagsATermWhosePointsAreOutOfOrder) {
  const std::filesystem::path fll = scratch("disordered.fll");
  std::ofstream(fll) << "Engine: disordered\n"
                        "InputVariable: delta\n"
                        "  range: -1 1.29\n"
                        "  term: start Triangle -1 -1 0.9\n"
                        "  term: center Triangle 0.9 5 1.29\n"
                        "OutputVariable: out\n"
                        "  range: -1 1\n"
                        "  aggregation: Maximum\n"
                        "  defuzzifier: Centroid 100\n"
                        "  default: 0\n"
                        "  term: up Triangle 0 1 1\n"
                        "RuleBlock: rules\n"
                        "  implication: Minimum\n"
                        "  rule: if delta is center then out is up\n";
  const auto run = run_program("fuzzy check " + shell_quoted(fll));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output,
              HasSubstr(fll.string() +
                        ":5: term 'center' (Triangle): 'vertexB' 5 is past 'vertexC' 1.29; its "
                        "points must be in order (in 'delta')"));
  // In order, it is ready.
  std::string text = read_text(fll);
  text.replace(text.find("0.9 5 1.29"), 10, "0.9 1 1.29");
  std::ofstream(fll) << text;
  const auto fixed = run_program("fuzzy check " + shell_quoted(fll));
  EXPECT_EQ(fixed.status, 0) << fixed.output;
  EXPECT_THAT(fixed.output, HasSubstr("status: ready"));
  // A Mamdani engine is evaluated by the general engine; a shipped controller is not, and one
  // whose rules leave the row-major order says which rule.
  EXPECT_THAT(fixed.output,
              HasSubstr("walker fast path: no (input 'delta' does not lock its range)"));
  const std::filesystem::path sway = std::filesystem::path(FUZZYGAIT_SOURCE_DIR) / "controllers" /
                                     "default" / "upper_body_pelvis_sway.fll";
  const auto shipped = run_program("fuzzy check " + shell_quoted(sway));
  EXPECT_EQ(shipped.status, 0) << shipped.output;
  EXPECT_THAT(shipped.output, HasSubstr("walker fast path: yes"));
  std::string rules = read_text(sway);
  const std::string first =
      "  rule: if knee is straight and hip is extended then sway is centred\n";
  const std::string second = "  rule: if knee is straight and hip is neutral then sway is over\n";
  ASSERT_NE(rules.find(first + second), std::string::npos);
  rules.replace(rules.find(first + second), first.size() + second.size(), second + first);
  const std::filesystem::path swapped = scratch("swapped.fll");
  std::ofstream(swapped) << rules;
  const auto off = run_program("fuzzy check " + shell_quoted(swapped));
  EXPECT_EQ(off.status, 0) << off.output;
  EXPECT_THAT(off.output, HasSubstr("walker fast path: no (rule 1 is not 'if knee is straight and "
                                    "hip is extended then ...' in row-major order)"));
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
  // A step that is no length: before, nan, 0 and -1 silently meant "no step" and inf printed
  // "-nan %".
  for (const char* step : {"nan", "0", "-1", "inf"}) {
    run = run_program("eval " + shell_quoted(good.string() + ".csv") + " --step " + step);
    EXPECT_NE(run.status, 0) << step;
    EXPECT_THAT(run.output, HasSubstr(std::string("--step must be a step length above 0 and at "
                                                  "most 10 m, got ") +
                                      step))
        << step;
  }
}

}  // namespace
}  // namespace fuzzygait

namespace fuzzygait {
namespace {

// The root's position (the first three numbers) on the last line of a BVH file's motion.
std::array<double, 3> last_root_position(const std::string& bvh) {
  std::istringstream lines(bvh);
  std::string line, last;
  while (std::getline(lines, line)) {
    if (!line.empty()) last = line;
  }
  std::istringstream numbers(last);
  std::array<double, 3> p{};
  numbers >> p[0] >> p[1] >> p[2];
  return p;
}

TEST(WalkCommand, WalksTheWholeBodyAlongAPath) {
  const std::filesystem::path route = scratch("corner.csv");
  std::ofstream(route) << "x,z\n0,0\n0,4\n# then to the left\n4,4\n";
  const std::filesystem::path a = scratch("path_a");
  const std::filesystem::path b = scratch("path_b");
  for (const auto& prefix : {a, b}) {
    const auto run = run_program("walk --path " + shell_quoted(route) +
                                 " --speed 1.2 --fps 60 -o " + shell_quoted(prefix));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_THAT(run.output, HasSubstr("the whole body along the path"));
  }
  const std::string bvh = read_text(a.string() + ".body.bvh");
  EXPECT_EQ(bvh, read_text(b.string() + ".body.bvh"));
  EXPECT_FALSE(std::filesystem::exists(a.string() + ".body.glb"));  // only with --gltf
  EXPECT_THAT(bvh, HasSubstr("ROOT hips"));
  EXPECT_THAT(bvh, HasSubstr("JOINT leftUpperArm"));
  // Walked to the path's end (4, 4) and a little past, facing +X: x beyond 4, z at 4.
  const auto end = last_root_position(bvh);
  EXPECT_GT(end[0], 4.0);
  EXPECT_LT(end[0], 5.0);
  EXPECT_NEAR(end[2], 4.0, 0.05);
  // The sagittal files cover the same walk.
  std::ifstream csv(a.string() + ".csv");
  const eval::Motion m = io::read_walk_csv(csv, "path_a.csv");
  EXPECT_THAT(bvh, HasSubstr("Frames: " + std::to_string(m.frames.size()) + "\n"));
}

TEST(WalkCommand, WalksTheBodyOnAMocapSkeleton) {
  const std::filesystem::path prefix = scratch("on_cmu");
  const auto run = run_program("walk --cycles 2 --fps 60 --gltf --skeleton " FUZZYGAIT_SOURCE_DIR
                               "/data/mocap/cmu/07_01.bvh -o " +
                               shell_quoted(prefix));
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string bvh = read_text(prefix.string() + ".body.bvh");
  EXPECT_THAT(bvh, HasSubstr("JOINT LeftUpLeg"));
  EXPECT_THAT(bvh, HasSubstr("JOINT LeftForeArm"));
  // With --gltf the same frames as glTF too (tests/io/skeleton_gltf_import_test.cpp plays them),
  // beside the sagittal walk's PREFIX.glb; both are listed.
  const std::string glb = read_text(prefix.string() + ".body.glb");
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_THAT(glb, HasSubstr("\"name\":\"LeftForeArm\""));
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + ".glb"));
  EXPECT_THAT(run.output, HasSubstr(prefix.string() + ".body.glb"));
  EXPECT_THAT(run.output, HasSubstr(prefix.string() + ".glb"));
  // The walk took the clip's legs: thigh 0.397 m.
  std::ifstream csv(prefix.string() + ".csv");
  EXPECT_NEAR(io::read_walk_csv(csv, "on_cmu.csv").segments.thigh, 0.397, 0.002);
  const auto both = run_program("walk --stature 1.8 --skeleton " FUZZYGAIT_SOURCE_DIR
                                "/data/mocap/cmu/07_01.bvh -o " +
                                shell_quoted(prefix));
  EXPECT_NE(both.status, 0);
  EXPECT_THAT(both.output, HasSubstr("give --skeleton or a body"));
}

TEST(WalkCommand, APathWalksAnyBodyAndStopsOnAStall) {
  const std::filesystem::path route = scratch("line.csv");
  std::ofstream(route) << "x,z\n0,0\n0,8\n";
  // A heel the stature's proportions do not give: the body is the walk's.
  const auto heel = run_program("walk --path " + shell_quoted(route) + " --heel 0.06 -o " +
                                shell_quoted(scratch("heel")));
  EXPECT_EQ(heel.status, 0) << heel.output;
  // Down short treads the walk stalls: the body's walk stops there too and the command says where.
  const auto stall =
      run_program("walk --path " + shell_quoted(route) + " --terrain stairs:-0.10:0.20:6 -o " +
                  shell_quoted(scratch("stall")));
  EXPECT_NE(stall.status, 0);
  EXPECT_THAT(stall.output, HasSubstr("the walk stalled"));
  const auto radius = run_program("walk --corner-radius 2 -o " + shell_quoted(scratch("radius")));
  EXPECT_NE(radius.status, 0);
  EXPECT_THAT(radius.output, HasSubstr("--corner-radius rounds the corners of a --path"));
}

TEST(WalkCommand, ABadPathFileNamesTheLine) {
  const std::filesystem::path route = scratch("bad_path.csv");
  // Turns back on itself at its third point, on line 4 after a comment.
  std::ofstream(route) << "x,z\n0,0\n  # out and back\n0,3\n0.1,0\n";
  const auto run = run_program("walk --path " + shell_quoted(route) + " -o " +
                               shell_quoted(scratch("bad_path")));
  EXPECT_NE(run.status, 0);
  EXPECT_THAT(run.output, HasSubstr("bad_path.csv:4"));
  EXPECT_THAT(run.output, HasSubstr("turns back on itself"));
  std::ofstream(route) << "x,z\n0,0\n1.5 2,3\n";  // a blank inside a number
  const auto nan = run_program("walk --path " + shell_quoted(route) + " -o " +
                               shell_quoted(scratch("bad_path")));
  EXPECT_NE(nan.status, 0);
  EXPECT_THAT(nan.output, HasSubstr("bad_path.csv:3"));
  EXPECT_FALSE(std::filesystem::exists(scratch("bad_path.body.bvh")));
}

}  // namespace
}  // namespace fuzzygait
