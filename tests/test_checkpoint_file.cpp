// The checkpoint container (common/checkpoint_file.h): round trip, and every single flipped bit
// and every truncation of a small file refused with an InputError naming the file.
#include <gtest/gtest.h>

#include <string>

#include "common/checkpoint_file.h"
#include "common/error.h"

namespace nmm {
namespace {

CheckpointSections sample() {
  return {{"META", std::string("\x01\x02\x03\x04\x05", 5)},
          {"EMPTY", ""},
          {"DATA", std::string(37, '\x5a')},
          {"LAST", "end"}};
}

TEST(CheckpointFile, RoundTrip) {
  const std::string bytes = checkpoint_to_bytes(sample());
  EXPECT_EQ(checkpoint_from_bytes(bytes, "x.nmmstate"), sample());
}

TEST(CheckpointFile, EveryFlippedBitIsRefused) {
  const std::string good = checkpoint_to_bytes(sample());
  for (std::size_t i = 0; i < good.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      std::string bad = good;
      bad[i] = static_cast<char>(bad[i] ^ (1 << bit));
      try {
        checkpoint_from_bytes(bad, "x.nmmstate");
        ADD_FAILURE() << "byte " << i << " bit " << bit << " flipped was accepted";
      } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "x.nmmstate");
      }
    }
}

TEST(CheckpointFile, EveryTruncationAndExtensionIsRefused) {
  const std::string good = checkpoint_to_bytes(sample());
  for (std::size_t n = 0; n < good.size(); ++n)
    EXPECT_THROW(checkpoint_from_bytes(good.substr(0, n), "x.nmmstate"), InputError) << n;
  EXPECT_THROW(checkpoint_from_bytes(good + '\0', "x.nmmstate"), InputError);
}

TEST(CheckpointFile, WriteIsAtomicAndReadable) {
  const std::string path = ::testing::TempDir() + "/nmm_test.nmmstate";
  write_checkpoint_file(sample(), path);
  EXPECT_EQ(read_checkpoint_file(path), sample());
  EXPECT_THROW(write_checkpoint_file(sample(), ::testing::TempDir() + "/no/such/dir/x.nmmstate"),
               InputError);
  EXPECT_THROW(read_checkpoint_file(::testing::TempDir() + "/no_such.nmmstate"), InputError);
}

}  // namespace
}  // namespace nmm
