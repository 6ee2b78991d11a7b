// ResultWriter: the HDF5 layout of contract section 3, read back with the HDF5 C++ API.
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

extern char** environ;

namespace {

namespace fs = std::filesystem;
using tmdem::coupling::FrameView;
using tmdem::coupling::OutputError;
using tmdem::coupling::ResultHeader;
using tmdem::coupling::ResultWriter;
using tmdem::test::TempDir;

constexpr std::size_t kParticles = 3;

ResultHeader sample_header() {
  ResultHeader h;
  // Larger than the 64 KiB limit of compact attribute storage, to show the TOML always fits.
  h.scene_toml = "format = \"tmdem-scene-1\"\n# " + std::string(100000, 'x') + "\n";
  h.radius_m = {1e-3, 2e-3, 1.5e-3};
  h.mass_kg = {3.3e-5, 2.6e-4, 1.1e-4};
  h.heat_capacity_J_per_K = {0.015, 0.12, 0.05};
  h.material = {0, 1, 0};
  h.material_names = {"steel", "glass"};
  return h;
}

// Frame f: 2, 3 and 0 contacts; frame 1 has a contact with wall 0 (j = -1).
struct SampleFrame {
  double time_s;
  std::vector<double> position, velocity, temperature;
  std::vector<std::int64_t> pair;
  std::vector<double> force, conductance, tangential;

  FrameView view() const {
    // No heat flows (stored as NaN) and no wall positions (the walls stay where they are).
    return FrameView{.time_s = time_s,
                     .position_m = position,
                     .velocity_m_per_s = velocity,
                     .temperature_K = temperature,
                     .thermal_energy_J = 10.0 * time_s + 1.0,
                     .boundary_heat_J = -0.5 * time_s,
                     .contact_pair = pair,
                     .normal_force_N = force,
                     .conductance_W_per_K = conductance,
                     .tangential_force_N = tangential,
                     .heat_flow_W = {},
                     .wall_point_m = {}};
  }
};

SampleFrame sample_frame(std::size_t f) {
  SampleFrame s;
  s.time_s = 0.25 * static_cast<double>(f);
  for (std::size_t i = 0; i < kParticles; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      s.position.push_back(static_cast<double>(f) + 0.1 * static_cast<double>(i) +
                           0.01 * static_cast<double>(k));
      s.velocity.push_back(-static_cast<double>(f) - 0.1 * static_cast<double>(i) -
                           0.01 * static_cast<double>(k));
    }
    s.temperature.push_back(300.0 + 10.0 * static_cast<double>(f) + static_cast<double>(i));
  }
  if (f == 0) s.pair = {0, 1, 1, 2};
  if (f == 1) s.pair = {0, 1, 1, 2, 0, -1};
  for (std::size_t c = 0; c < s.pair.size() / 2; ++c) {
    s.force.push_back(100.0 * static_cast<double>(f) + static_cast<double>(c));
    s.conductance.push_back(1e-4 * static_cast<double>(c + 1));
    for (int k = 0; k < 3; ++k) s.tangential.push_back(0.5 * static_cast<double>(f) - k - 0.1 * c);
  }
  return s;
}

// ---- reading helpers (HDF5 C++ API) ----

std::vector<hsize_t> dims_of(const H5::DataSet& d) {
  H5::DataSpace space = d.getSpace();
  std::vector<hsize_t> dims(static_cast<std::size_t>(space.getSimpleExtentNdims()));
  space.getSimpleExtentDims(dims.data());
  return dims;
}

