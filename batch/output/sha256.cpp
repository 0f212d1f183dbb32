#include "batch/output/sha256.hpp"

#include <openssl/evp.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ncpath::out {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const char* what, int err) {
  std::string msg = "sha256_file: cannot " + std::string(what) + " '" + path.string() + "'";
  if (err != 0) msg += ": " + std::string(std::strerror(err));
  throw std::runtime_error(msg);
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
struct MdCtxFree {
  void operator()(EVP_MD_CTX* c) const { EVP_MD_CTX_free(c); }
};

}  // namespace

std::string sha256_file(const std::filesystem::path& path) {
  // A directory opens fine with fopen on Linux and only fails at read; say so clearly.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "hash a directory", 0);

  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) fail(path, "open", errno);

  std::unique_ptr<EVP_MD_CTX, MdCtxFree> ctx(EVP_MD_CTX_new());
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    fail(path, "initialise OpenSSL SHA-256 for", 0);
  }
  std::vector<unsigned char> block(std::size_t{1} << 20);
  for (;;) {
    const std::size_t got = std::fread(block.data(), 1, block.size(), file.get());
    if (got > 0 && EVP_DigestUpdate(ctx.get(), block.data(), got) != 1) {
      fail(path, "hash", 0);
    }
    if (got < block.size()) {
      if (std::ferror(file.get())) fail(path, "read", errno);
      break;  // end of file
    }
  }
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int len = 0;
  if (EVP_DigestFinal_ex(ctx.get(), digest.data(), &len) != 1) fail(path, "hash", 0);

  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * len);
  for (unsigned int i = 0; i < len; ++i) {
    hex.push_back(kHex[digest[i] >> 4]);
    hex.push_back(kHex[digest[i] & 0xF]);
  }
  return hex;
}

}  // namespace ncpath::out
