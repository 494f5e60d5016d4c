// jemalloc's options for the executables linked with it (CMake option
// IGABDE_JEMALLOC, on by default): compiled into each such executable, not
// into igabde_lib, since jemalloc reads them from the program's own
// `malloc_conf` when it starts.
//
// thp:always asks the kernel for transparent huge pages (2 MiB) for every
// large extent: the sparse factorisation and the dense contact blocks touch
// hundreds of MiB once, and with 4 KiB pages much of the B2 8x16x8 run
// went to page faults (doc/performance.md). The kernel's own setting still
// decides ('never' turns it off); MALLOC_CONF in the environment overrides
// these options (e.g. MALLOC_CONF=thp:default).

extern "C" {
// NOLINTNEXTLINE: the name and type are jemalloc's interface.
extern const char *malloc_conf;
const char        *malloc_conf = "thp:always,metadata_thp:auto";
}
