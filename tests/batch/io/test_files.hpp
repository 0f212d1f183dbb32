#pragma once
// Fixture files for the reader/writer tests, generated in a fresh temporary directory. The
// binary STL bytes are laid out here by hand (not by the writer under test), so the reader
// tests have an independent oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "batch/io/mesh_reader.hpp"
#include "batch/io/read_error.hpp"

namespace ncpath::io::testing {

// A directory of its own per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "ncpath_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    if (info) name += std::string("_") + info->name();
    dir_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return dir_; }

  // Writes `bytes` to dir/name and returns the full path.
  std::filesystem::path write(const std::string& name, std::string_view bytes) const {
    const auto p = dir_ / name;
    std::ofstream out(p, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    EXPECT_TRUE(out.good()) << "cannot write fixture " << p;
    return p;
  }

 private:
  std::filesystem::path dir_;
};

// One binary STL facet: normal, then three vertices, float32.
using RawFacet = std::array<float, 12>;

inline RawFacet raw_facet(std::array<float, 3> a, std::array<float, 3> b, std::array<float, 3> c) {
  return {0, 0, 0, a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]};
}

// Binary STL bytes: 80-byte header (zero-padded), count (the real one unless overridden),
// 50 bytes per facet with a zero attribute.
inline std::string binary_stl(std::string_view header, const std::vector<RawFacet>& facets,
                              std::optional<std::uint32_t> count = std::nullopt) {
  std::string out(80, '\0');
  std::memcpy(out.data(), header.data(), std::min<std::size_t>(header.size(), 80));
  const std::uint32_t n = count.value_or(static_cast<std::uint32_t>(facets.size()));
  const unsigned char le[4] = {static_cast<unsigned char>(n), static_cast<unsigned char>(n >> 8),
                               static_cast<unsigned char>(n >> 16),
                               static_cast<unsigned char>(n >> 24)};
  out.append(reinterpret_cast<const char*>(le), 4);
  for (const RawFacet& f : facets) {
    for (float x : f) {
      std::uint32_t bits;
      std::memcpy(&bits, &x, 4);
      for (int k = 0; k < 4; ++k) out += static_cast<char>((bits >> (8 * k)) & 0xFF);
    }
    out.append(2, '\0');
  }
  return out;
}

// Expects that calling f throws a ReadError whose message contains every one of `parts`.
template <class F>
void expect_read_error(F&& f, std::initializer_list<std::string_view> parts) {
  try {
    f();
    ADD_FAILURE() << "expected a ReadError";
  } catch (const ReadError& e) {
    const std::string what = e.what();
    for (std::string_view part : parts)
      EXPECT_NE(what.find(part), std::string::npos)
          << "message lacks \"" << part << "\"\n  message: " << what;
  }
}

// A file read in pieces against the same file read as one: the same mesh and statistics.
inline void expect_same_read(const MeshReadResult& pieces, const MeshReadResult& whole,
                             std::size_t piece_bytes) {
  EXPECT_EQ(pieces.mesh.vertices, whole.mesh.vertices) << piece_bytes;
  EXPECT_EQ(pieces.mesh.facets, whole.mesh.facets) << piece_bytes;
  EXPECT_EQ(pieces.stats.facets_in_file, whole.stats.facets_in_file) << piece_bytes;
  EXPECT_EQ(pieces.stats.facets_read, whole.stats.facets_read) << piece_bytes;
  EXPECT_EQ(pieces.stats.facets_degenerate, whole.stats.facets_degenerate) << piece_bytes;
  EXPECT_EQ(pieces.stats.polygons_triangulated, whole.stats.polygons_triangulated) << piece_bytes;
  EXPECT_EQ(pieces.stats.format, whole.stats.format) << piece_bytes;
}

// The ReadError message of read(), or "" when it reads.
template <class Read>
std::string read_error_of(Read&& read) {
  try {
    read();
  } catch (const ReadError& e) {
    return e.what();
  }
  return "";
}

}  // namespace ncpath::io::testing
