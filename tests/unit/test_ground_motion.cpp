// Recorded ground motions: the PEER AT2 reader and the table reader on a
// synthetic record written from a known function (tests/data/ground_motion:
// a triangular pulse, 0.25 g at 0.25 s, -0.25 g at 0.75 s, 0 at 1 s, sampled
// every 0.05 s at its corners, so that linear interpolation reproduces the
// function exactly at any time), units, scale, baseline correction, and the
// errors naming file, line and value.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "dynamics/ground_motion.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

const std::string kData = std::string(ASHLAR_TEST_DATA) + "/ground_motion/";

// The pulse (in g) at time t (s).
double triangle(double t) {
  if (t < 0.0 || t > 1.0) return 0.0;
  if (t <= 0.25) return t;
  if (t <= 0.75) return 0.5 - t;
  return t - 1.0;
}

// A file of `text` in the test's temporary folder; its path.
std::string written(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

const char* kAt2Header =
    "PEER NGA STRONG MOTION DATABASE RECORD\nTEST\nACCELERATION TIME SERIES IN UNITS OF G\n";

}  // namespace

TEST(GroundMotion, At2RecordInterpolatesTheSampledFunctionExactly) {
  const RecordColumns record = read_at2(kData + "triangle.at2");
  ASSERT_EQ(record.times.size(), 21u);
  EXPECT_DOUBLE_EQ(record.times[20], 1.0);
  EXPECT_TRUE(record.has_unit);
  EXPECT_EQ(record.unit, AccelerationUnit::g);
  const GroundMotion motion(
      {record_component(record, 0, AccelerationUnit::g, 2.0, Baseline::none, Vec3::UnitX())});
  for (const double t : {-0.5, 0.0, 0.0123, 0.25, 0.3337, 0.5, 0.74, 0.75, 0.9876, 1.0, 1.2}) {
    const Vec3 a = motion(t);
    EXPECT_NEAR(a.x(), 2.0 * kGravity * triangle(t), 1e-12) << "t = " << t;
    EXPECT_EQ(a.y(), 0.0);
    EXPECT_EQ(a.z(), 0.0);
  }
  EXPECT_DOUBLE_EQ(motion.duration(), 1.0);
  EXPECT_NEAR(motion.peak(), 2.0 * 0.25 * kGravity, 1e-12);
  EXPECT_NEAR(motion.peak_time(), 0.25, 1e-12);
}

TEST(GroundMotion, TableColumnsActAlongTheirAxesInTheStatedUnits) {
  const RecordColumns record = read_acceleration_table(kData + "triangle.csv");
  ASSERT_EQ(record.columns.size(), 2u);
  EXPECT_FALSE(record.has_unit);
  const GroundMotion motion(
      {record_component(record, 0, AccelerationUnit::g, 1.0, Baseline::none, Vec3::UnitX()),
       record_component(record, 1, AccelerationUnit::m_per_s2, 1.0, Baseline::none, Vec3::UnitZ())});
  for (const double t : {0.1, 0.42, 0.8}) {
    EXPECT_NEAR(motion(t).x(), kGravity * triangle(t), 1e-12);
    EXPECT_NEAR(motion(t).z(), 0.5 * triangle(t), 1e-12);  // m/s^2 as written
  }
}

TEST(GroundMotion, NgaWest1HeaderAndFortranNumbersRead) {
  const std::string path = written("west1.at2", std::string(kAt2Header) +
                                                    "    4    0.0200    NPTS, DT\n +.1000E+00 -.2000E+00\n .3E-1 0\n");
  const RecordColumns record = read_at2(path);
  ASSERT_EQ(record.times.size(), 4u);
  EXPECT_DOUBLE_EQ(record.times[3], 0.06);
  EXPECT_DOUBLE_EQ(record.columns[0][1], -0.2);
  EXPECT_DOUBLE_EQ(record.columns[0][2], 0.03);
}

TEST(GroundMotion, BaselineCorrectionRemovesAConstantOrLinearOffset) {
  const RecordColumns clean = read_at2(kData + "triangle.at2");
  RecordColumns shifted = clean, drifting = clean;
  for (size_t k = 0; k < clean.times.size(); ++k) {
    shifted.columns[0][k] += 0.01;                                  // the pulse's samples sum to 0
    drifting.columns[0][k] += 0.01 + 0.02 * clean.times[k];
  }
  const auto values = [](const RecordColumns& r, Baseline b) {
    return record_component(r, 0, AccelerationUnit::g, 1.0, b, Vec3::UnitX()).values;
  };
  const std::vector<double> exact = values(clean, Baseline::none);
  const std::vector<double> mean = values(shifted, Baseline::mean);
  const std::vector<double> line = values(drifting, Baseline::linear), line_clean = values(clean, Baseline::linear);
  for (size_t k = 0; k < exact.size(); ++k) {
    EXPECT_NEAR(mean[k], exact[k], 1e-12);
    EXPECT_NEAR(line[k], line_clean[k], 1e-12);  // linear in the record: the added line goes whole
  }
}

TEST(GroundMotion, MalformedFilesNameFileLineAndValue) {
  const std::string bad_value = written("bad_value.at2", std::string(kAt2Header) + "NPTS=    3, DT= .01 SEC\n0.1 0.2x 0.3\n");
  EXPECT_EQ(error_of([&] { read_at2(bad_value); }), bad_value + ":5: expected an acceleration, got \"0.2x\"");
  const std::string short_file = written("short.at2", std::string(kAt2Header) + "NPTS=    4, DT= .01 SEC\n0.1 0.2 0.3\n");
  EXPECT_EQ(error_of([&] { read_at2(short_file); }), short_file + ":5: NPTS = 4 but the file holds 3 values");
  const std::string bad_units = written("units.at2", "A\nB\nVELOCITY IN CM/S\nNPTS= 2, DT= .01\n0 0\n");
  EXPECT_EQ(error_of([&] { read_at2(bad_units); }), bad_units + ":3: expected the units of acceleration (\"... UNITS OF G\", or CM/S/S, M/S/S), got \"VELOCITY IN CM/S\"");
  const std::string bad_dt = written("dt.at2", std::string(kAt2Header) + "NPTS= 2, DT= -1\n0 0\n");
  EXPECT_EQ(error_of([&] { read_at2(bad_dt); }), bad_dt + ":4: expected the step DT > 0 (s), got \"-1\"");
  const std::string back = written("back.csv", "t,a\n0,0\n0.1,1\n0.1,2\n");
  EXPECT_EQ(error_of([&] { read_acceleration_table(back); }), back + ":4: times must increase: 0.1 s follows 0.1 s");
  const std::string ragged = written("ragged.csv", "0,0,1\n0.1,1\n");
  EXPECT_EQ(error_of([&] { read_acceleration_table(ragged); }),
            ragged + ":2: expected 3 values as on the first data line, got 2: \"0.1,1\"");
  const std::string nan = written("nan.csv", "0,0\n0.1,nan\n");
  EXPECT_EQ(error_of([&] { read_acceleration_table(nan); }), nan + ":2: expected an acceleration, got \"nan\"");
  EXPECT_EQ(error_of([&] { read_acceleration_table(kData + "missing.csv"); }),
            "ground_motion: cannot open \"" + kData + "missing.csv\"");
}
