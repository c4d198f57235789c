// Transparent huge pages for a tool's heap. glibc's malloc asks the kernel for them only
// when the GLIBC_TUNABLES variable holds glibc.malloc.hugetlb=1, and it reads that variable
// only as the program starts. The tools touch gigabytes of fresh memory on large scenes, and
// a 4 KiB page fault is dear (on this project's VMs): rad-mesh on 5e6 triangles takes 76 s
// with them and 47 s with 2 MiB pages, rad-solve's 1e5-patch PR 5.2 s and 2.1-3.3 s,
// rad-ff 14% less; the same bytes out. rad-mesh, rad-ff, rad-solve, rad-shade and
// rad-gather restart themselves once with it.
#pragma once
#include <string>

namespace rad {

// Restarts the running program (/proc/self/exe, the same arguments) with
// glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES, unless the kernel has transparent huge
// pages off, GLIBC_TUNABLES already sets glibc.malloc.hugetlb, or RADIOSITY_HUGE_PAGES=0.
// Nor when the process image is not the program argv[0] names (run as `ld.so TOOL` or under
// valgrind: exec'ing /proc/self/exe would run the loader or the tool with the tool's
// arguments); huge_pages_state() then says so. Returns (and the program goes on as it is)
// when it does not restart or the restart fails.
void restart_with_huge_pages(char** argv);

// One line for --timings: whether huge pages were asked for, and how much of the heap is in
// them now (AnonHugePages of /proc/self/smaps_rollup).
std::string huge_pages_state();

} // namespace rad
