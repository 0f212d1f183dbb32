#pragma once
// Large arrays on transparent huge pages, for the command-line programs.
//
// Mesh preparation writes gigabytes of fresh memory (offset elements, indexes); on the
// virtual machines users rent, each 4 KiB page fault is costly, and glibc's malloc asks the
// kernel for huge pages (madvise MADV_HUGEPAGE) only when the tunable glibc.malloc.hugetlb=1
// is set, which it reads from GLIBC_TUNABLES at start-up. So the program adds it and
// re-executes itself once, before doing anything else. Measured on this project's machine
// (docs/performance.md, "Huge pages"): scan of one family on the 4.8 M-facet scan 31.8 ->
// 15.9 s, pencil on the 1.2 M-facet scan 46.3 -> 36.6 s, same output bytes.
//
// Left alone when NCPATH_HUGE_PAGES is set (0 turns it off; the re-executed process sees 1),
// when GLIBC_TUNABLES already names glibc.malloc.hugetlb (the user's own choice), or when
// the re-execution fails (the program then runs as it is). Where the kernel's transparent
// huge pages are "never", the tunable changes nothing.
namespace ncpath::cli {

// Call first in main(). Returns only when the process is not re-executed.
void reexec_with_huge_pages(char** argv);

}  // namespace ncpath::cli