std::vector<double> read_doubles(const H5::H5File& file, const std::string& name) {
  H5::DataSet d = file.openDataSet(name);
  hsize_t count = 1;
  for (hsize_t n : dims_of(d)) count *= n;
  std::vector<double> values(count);
  if (count > 0) d.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

std::vector<std::int64_t> read_int64(const H5::H5File& file, const std::string& name) {
  H5::DataSet d = file.openDataSet(name);
  hsize_t count = 1;
  for (hsize_t n : dims_of(d)) count *= n;
  std::vector<std::int64_t> values(count);
  if (count > 0) d.read(values.data(), H5::PredType::NATIVE_INT64);
  return values;
}

std::string string_attribute(const H5::H5Object& object, const std::string& name) {
  H5::Attribute a = object.openAttribute(name);
  std::string value;
  a.read(a.getStrType(), value);
  return value;
}

// In the writing process itself, a second open of a file the ResultWriter holds must use the
// writer's file locking setting (off), else HDF5 refuses with "file locking flag values don't
// match". Other processes need no special setting (see OtherProcessReadsFileWhileRunning).
std::string root_attribute(const std::string& path, const std::string& name) {
  H5::FileAccPropList access;
  H5Pset_file_locking(access.getId(), false, true);
  H5::H5File file(path, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, access);
  return string_attribute(file, name);
}

using Dims = std::vector<hsize_t>;

herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* data) {
  if (info->type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

std::vector<std::string> all_datasets(const H5::H5File& file) {
  std::vector<std::string> names;
  H5Ovisit(file.getId(), H5_INDEX_NAME, H5_ITER_NATIVE, collect_dataset, &names);
  return names;
}

void write_sample(ResultWriter& writer, std::size_t frames) {
  for (std::size_t f = 0; f < frames; ++f) writer.write_frame(sample_frame(f).view());
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

TEST(ResultWriter, DestructorWithoutFinishMarksFailed) {
  TempDir dir;
  const std::string path = dir.file("crash.h5");
  {
    ResultWriter writer(path, sample_header(), true);
    write_sample(writer, 2);
  }
  EXPECT_EQ(root_attribute(path, "status"), "failed");
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(read_doubles(file, "/frames/time").size(), 2u);
  EXPECT_TRUE(fs::exists(dir.file("crash.xdmf")));
}

TEST(ResultWriter, FinishFailedSetsStatus) {
  TempDir dir;
  const std::string path = dir.file("failed.h5");
  ResultWriter writer(path, sample_header(), true);
  write_sample(writer, 1);
  writer.finish("failed");
  writer.finish("ok");  // a second call does nothing
  EXPECT_EQ(root_attribute(path, "status"), "failed");
  EXPECT_THROW(writer.write_frame(sample_frame(1).view()), std::logic_error);
}

TEST(ResultWriter, MissingFolderThrowsOutputErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("no/such/folder/result.h5");
  try {
    ResultWriter writer(path, sample_header(), true);
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST(ResultWriter, UnwritablePathThrowsOutputError) {
  TempDir dir;
  const std::string path = dir.file("a_folder.h5");
  fs::create_directories(path);  // a folder where the file should go
  try {
    ResultWriter writer(path, sample_header(), true);
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(ResultWriter, WithoutContactsWritesZeroOffsetsAndEmptyContacts) {
  TempDir dir;
  const std::string path = dir.file("nocontacts.h5");
  {
    ResultWriter writer(path, sample_header(), false);
    write_sample(writer, 3);  // the contacts given are ignored
    writer.finish("ok");
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(read_int64(file, "/frames/contact_offset"), (std::vector<std::int64_t>{0, 0, 0, 0}));
  EXPECT_EQ(dims_of(file.openDataSet("/contacts/pair")), (Dims{0, 2}));
  EXPECT_EQ(dims_of(file.openDataSet("/contacts/normal_force")), Dims{0});
  EXPECT_EQ(dims_of(file.openDataSet("/contacts/conductance")), Dims{0});
  EXPECT_EQ(dims_of(file.openDataSet("/contacts/tangential_force")), (Dims{0, 3}));
  EXPECT_EQ(string_attribute(file.openDataSet("/contacts/pair"), "units"), "1");
}

TEST(ResultWriter, RejectsInconsistentInput) {
  TempDir dir;
  ResultHeader header = sample_header();
  header.mass_kg.pop_back();
  EXPECT_THROW(ResultWriter(dir.file("a.h5"), header, true), std::invalid_argument);

  ResultWriter writer(dir.file("b.h5"), sample_header(), true);
  SampleFrame s = sample_frame(0);
  s.temperature.pop_back();
  EXPECT_THROW(writer.write_frame(s.view()), std::invalid_argument);
  s = sample_frame(0);
  s.force.pop_back();
  EXPECT_THROW(writer.write_frame(s.view()), std::invalid_argument);
  EXPECT_THROW(writer.finish("done"), std::invalid_argument);
  EXPECT_EQ(writer.frames(), 0u);
  writer.finish("ok");
}

TEST(ResultWriter, ZeroParticlesAndZeroFrames) {
  TempDir dir;
  const std::string path = dir.file("empty.h5");
  {
    ResultWriter writer(path, ResultHeader{}, true);
    writer.finish("ok");
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(dims_of(file.openDataSet("/frames/position")), (Dims{0, 0, 3}));
  EXPECT_EQ(read_int64(file, "/frames/contact_offset"), (std::vector<std::int64_t>{0}));
  EXPECT_EQ(string_attribute(file, "status"), "ok");
}

TEST(ResultWriter, ReopenKeepsFramesAndAppends) {
  TempDir dir;
  const std::string path = dir.file("restart.h5");
  {
    ResultWriter writer(path, sample_header(), true);
    write_sample(writer, 3);
  }  // "failed"
  {
    ResultWriter writer = ResultWriter::reopen(path, 2);
    EXPECT_EQ(writer.frames(), 2u);
    EXPECT_EQ(writer.particles(), kParticles);
    EXPECT_EQ(root_attribute(path, "status"), "running");
    SampleFrame s = sample_frame(1);
    s.time_s = 0.75;
    writer.write_frame(s.view());
    writer.finish("ok");
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(string_attribute(file, "status"), "ok");
  EXPECT_EQ(read_doubles(file, "/frames/time"), (std::vector<double>{0.0, 0.25, 0.75}));
  EXPECT_EQ(read_int64(file, "/frames/contact_offset"), (std::vector<std::int64_t>{0, 2, 5, 8}));
  EXPECT_EQ(dims_of(file.openDataSet("/contacts/pair")), (Dims{8, 2}));
  EXPECT_EQ(dims_of(file.openDataSet("/frames/velocity")), (Dims{3, kParticles, 3}));
}

TEST(ResultWriter, ReopenRejectsMissingFramesAndOtherFiles) {
  TempDir dir;
  const std::string path = dir.file("short.h5");
  {
    ResultWriter writer(path, sample_header(), true);
    write_sample(writer, 1);
    writer.finish("ok");
  }
  EXPECT_THROW(ResultWriter::reopen(path, 2), OutputError);
  EXPECT_EQ(root_attribute(path, "status"), "ok");
  EXPECT_THROW(ResultWriter::reopen(dir.file("none.h5"), 0), OutputError);
  {
    H5::H5File other(dir.file("other.h5"), H5F_ACC_TRUNC);
  }
  EXPECT_THROW(ResultWriter::reopen(dir.file("other.h5"), 0), OutputError);
}

TEST(ResultWriter, MoveKeepsOneOwner) {
  TempDir dir;
  const std::string path = dir.file("moved.h5");
  ResultWriter a(path, sample_header(), true);
  write_sample(a, 1);
  ResultWriter b(std::move(a));
  write_sample(b, 1);
  b.finish("ok");
  EXPECT_EQ(root_attribute(path, "status"), "ok");
}

// ---- no silent loss ----

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ResultWriter, ExistingFileIsRefusedUnlessOverwrite) {
  TempDir dir;
  const std::string path = dir.file("precious.h5");
  std::ofstream(path) << "not yours to overwrite\n";
  try {
    ResultWriter writer(path, sample_header(), true);
    FAIL() << "no exception";
  } catch (const tmdem::coupling::ResultMismatch& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--overwrite"), std::string::npos) << e.what();
  }
  EXPECT_EQ(file_bytes(path), "not yours to overwrite\n");
  EXPECT_FALSE(fs::exists(dir.file("precious.xdmf")));
  {
    ResultWriter writer(path, sample_header(), true, tmdem::coupling::ExistingResult::Overwrite);
    write_sample(writer, 1);
    writer.finish("ok");
  }
  EXPECT_EQ(root_attribute(path, "status"), "ok");
}

TEST(ResultWriter, SecondConcurrentWriterIsRefusedNamingTheFile) {
  TempDir dir;
  const std::string path = dir.file("shared.h5");
  ResultWriter first(path, sample_header(), true);
  write_sample(first, 2);
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      if (attempt == 0) {
        ResultWriter second(path, sample_header(), true, tmdem::coupling::ExistingResult::Overwrite);
      } else {
        ResultWriter second = ResultWriter::reopen(path, 1);
      }
      FAIL() << "no exception (attempt " << attempt << ")";
    } catch (const OutputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("another process"), std::string::npos) << e.what();
    }
  }
  // The first writer is untouched and completes its file.
  first.write_frame(sample_frame(2).view());
  first.finish("ok");
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(string_attribute(file, "status"), "ok");
  EXPECT_EQ(read_doubles(file, "/frames/time"), (std::vector<double>{0.0, 0.25, 0.5}));
  EXPECT_EQ(read_doubles(file, "/frames/temperature").back(), sample_frame(2).temperature.back());
}

TEST(ResultWriter, ReopenOfAnotherScenesFileLeavesItByteForByte) {
  TempDir dir;
  const std::string path = dir.file("other_scene.h5");
  const ResultHeader header = sample_header();
  {
    ResultWriter writer(path, header, true);
    write_sample(writer, 3);
    writer.finish("ok");
  }
  const std::string before = file_bytes(path);
  tmdem::coupling::RestartMatch match;
  match.particles = kParticles + 1;
  match.scene_toml = header.scene_toml;
  match.checkpoint_time_s = 10.0;
  EXPECT_THROW(ResultWriter::reopen(path, 2, &match), tmdem::coupling::ResultMismatch);
  match.particles = kParticles;
  match.scene_toml = "format = \"tmdem-scene-1\"\n# another scene\n";
  EXPECT_THROW(ResultWriter::reopen(path, 2, &match), tmdem::coupling::ResultMismatch);
  match.scene_toml = header.scene_toml;
  match.checkpoint_time_s = 0.1;  // frame 1 is at 0.25 s: the checkpoint cannot be from this file
  EXPECT_THROW(ResultWriter::reopen(path, 2, &match), tmdem::coupling::ResultMismatch);
  EXPECT_THROW(ResultWriter::reopen(path, 4, &match), OutputError);  // only 3 frames
  EXPECT_EQ(file_bytes(path), before);

  match.checkpoint_time_s = 0.25;
  match.next_scene_toml = header.scene_toml + "# extended\n";
  {
    ResultWriter writer = ResultWriter::reopen(path, 2, &match);
    writer.finish("ok");
  }
  EXPECT_EQ(root_attribute(path, "scene"), match.next_scene_toml);
}

}  // namespace
