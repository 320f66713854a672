// Sanitizer defaults for programs that create OpenGL contexts (compiled in only with
// LODLINE_SANITIZE). Mesa's dlopen'ed driver keeps allocations that LeakSanitizer reports
// from an unloaded ("unknown") module, which no suppression can name, so leak checking is
// off in these programs; address and UB checks stay on, and every GL-free test suite keeps
// leak checking. ASAN_OPTIONS in the environment still override these defaults.
extern "C" const char* __asan_default_options() { return "detect_leaks=0:detect_odr_violation=0"; }
