// The one whole-file reader (common/whole_file.h): the bytes to the end, or an InputError that
// names the file and the system's reason, worded as each kind of input has always been.
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "common/whole_file.h"

namespace nmm {
namespace {

TEST(WholeFile, ReadsToTheEnd) {
  const std::string text = read_whole_file(std::string(NMM_SOURCE_DIR) + "/common/whole_file.h");
  EXPECT_NE(text.find("read_whole_file"), std::string::npos);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(read_text_file(std::string(NMM_SOURCE_DIR) + "/common/whole_file.h"), text);
}

TEST(WholeFile, AMissingFileNamesTheFileAndTheReason) {
  const std::string missing = std::string(NMM_SOURCE_DIR) + "/no/such/file.json";
  try {
    read_text_file(missing);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), missing);
    EXPECT_EQ(e.where(), "");
    EXPECT_EQ(std::string(e.what()), missing + ": cannot read file: No such file or directory");
  }
}

TEST(WholeFile, AFolderFailsOnTheFirstRead) {
  try {
    read_whole_file(NMM_SOURCE_DIR);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), NMM_SOURCE_DIR);
    EXPECT_EQ(e.message(), "cannot read: Is a directory");
  }
  EXPECT_THROW(read_text_file(NMM_SOURCE_DIR), InputError);
}

}  // namespace
}  // namespace nmm
