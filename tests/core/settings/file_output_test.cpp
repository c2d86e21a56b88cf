// Output files are written whole or not at all (core/settings/file_output.h): the PNG, the bench tables, the
// sim's and the viewer's reports, saved scenes.
#include "core/settings/file_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace slime::testing {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Nothing but `expected` in the directory: no temporary file left beside it.
void expectOnly(const fs::path& directory, const std::vector<std::string>& expected) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(directory)) found.push_back(entry.path().filename().string());
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected);
}

TEST(FileOutput, WritesWholeAndReplacesTheOldFile) {
  const fs::path directory = fs::path(SLIME_TEST_OUTPUT_DIR) / "file_output";
  fs::remove_all(directory);
  fs::create_directories(directory);
  const fs::path path = directory / "report.json";
  writeFileAtomically(path.string(), "first\n");
  EXPECT_EQ(contents(path), "first\n");
  const std::string longer(100000, 'x');
  writeFileAtomically(path.string(), longer);
  EXPECT_EQ(contents(path), longer);
  writeFileAtomically(path.string(), "");
  EXPECT_EQ(contents(path), "");
  expectOnly(directory, {"report.json"});
}

TEST(FileOutput, AFailedWriteLeavesNothingAndSaysWhy) {
  const fs::path directory = fs::path(SLIME_TEST_OUTPUT_DIR) / "file_output_failed";
  fs::remove_all(directory);
  fs::create_directories(directory);
  // No such directory: nothing is created, and the message names the path and the reason.
  const std::string missing = (directory / "no_such_dir" / "out.json").string();
  try {
    writeFileAtomically(missing, "text");
    FAIL() << "a write into a missing directory succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write " + missing), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos) << e.what();
  }
  // The target is a directory: the bytes are written, the rename fails; the temporary file is
  // removed and the file beside it untouched.
  const fs::path kept = directory / "kept.json";
  writeFileAtomically(kept.string(), "old\n");
  const fs::path blocked = directory / "blocked";
  fs::create_directories(blocked / "inside");
  EXPECT_THROW(writeFileAtomically(blocked.string(), "text"), std::runtime_error);
  EXPECT_EQ(contents(kept), "old\n");
  expectOnly(directory, {"blocked", "kept.json"});
}

// Files that belong together (an .obj and its .mtl): when one cannot be written, neither is.
TEST(FileOutput, FilesThatBelongTogetherAreWrittenAllOrNone) {
  const fs::path directory = fs::path(SLIME_TEST_OUTPUT_DIR) / "file_output_together";
  fs::remove_all(directory);
  fs::create_directories(directory);
  const std::string first = (directory / "a.mtl").string(), second = (directory / "a.obj").string();
  EXPECT_THROW(writeFilesAtomically({{first, "mtl\n"}, {(directory / "missing" / "a.obj").string(), "obj\n"}}),
               std::runtime_error);
  expectOnly(directory, {});  // the first file's bytes were written, then removed
  writeFilesAtomically({{first, "mtl\n"}, {second, "obj\n"}});
  EXPECT_EQ(contents(first), "mtl\n");
  EXPECT_EQ(contents(second), "obj\n");
  expectOnly(directory, {"a.mtl", "a.obj"});
}

}  // namespace
}  // namespace slime::testing
