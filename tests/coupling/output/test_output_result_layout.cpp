// ResultWriter, the layout: the HDF5 layout of contract section 3 (datasets, units, values),
// read back with the HDF5 C++ API, and another process reading the file while it is written.
#include <H5Cpp.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "coupling/output/ResultWriter.h"
#include "coupling/output/XdmfWriter.h"
#include "support/TempDir.h"
#include "tests/coupling/output/ResultSample.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using tmdem::coupling::ResultWriter;
using tmdem::test::TempDir;
using namespace tmdem::coupling::test::result_sample;

herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* data) {
  if (info->type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

std::vector<std::string> all_datasets(const H5::H5File& file) {
  std::vector<std::string> names;
  H5Ovisit(file.getId(), H5_INDEX_NAME, H5_ITER_NATIVE, collect_dataset, &names);
  return names;
}

// ---- tests ----

TEST(ResultWriter, WritesContractLayoutUnitsAndValues) {
  TempDir dir;
  const std::string path = dir.file("result.h5");
  const ResultHeader header = sample_header();
  {
    ResultWriter writer(path, header, true);
    write_sample(writer, 3);
    EXPECT_EQ(writer.frames(), 3u);
    EXPECT_EQ(writer.particles(), kParticles);
    writer.finish("ok");
    EXPECT_TRUE(writer.finished());
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(string_attribute(file, "format"), "tmdem-result-1");
  EXPECT_EQ(string_attribute(file, "version"), TMDEM_VERSION);
  EXPECT_EQ(string_attribute(file, "scene"), header.scene_toml);
  EXPECT_EQ(string_attribute(file, "status"), "ok");

  const std::map<std::string, std::pair<Dims, std::string>> expected = {
      {"/particles/radius", {{3}, "m"}},
      {"/particles/mass", {{3}, "kg"}},
      {"/particles/heat_capacity", {{3}, "J/K"}},
      {"/particles/material", {{3}, "1"}},
      {"/frames/time", {{3}, "s"}},
      {"/frames/position", {{3, 3, 3}, "m"}},
      {"/frames/velocity", {{3, 3, 3}, "m/s"}},
      {"/frames/temperature", {{3, 3}, "K"}},
      {"/frames/thermal_energy", {{3}, "J"}},
      {"/frames/boundary_heat", {{3}, "J"}},
      {"/frames/contact_offset", {{4}, "1"}},
      {"/contacts/pair", {{5, 2}, "1"}},
      {"/contacts/normal_force", {{5}, "N"}},
      {"/contacts/tangential_force", {{5, 3}, "N"}},
      {"/contacts/conductance", {{5}, "W/K"}},
      {"/contacts/heat_flow", {{5}, "W"}},
      {"/walls/point", {{0, 3}, "m"}},
      {"/walls/normal", {{0, 3}, "1"}},
      {"/walls/radius", {{0}, "m"}},
      {"/walls/temperature", {{0}, "K"}},
      {"/xdmf/vertices", {{3}, "1"}},
      {"/xdmf/no_lines", {{0, 2}, "1"}},
      {"/xdmf/no_values", {{0}, "1"}},
      {"/xdmf/no_vectors", {{0, 3}, "1"}},
  };
  for (const auto& [name, shape_units] : expected) {
    SCOPED_TRACE(name);
    H5::DataSet d = file.openDataSet(name);
    EXPECT_EQ(dims_of(d), shape_units.first);
    EXPECT_EQ(string_attribute(d, "units"), shape_units.second);
  }
  // No other datasets but the per-frame views of RESULT.xdmf, and every dataset has units.
  std::vector<std::string> names = all_datasets(file);
  std::size_t views = 0;
  for (const std::string& name : names) {
    if (name.rfind("xdmf/frame_", 0) == 0) {
      ++views;
      EXPECT_FALSE(string_attribute(file.openDataSet(name), "units").empty()) << name;
    } else {
      EXPECT_TRUE(expected.count("/" + name)) << name;
    }
  }
  EXPECT_EQ(names.size() - views, expected.size());

  EXPECT_EQ(read_doubles(file, "/particles/radius"), header.radius_m);
  EXPECT_EQ(read_doubles(file, "/particles/mass"), header.mass_kg);
  EXPECT_EQ(read_doubles(file, "/particles/heat_capacity"), header.heat_capacity_J_per_K);
  {
    H5::DataSet material = file.openDataSet("/particles/material");
    EXPECT_EQ(material.getTypeClass(), H5T_INTEGER);
    std::vector<int> values(3);
    material.read(values.data(), H5::PredType::NATIVE_INT);
    EXPECT_EQ(values, header.material);
    H5::Attribute names_attribute = material.openAttribute("names");
    EXPECT_EQ(names_attribute.getSpace().getSimpleExtentNpoints(), 2);
  }
  EXPECT_EQ(file.openDataSet("/contacts/pair").getDataType(), H5::PredType::STD_I64LE);

  std::vector<double> time, position, velocity, temperature, energy, heat;
  std::vector<std::int64_t> pair;
  std::vector<double> force, conductance, tangential;
  for (std::size_t f = 0; f < 3; ++f) {
    const SampleFrame s = sample_frame(f);
    time.push_back(s.time_s);
    position.insert(position.end(), s.position.begin(), s.position.end());
    velocity.insert(velocity.end(), s.velocity.begin(), s.velocity.end());
    temperature.insert(temperature.end(), s.temperature.begin(), s.temperature.end());
    energy.push_back(s.view().thermal_energy_J);
    heat.push_back(s.view().boundary_heat_J);
    pair.insert(pair.end(), s.pair.begin(), s.pair.end());
    force.insert(force.end(), s.force.begin(), s.force.end());
    conductance.insert(conductance.end(), s.conductance.begin(), s.conductance.end());
    tangential.insert(tangential.end(), s.tangential.begin(), s.tangential.end());
  }
  EXPECT_EQ(read_doubles(file, "/frames/time"), time);
  EXPECT_EQ(read_doubles(file, "/frames/position"), position);
  EXPECT_EQ(read_doubles(file, "/frames/velocity"), velocity);
  EXPECT_EQ(read_doubles(file, "/frames/temperature"), temperature);
  EXPECT_EQ(read_doubles(file, "/frames/thermal_energy"), energy);
  EXPECT_EQ(read_doubles(file, "/frames/boundary_heat"), heat);
  EXPECT_EQ(read_int64(file, "/frames/contact_offset"), (std::vector<std::int64_t>{0, 2, 5, 5}));
  EXPECT_EQ(read_int64(file, "/contacts/pair"), pair);
  EXPECT_EQ(pair[9], -1);  // frame 1, third contact: wall 0
  EXPECT_EQ(read_doubles(file, "/contacts/normal_force"), force);
  EXPECT_EQ(read_doubles(file, "/contacts/conductance"), conductance);
  EXPECT_EQ(read_doubles(file, "/contacts/tangential_force"), tangential);

  EXPECT_TRUE(fs::exists(dir.file("result.xdmf")));
}

// ---- a second process reads the file while the writer is still open ----

int run_reader_process(const std::string& file, std::size_t frames, std::string& log_text) {
  std::vector<std::string> environment;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    if (entry.rfind("HDF5_USE_FILE_LOCKING=", 0) == 0 || entry.rfind("TMDEM_OUTPUT_CHILD", 0) == 0 ||
        entry.rfind("GTEST_", 0) == 0) {
      continue;  // the reader uses plain default HDF5 settings
    }
    environment.push_back(entry);
  }
  environment.push_back("TMDEM_OUTPUT_CHILD_FILE=" + file);
  environment.push_back("TMDEM_OUTPUT_CHILD_FRAMES=" + std::to_string(frames));
  std::vector<char*> envp;
  for (std::string& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);

  std::string program = fs::read_symlink("/proc/self/exe").string();
  std::string filter = "--gtest_filter=NoTestAtAll";  // never recurse into the tests
  char* argv[] = {program.data(), filter.data(), nullptr};
  const std::string log = file + ".child.log";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv, envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  log_text = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The reader process of ResultWriter.OtherProcessReadsFileWhileRunning: this same test program,
// started with TMDEM_OUTPUT_CHILD_FILE set, opens the file with plain default HDF5 settings, checks
// it and exits before gtest starts. Exit 0 and a FILE.child-ok marker mean success.
int reader_process_main(const std::string& file, hsize_t frames) {
  try {
    H5::H5File h5(file, H5F_ACC_RDONLY);  // default access properties, default file locking
    std::string problem;
    if (string_attribute(h5, "status") != "running") problem += "status is not running; ";
    if (dims_of(h5.openDataSet("/frames/time")) != Dims{frames}) problem += "time shape; ";
    if (dims_of(h5.openDataSet("/frames/position")) != Dims{frames, kParticles, 3})
      problem += "position; ";
    if (dims_of(h5.openDataSet("/frames/contact_offset")) != Dims{frames + 1}) problem += "offset; ";
    const std::vector<double> temperature = read_doubles(h5, "/frames/temperature");
    if (temperature.size() != frames * kParticles ||
        temperature.back() != sample_frame(frames - 1).temperature.back()) {
      problem += "temperature values; ";
    }
    if (!problem.empty()) {
      std::fprintf(stderr, "reader process: %s\n", problem.c_str());
      return 1;
    }
  } catch (const H5::Exception& e) {
    std::fprintf(stderr, "reader process: %s %s\n", e.getFuncName().c_str(),
                 e.getDetailMsg().c_str());
    return 1;
  }
  std::ofstream(file + ".child-ok") << "ok\n";
  return 0;
}

const bool kIsReaderProcess = [] {
  const char* file = std::getenv("TMDEM_OUTPUT_CHILD_FILE");
  const char* frames = std::getenv("TMDEM_OUTPUT_CHILD_FRAMES");
  if (file == nullptr || frames == nullptr) return false;
  std::exit(reader_process_main(file, std::stoul(frames)));
}();

TEST(ResultWriter, OtherProcessReadsFileWhileRunning) {
  TempDir dir;
  const std::string path = dir.file("running.h5");
  ResultWriter writer(path, sample_header(), true);
  write_sample(writer, 2);
  std::string log;
  EXPECT_EQ(run_reader_process(path, 2, log), 0) << log;
  EXPECT_TRUE(fs::exists(path + ".child-ok")) << log;

  writer.write_frame(sample_frame(2).view());
  fs::remove(path + ".child-ok");
  EXPECT_EQ(run_reader_process(path, 3, log), 0) << log;
  EXPECT_TRUE(fs::exists(path + ".child-ok")) << log;

  writer.finish("ok");
  EXPECT_EQ(root_attribute(path, "status"), "ok");
}

}  // namespace
