// The sanitizer build's defaults (WAVEPATH_SANITIZE, docs/bad-input.md),
// compiled into every executable so that the tests, the wavepath binary they
// run and the fuzzers behave alike however they are started. The runtimes
// call these functions at start-up; environment variables still override.

// UndefinedBehaviorSanitizer's findings with their stacks (they are fatal:
// -fno-sanitize-recover=all).
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1"; }

// LeakSanitizer's tracer could crash at exit ("Tracer caught signal 11",
// exit 1, no leak named) when a dynamic TLS block, which PoCL's kernel
// libraries and LLVM allocate, happens to start 16 bytes past a page: up to
// LLVM 16 the __tls_get_addr interceptor takes such a block for one with a
// glibc 2.19 header and reads two words before it as a range (fixed in later
// runtimes). Not intercepting __tls_get_addr only leaves those blocks out of
// the leak scan's roots, and the pointers they hold are the libraries' own,
// which the suppressions below already name.
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }

// LeakSanitizer's table of the suppressions it used would follow a
// successful render's summary on stderr, which the tests read.
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }

// Leaks whose allocation stacks run through these libraries, none of them
// ours. The OpenCL ICD loader, PoCL and the LLVM that PoCL loads to compile
// kernels keep allocations for the life of the process (platform and device
// lists, compiled programs, LLVM's global state) and free none of them at
// exit. assimp 5.2.5 (Debian 12) leaks the meshes it has built when an
// importer throws, e.g. the OBJ reader's "vertex index out of range" (found
// by fuzz_mesh; the corpus case mesh_index_out_of_range_obj.json shows it).
// A leak allocated by our code with none of these on its stack is reported.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOpenCL.so\n"
           "leak:libpocl.so\n"
           "leak:libLLVM\n"
           "leak:libassimp.so\n";
}
