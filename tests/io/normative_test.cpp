// Reference curves read from CSV: resampled onto the 2 % cycle grid, and bad files refused with
// the line and the column.
#include "fuzzygait/io/normative.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "fuzzygait/fuzzy/fll.hpp"

namespace fuzzygait {
namespace {

using ::testing::HasSubstr;

const std::string kHeader =
    "percent,hip_mean,hip_sd,knee_mean,knee_sd,ankle_mean,ankle_sd,pelvis_tilt_mean,"
    "pelvis_tilt_sd\n";

eval::Normative read(const std::string& text) {
  std::istringstream in(text);
  return io::read_normative_csv(in, "ref.csv");
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const fuzzy::ParseError& e) {
    return e.what();
  }
  return "no error";
}

TEST(NormativeCsv, ResamplesOntoTheCycleGrid) {
  const eval::Normative n = read(kHeader +
                                 "0,30,5,0,4,0,3,10,2\n"
                                 "50,-10,5,20,4,10,3,12,2\n"
                                 "100,30,7,0,6,0,5,10,4\n");
  EXPECT_DOUBLE_EQ(n.hip.mean[0], 30.0);
  EXPECT_DOUBLE_EQ(n.hip.mean[25], -10.0);  // 50 %
  EXPECT_DOUBLE_EQ(n.hip.mean[12], 30.0 - 40.0 * 24.0 / 50.0);
  EXPECT_DOUBLE_EQ(n.knee.sd[50], 6.0);
  EXPECT_DOUBLE_EQ(n.thigh.mean[25], -10.0 - 12.0);  // hip minus pelvis tilt
  EXPECT_DOUBLE_EQ(n.thigh.sd[50], 7.0);
}

TEST(NormativeCsv, BadFilesNameTheLineAndTheColumn) {
  const std::string good = "0,30,5,0,4,0,3,10,2\n100,30,7,0,6,0,5,10,4\n";
  EXPECT_EQ(error_of(kHeader + good), "no error");
  EXPECT_THAT(error_of(""), HasSubstr("ref.csv:1: the file is empty"));
  EXPECT_THAT(error_of("percent,hip_mean\n" + good), HasSubstr("ref.csv:1: missing column"));
  EXPECT_THAT(error_of(kHeader + "0,30,5,0,4,0,3,10,2\n100,30,7,x,6,0,5,10,4\n"),
              HasSubstr("ref.csv:3: column 'knee_mean' is not a finite number"));
  EXPECT_THAT(error_of(kHeader + "0,30,5,0,4,0,3,10,2\n0,30,7,0,6,0,5,10,4\n"),
              HasSubstr("ref.csv:3: percent must increase"));
  EXPECT_THAT(error_of(kHeader + "0,30,5,0,4,0,3,10,2\n90,30,7,0,6,0,5,10,4\n"),
              HasSubstr("must cover 0 to 100 percent"));
  // A negative spread would draw the band upside down and count no sample inside it.
  EXPECT_THAT(error_of(kHeader + "0,30,5,0,-4,0,3,10,2\n100,30,7,0,6,0,5,10,4\n"),
              HasSubstr("ref.csv:2: column 'knee_sd' is -4; a standard deviation in degrees"));
  EXPECT_THAT(error_of(kHeader + "0,30,5,0,4,0,3,10,2\n100,30,7,0,6,0,5,1e3,4\n"),
              HasSubstr("ref.csv:3: column 'pelvis_tilt_mean' is 1000; a mean angle in degrees"));
  EXPECT_EQ(error_of(kHeader + "0,180,0,-180,0,0,180,0,0\n100,30,7,0,6,0,5,10,4\n"), "no error");
}

TEST(NormativeCsv, EveryBuiltInReferenceLoads) {
  // Schwartz et al. 2008 at five speeds, Bovi et al. 2011 at five and on stairs up and down.
  ASSERT_EQ(io::builtin_normative_names().size(), 12u);
  for (const std::string& name : io::builtin_normative_names()) {
    const eval::Normative n = io::load_normative(name);
    EXPECT_EQ(n.name, name);
    // Level walks flex the swing knee at 72 %; Bovi's step ascent is a transitional stride whose
    // knee peaks earlier (see data/SOURCES.md).
    if (name.find("ascending") == std::string::npos) {
      EXPECT_GT(n.knee.mean[36], 40.0) << name << ": swing knee flexion at 72 %";
    }
    EXPECT_GT(*std::max_element(n.knee.mean.begin(), n.knee.mean.end()), 40.0) << name;
  }
}

}  // namespace
}  // namespace fuzzygait
