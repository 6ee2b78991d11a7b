// ResultWriter, the file's life: the status when finished, failed or destroyed unfinished;
// refused paths and inconsistent input; no particles or frames; reopening to append; moves;
// no silent loss (an existing file kept unless overwritten, one writer per file).
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "coupling/output/ResultWriter.h"
#include "support/TempDir.h"
#include "tests/coupling/output/ResultSample.h"

namespace {

namespace fs = std::filesystem;
using tmdem::coupling::OutputError;
using tmdem::coupling::ResultHeader;
using tmdem::coupling::ResultWriter;
using tmdem::test::TempDir;
using namespace tmdem::coupling::test::result_sample;

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
