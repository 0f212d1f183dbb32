#include "batch/cli/huge_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace ncpath::cli {

void reexec_with_huge_pages(char** argv) {
  if (std::getenv("NCPATH_HUGE_PAGES") != nullptr) return;
  const char* old = std::getenv("GLIBC_TUNABLES");
  std::string tunables = old != nullptr ? old : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;
  tunables += (tunables.empty() ? "" : ":") + std::string("glibc.malloc.hugetlb=1");
  if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
  if (setenv("NCPATH_HUGE_PAGES", "1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the re-execution failed. Run as we are (the tunable only matters at start-up).
}

}  // namespace ncpath::cli
