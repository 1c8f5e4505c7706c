// The `globalvis` executable's memory allocator: jemalloc (CMakeLists.txt links it outside the
// sanitizer builds, whose own allocator checks every access), backed by transparent huge pages.
//
// Why: the radiosity solver builds and drops tens of megabytes of links, taps and elements every
// refinement round. Under glibc's malloc each round's big vectors came back as fresh pages from
// the kernel, and the page faults ran on the thread that merges the round's results: 7 % of the
// default office's samples, nearly all on that one thread, which held the second core back
// (1.4x). With huge pages the faults and the TLB misses drop (office radiosity 2.3-2.8 s -> 1.8 s
// at 2 threads, 10k office 26.5 -> 21.0 s and 765 -> 645 MB; docs/BENCHMARKS.md, session 31).
// `vis` is unchanged by it (retrojam1 within noise).
#ifdef GV_USE_JEMALLOC
extern "C" {
// jemalloc reads this string at its first allocation: its documented way for a program to set
// its own defaults (the MALLOC_CONF environment variable still overrides them).
// NOLINTNEXTLINE(cppcoreguidelines-avoid-non-const-global-variables)
const char* malloc_conf = "thp:always,metadata_thp:auto";
}
#endif
