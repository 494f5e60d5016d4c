// jemalloc's options for the executables linked with it (CMake option
// IGABDE_JEMALLOC, on by default): compiled into each such executable, not
// into igabde_lib, since jemalloc reads them from the program's own
// `malloc_conf` when it starts.
//
// thp:always asks the kernel for transparent huge pages (2 MiB) for every
// large extent: the dense contact blocks and the set-up touch hundreds of
// MiB once, and with 4 KiB pages a third of the B2 8x16x8 run went to page
// faults (doc/performance.md). The sparse factorisations are the
// exception: MUMPS touches its workspace front by front, and zeroing it in
// 2 MiB pages cost more than it saved, so they run with the process's huge
// pages off (base::WithoutHugePages). The kernel's own setting still
// decides ('never' turns it off); MALLOC_CONF in the environment overrides
// these options (e.g. MALLOC_CONF=thp:default).

extern "C" {
// NOLINTNEXTLINE: the name and type are jemalloc's interface.
extern const char *malloc_conf;
const char        *malloc_conf = "thp:always,metadata_thp:auto";
}
