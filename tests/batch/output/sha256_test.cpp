// batch/output/sha256: FIPS 180-2 test vectors, and coreutils' sha256sum as an outside oracle
// for a file larger than the 1 MiB read block.
#include "batch/output/sha256.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "tests/batch/output/h5_read.hpp"  // test::out_dir

namespace ncpath::out {
namespace {

std::filesystem::path write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(Sha256File, KnownVectors) {
  const auto dir = test::out_dir("sha256");
  EXPECT_EQ(sha256_file(write_file(dir / "empty", "")),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_file(write_file(dir / "abc", "abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_file(write_file(dir / "two_blocks",
                                   "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_file(write_file(dir / "million_a", std::string(1000000, 'a'))),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256File, LargerThanOneReadBlockMatchesSha256sum) {
  const auto dir = test::out_dir("sha256_large");
  std::string bytes(3 * (1 << 20) + 12345, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 131) >> 3);
  const auto path = write_file(dir / "large.bin", bytes);

  std::FILE* pipe = popen(("sha256sum '" + path.string() + "'").c_str(), "r");
  if (pipe == nullptr) GTEST_SKIP() << "cannot run sha256sum";
  char out[65] = {};
  const std::size_t got = std::fread(out, 1, 64, pipe);
  const int rc = pclose(pipe);
  if (rc != 0 || got != 64) GTEST_SKIP() << "sha256sum not available";
  EXPECT_EQ(sha256_file(path), std::string(out, 64));
}

TEST(Sha256File, MissingFileThrowsNamingThePath) {
  const auto path = test::out_dir("sha256_missing") / "missing.stl";
  try {
    sha256_file(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(sha256_file(path.parent_path()), std::runtime_error);  // a directory
}

}  // namespace
}  // namespace ncpath::out
