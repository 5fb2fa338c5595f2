# -DVKCOLLIDE_SANITIZE=<list> builds every target of this project with -fsanitize=<list>
# (e.g. address,undefined: the sanitizer jobs of tools/test.sh), with GCC or clang. Any
# report stops the program (-fno-sanitize-recover=all), so the test fails.
#
# Every executable also links tools/sanitize/sanitizer_runtime.c: the sanitizers' default
# options (leak suppressions: tools/sanitize/lsan.supp) and a dlclose() that keeps the
# Vulkan driver and the validation layer loaded until exit (that file says why), so a
# plain `ctest` in the build folder, the command-line tool and the fuzz targets need no
# environment. vkcollide_sanitize_executables() (called at the end of the top-level
# CMakeLists.txt, when every target exists) links it.
# Configure with -DVKCOLLIDE_INSTALL=OFF: the package tests build a consumer without the
# sanitizers, which cannot link a sanitized static library.
set(VKCOLLIDE_SANITIZE "" CACHE STRING "Build everything with -fsanitize=<this list>, e.g. address,undefined")
# -DVKCOLLIDE_FUZZ=ON (clang): every target also gets libFuzzer's coverage instrumentation
# and tools/fuzz builds its libFuzzer binaries (tools/fuzz/run_fuzz.sh sets this up).
option(VKCOLLIDE_FUZZ "Build the libFuzzer targets of tools/fuzz (clang)" OFF)
if(VKCOLLIDE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "VKCOLLIDE_FUZZ needs clang (libFuzzer); this is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
if(VKCOLLIDE_SANITIZE)
  set(vkcollide_san_flags -fsanitize=${VKCOLLIDE_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_compile_options(${vkcollide_san_flags})
  add_link_options(${vkcollide_san_flags})
  # Not instrumented itself (no options from the folder): it only answers the runtimes.
  add_library(vkcollide_sanitizer_runtime OBJECT ${PROJECT_SOURCE_DIR}/tools/sanitize/sanitizer_runtime.c)
  set_target_properties(vkcollide_sanitizer_runtime PROPERTIES COMPILE_OPTIONS "")
  target_compile_definitions(vkcollide_sanitizer_runtime PRIVATE
    VKCOLLIDE_LSAN_SUPPRESSIONS="${PROJECT_SOURCE_DIR}/tools/sanitize/lsan.supp")
endif()

# Links the runtime above into every executable under `dir` (recursively; cmake/Targets.cmake).
function(vkcollide_sanitize_executables dir)
  if(NOT VKCOLLIDE_SANITIZE)
    return()
  endif()
  vkcollide_targets_under(${dir} targets)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      target_link_libraries(${target} PRIVATE vkcollide_sanitizer_runtime)
      target_link_options(${target} PRIVATE -Wl,--export-dynamic-symbol=dlclose)
    endif()
  endforeach()
endfunction()
