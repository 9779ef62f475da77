// tools/sanitizer_options.cpp: the sanitizer runtime's default options, linked into every
// executable of a sanitizer or fuzz build (CMakeLists.txt). $ASAN_OPTIONS still overrides them.
//
// intercept_tls_get_addr=0: clang-14's LeakSanitizer, on Debian 12's glibc 2.36, records a
// dynamic TLS block of a dlopen'ed library with a garbage range once the image-file module
// (OpenImageIO and its 260 libraries) is loaded, and its leak check at exit then crashes
// ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error") although the
// program passed. Without the interception the dynamic TLS blocks are not scanned as roots;
// they stay heap blocks reachable from the thread's vector of TLS blocks, so leak checking is
// otherwise unchanged.

extern "C" const char* __asan_default_options();

extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }
