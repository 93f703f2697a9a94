// Whole files: a replaced file is never seen half-written, and every failure names the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "binpick/core/file.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::core {
namespace {

namespace fs = std::filesystem;

class WholeFile : public test::TempDirectoryTest {
 protected:
  // Names in the test's directory: a leftover temporary file would show here.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(root())) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

TEST_F(WholeFile, WritesReadsAndReplaces) {
  const std::string path = pathOf("port");
  writeFileAtomically(path, "4242\n");
  EXPECT_EQ(readFile(path), "4242\n");
  writeFileAtomically(path, std::string("\0binary\xff", 8));
  EXPECT_EQ(readFile(path), std::string("\0binary\xff", 8));
  EXPECT_EQ(entries(), std::vector<std::string>{"port"});
}

TEST_F(WholeFile, MissingDirectoryIsAnErrorNamingThePath) {
  const std::string path = pathOf("no_such_directory/calib.yaml");
  EXPECT_TRUE(test::throwsNaming([&] { writeFileAtomically(path, "x"); }, path + ": cannot write the file"));
  EXPECT_TRUE(entries().empty());
  writeFileAtomically(path, "x", ParentDirectory::Create);
  EXPECT_EQ(readFile(path), "x");
}

TEST_F(WholeFile, AFailedWriterLeavesTheOldFileAndNoTemporary) {
  const std::string path = pathOf("calib.yaml");
  writeFileAtomically(path, "old");
  EXPECT_THROW(replaceFileAtomically(path,
                                     [](const std::string& temporary) {
                                       std::ofstream(temporary) << "half";
                                       throw std::runtime_error("encoder failed");
                                     }),
               std::runtime_error);
  EXPECT_EQ(readFile(path), "old");
  EXPECT_EQ(entries(), std::vector<std::string>{"calib.yaml"});
}

TEST_F(WholeFile, WritingOverADirectoryFailsAndKeepsIt) {
  const std::string path = pathOf("taken");
  fs::create_directories(path + "/inside");
  EXPECT_TRUE(test::throwsNaming([&] { writeFileAtomically(path, "1"); }, path + ": cannot write the file"));
  EXPECT_TRUE(fs::is_directory(path + "/inside"));
  EXPECT_EQ(entries(), std::vector<std::string>{"taken"});
}

TEST_F(WholeFile, MissingFileOrADirectoryIsAnErrorNamingIt) {
  const std::string path = pathOf("missing.txt");
  EXPECT_TRUE(test::throwsNaming([&] { readFile(path); }, path + ": the file does not exist"));
  EXPECT_TRUE(test::throwsNaming([&] { readFile(root()); }, root() + ": is a directory"));
}

// A mapped file holds the bytes it had when it was mapped: writers replace files whole, so one
// replaced under a reader (a model cache rewritten by another service) leaves the reader's bytes.
TEST_F(WholeFile, AMappedFileKeepsItsBytesWhenTheFileIsReplaced) {
  const std::string path = pathOf("cache");
  writeFileAtomically(path, "first version");
  const std::shared_ptr<const MappedFile> mapped = MappedFile::open(path);
  writeFileAtomically(path, "second, longer version");
  ASSERT_EQ(mapped->size(), 13u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(mapped->data()), mapped->size()), "first version");
  EXPECT_EQ(MappedFile::open(path)->size(), 22u);

  writeFileAtomically(path, "");
  EXPECT_EQ(MappedFile::open(path)->size(), 0u) << "an empty file maps to nothing, without an error";
}

TEST_F(WholeFile, MappingAMissingFileOrADirectoryIsAnErrorNamingIt) {
  const std::string path = pathOf("missing.cache");
  EXPECT_TRUE(test::throwsNaming([&] { MappedFile::open(path); }, path + ": the file does not exist"));
  EXPECT_TRUE(test::throwsNaming([&] { MappedFile::open(root()); }, root() + ": is a directory"));
}

}  // namespace
}  // namespace binpick::core
