// Linked into every executable of a -DVKCOLLIDE_SANITIZE build (cmake/Sanitizers.cmake), so
// that a plain `ctest`, the command-line tool and the fuzz targets run the way CI runs them,
// with no environment to set. Not in any other build.

// The sanitizers' defaults (ASAN_OPTIONS, LSAN_OPTIONS and UBSAN_OPTIONS still override
// them). Leaks are checked at exit, with tools/sanitize/lsan.supp for what the Vulkan driver
// and the validation layer leak themselves (each entry says why). Shadow memory is cleared
// in place, however large the range (clear_shadow_mmap_threshold): remapped, every large free
// and thread exit cost an mmap, a TLB flush on every core and fresh page faults later, dear on
// a VM; no MADV_DONTDUMP per mapping (no core files here). Both leave what ASan checks as it
// was; the sanitized suite's time on two cores went from 200 to 184 s (docs/stability.md).
const char* __asan_default_options(void) {
    return "detect_leaks=1:abort_on_error=1:clear_shadow_mmap_threshold=1073741824:use_madv_dontdump=0";
}
const char* __lsan_default_options(void) { return "suppressions=" VKCOLLIDE_LSAN_SUPPRESSIONS ":print_suppressions=0"; }
const char* __ubsan_default_options(void) { return "print_stacktrace=1"; }

// dlclose() that keeps the library loaded. The Vulkan loader dlopen()s the driver
// (lavapipe), its LLVM and the validation layer, and dlclose()s them at vkDestroyInstance,
// before LeakSanitizer looks at the heap at exit. Memory those libraries keep in their
// own globals then looks leaked (their data is gone, so nothing points at it), with every
// frame of its allocation stack in "<unknown module>", which no suppression can name.
// Kept loaded, their globals are roots again and what they really leak names its library.
// (Preloading them instead fails for the validation layer: its exported vkCreateInstance
// and friends would interpose the loader's.) Linked with --export-dynamic-symbol=dlclose so
// that the loader's calls resolve here.
int dlclose(void* handle) {
    (void)handle;
    return 0;
}
