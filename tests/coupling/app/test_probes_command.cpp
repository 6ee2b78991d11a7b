// Probes end to end: a run of four touching particles at known temperatures (mechanics off)
// stores per frame the count, mean, min and max temperature of the particles inside each
// [[probe]], equal to those computed here from the file's own /frames/temperature; `tmdem
// probes` prints them as CSV; a result without probes is refused with exit code 2.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "e2e/E2eSupport.h"

namespace tmdem::e2e {
namespace {

// Four steel spheres of 1 mm in a row along x (touching), at 400, 300, 350 and 290 K, conducting
// through constant contact conductances. "left": a sphere holding particles 0 and 1 (each 1 mm
// from its centre); "right": a box holding 2 and 3; "nothing": a sphere off the row.
const char* kScene = R"(format = "tmdem-scene-1"
[simulation]
duration = 1.0
[effects]
mechanics = "off"
conduction = true
[[material]]
name = "steel"
density = 7800.0
young_modulus = 2.1e11
poisson_ratio = 0.3
conductivity = 50.0
heat_capacity = 460.0
[[particle]]
position = [0.0, 0.0, 0.0]
radius = 0.001
material = "steel"
temperature = 400.0
[[particle]]
position = [0.002, 0.0, 0.0]
radius = 0.001
material = "steel"
temperature = 300.0
[[particle]]
position = [0.004, 0.0, 0.0]
radius = 0.001
material = "steel"
temperature = 350.0
[[particle]]
position = [0.006, 0.0, 0.0]
radius = 0.001
material = "steel"
temperature = 290.0
[thermal]
conductance = "constant"
constant_conductance = 1.0e-2
[output]
file = "r.h5"
interval = 0.25
contacts = false
[[probe]]
name = "left"
point = [0.001, 0.0, 0.0]
radius = 0.0011
[[probe]]
name = "right"
point = [0.005, 0.0, 0.0]
box = [0.0025, 0.001, 0.001]
[[probe]]
name = "nothing"
point = [0.0, 0.01, 0.0]
radius = 0.001
)";

std::vector<double> read_all(const H5::H5File& file, const std::string& name, std::vector<hsize_t>& dims) {
  const H5::DataSet set = file.openDataSet(name);
  const H5::DataSpace space = set.getSpace();
  dims.assign(std::size_t(space.getSimpleExtentNdims()), 0);
  space.getSimpleExtentDims(dims.data());
  std::size_t n = 1;
  for (auto d : dims) n *= d;
  std::vector<double> values(n);
  set.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

}  // namespace

TEST(Probes, ReadingsEqualTheStoredTemperaturesAndTheCommandPrintsThem) {
  const std::string dir = scratch_dir("probes");
  write_file(dir + "/scene.toml", kScene);
  const ProgramResult run = run_tmdem("run scene.toml --quiet", dir);
  ASSERT_EQ(run.exit_code, 0) << run.output;

  H5::H5File file(dir + "/r.h5", H5F_ACC_RDONLY);
  std::vector<hsize_t> dims;
  const std::vector<double> time = read_all(file, "/frames/time", dims);
  const std::size_t frames = time.size();
  ASSERT_EQ(frames, 5u);  // t = 0, 0.25, ..., 1
  const std::vector<double> T = read_all(file, "/frames/temperature", dims);
  const std::vector<double> mean = read_all(file, "/probes/mean_K", dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{frames, 3}));
  const std::vector<double> min = read_all(file, "/probes/min_K", dims);
  const std::vector<double> max = read_all(file, "/probes/max_K", dims);
  const std::vector<double> count = read_all(file, "/probes/count", dims);
  file.close();

  // The first frame holds the scene's temperatures: by hand.
  EXPECT_EQ(mean[0], 350.0);
  EXPECT_EQ(min[0], 300.0);
  EXPECT_EQ(max[0], 400.0);
  EXPECT_EQ(mean[1], 320.0);
  EXPECT_EQ(min[1], 290.0);
  EXPECT_EQ(max[1], 350.0);
  for (std::size_t f = 0; f < frames; ++f) {
    const double* t = &T[4 * f];
    const double* row_mean = &mean[3 * f];
    EXPECT_EQ(count[3 * f + 0], 2.0);
    EXPECT_DOUBLE_EQ(row_mean[0], 0.5 * (t[0] + t[1]));
    EXPECT_EQ(min[3 * f + 0], std::min(t[0], t[1]));
    EXPECT_EQ(max[3 * f + 0], std::max(t[0], t[1]));
    EXPECT_EQ(count[3 * f + 1], 2.0);
    EXPECT_DOUBLE_EQ(row_mean[1], 0.5 * (t[2] + t[3]));
    EXPECT_EQ(min[3 * f + 1], std::min(t[2], t[3]));
    EXPECT_EQ(max[3 * f + 1], std::max(t[2], t[3]));
    EXPECT_EQ(count[3 * f + 2], 0.0);
    EXPECT_EQ(row_mean[2], 0.0);
    EXPECT_EQ(min[3 * f + 2], 0.0);
    EXPECT_EQ(max[3 * f + 2], 0.0);
  }
  // Heat flowed: the left pair's spread shrank by the last frame.
  EXPECT_LT(max[3 * (frames - 1)] - min[3 * (frames - 1)], 100.0 - 1.0);

  const ProgramResult printed = run_tmdem("probes r.h5", dir);
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  std::istringstream lines(printed.output);
  std::string line;
  ASSERT_TRUE(std::getline(lines, line));
  EXPECT_EQ(line, "time_s,probe,count,mean_K,min_K,max_K");
  const char* names[3] = {"left", "right", "nothing"};
  for (std::size_t f = 0; f < frames; ++f)
    for (std::size_t p = 0; p < 3; ++p) {
      ASSERT_TRUE(std::getline(lines, line)) << "frame " << f << " probe " << p;
      std::istringstream fields(line);
      std::string time_s, name, n, m, lo, hi;
      std::getline(fields, time_s, ',');
      std::getline(fields, name, ',');
      std::getline(fields, n, ',');
      std::getline(fields, m, ',');
      std::getline(fields, lo, ',');
      std::getline(fields, hi, ',');
      EXPECT_EQ(std::stod(time_s), time[f]);
      EXPECT_EQ(name, names[p]);
      EXPECT_EQ(std::stod(n), count[3 * f + p]);
      EXPECT_EQ(std::stod(m), mean[3 * f + p]);  // shortest round-trip text: the same double
      EXPECT_EQ(std::stod(lo), min[3 * f + p]);
      EXPECT_EQ(std::stod(hi), max[3 * f + p]);
    }
  EXPECT_FALSE(std::getline(lines, line));
  EXPECT_EQ(printed.output.substr(0, 75).find("0,left,2,350,300,400"), 38u) << printed.output;

  const ProgramResult written = run_tmdem("probes r.h5 -o probes.csv", dir);
  ASSERT_EQ(written.exit_code, 0) << written.output;
  EXPECT_EQ(text_of(dir + "/probes.csv"), printed.output);

  const std::string scene = kScene;
  write_file(dir + "/plain.toml", scene.substr(0, scene.find("[[probe]]")));
  const ProgramResult plain = run_tmdem("run plain.toml --quiet -o plain.h5", dir);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const ProgramResult refused = run_tmdem("probes plain.h5", dir);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.output.find("has no probes"), std::string::npos) << refused.output;
  const ProgramResult missing = run_tmdem("probes nowhere.h5", dir);
  EXPECT_EQ(missing.exit_code, 4);
}

}  // namespace tmdem::e2e
