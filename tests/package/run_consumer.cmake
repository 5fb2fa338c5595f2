# Builds tests/package/consumer against an installed vkcollide and runs it, then runs the
# installed command-line tool.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... [-DBUILD_DIR=...] [-DSHARED=ON] -P run_consumer.cmake
# BUILD_DIR: install that (already built) build tree.
# SHARED=ON: first configure and build vkcollide itself with -DBUILD_SHARED_LIBS=ON in
#            SHARED_BUILD_DIR (default WORK_DIR/vkcollide; emptied first; library and CLI
#            only), and install that: a shared libvkcollide.
# The consumer is configured with Eigen3 made unfindable: consumers must not need it.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(expect STATIC_LIBRARY)

# Runs one command given as a list; stops the script when it fails.
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}")
  endif()
endfunction()

if(SHARED)
  set(expect SHARED_LIBRARY)
  if(NOT SHARED_BUILD_DIR)
    set(SHARED_BUILD_DIR ${WORK_DIR}/vkcollide)
  endif()
  file(REMOVE_RECURSE ${SHARED_BUILD_DIR})
  set(BUILD_DIR ${SHARED_BUILD_DIR})
  # UNITY and TOOL_OPTIONS: the unity settings and VKCOLLIDE_TOOL_COMPILE_OPTIONS of the build
  # running this test, so that a compiler cache given to both finds the same batches.
  step(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR} -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON ${UNITY}
       "-DVKCOLLIDE_TOOL_COMPILE_OPTIONS=${TOOL_OPTIONS}"
       -DVKCOLLIDE_BUILD_TESTS=OFF -DVKCOLLIDE_BUILD_SAMPLES=OFF -DVKCOLLIDE_BUILD_TOOLS=ON -DVKCOLLIDE_INSTALL=ON
       -DVKCOLLIDE_WERROR=ON)
  step(${CMAKE_COMMAND} --build ${BUILD_DIR} --target vkcollide vkcollide_cli)
endif()
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/consumer -B ${WORK_DIR}/build -G Ninja -DCMAKE_PREFIX_PATH=${prefix}
     -DCMAKE_BUILD_TYPE=Release -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=TRUE -DEXPECT_LIBRARY_TYPE=${expect} --no-warn-unused-cli)
step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step(${WORK_DIR}/build/consumer)
if(SHARED)
  file(GLOB shared_lib ${prefix}/lib*/libvkcollide.so*)
  if(NOT shared_lib)
    message(FATAL_ERROR "no libvkcollide.so installed under ${prefix}")
  endif()
  # The installed library exports the public API only (include/vkcollide/export.hpp): no
  # symbol of an internal namespace (vkcollide::passes::, vkcollide::vk::, ...: a lower-case
  # name after vkcollide::), and nothing outside vkcollide but the standard library's
  # template instantiations that the API's types need.
  list(GET shared_lib 0 lib)
  execute_process(COMMAND nm -D --defined-only -C ${lib} RESULT_VARIABLE rc OUTPUT_VARIABLE symbols ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "nm -D ${lib} failed: ${err}")
  endif()
  string(REPLACE "\n" ";" symbols "${symbols}")
  set(exported 0)
  set(internal "")
  foreach(line IN LISTS symbols)
    # "<address> <type> <name>"; the name's own scope is what precedes its first '(' or '<'.
    if(NOT line MATCHES "^[0-9a-f]+ [A-Za-z] (.*)$")
      continue()
    endif()
    set(name "${CMAKE_MATCH_1}")
    string(REGEX REPLACE "^(typeinfo name for|typeinfo for|vtable for|VTT for|guard variable for) " "" scope "${name}")
    string(REGEX REPLACE "[(<].*$" "" scope "${scope}")
    if(scope MATCHES "^vkcollide::")
      math(EXPR exported "${exported} + 1")
      if(scope MATCHES "^vkcollide::[a-z_0-9]+::")
        list(APPEND internal "${name}")
      endif()
    elseif(NOT scope MATCHES "^(std|__gnu_cxx)::")
      list(APPEND internal "${name}")
    endif()
  endforeach()
  list(LENGTH internal n_internal)
  if(n_internal GREATER 0)
    list(JOIN internal "\n  " shown)
    message(FATAL_ERROR "${lib} exports ${n_internal} symbols outside the public API:\n  ${shown}")
  endif()
  if(exported LESS 50)
    message(FATAL_ERROR "${lib} exports only ${exported} vkcollide symbols: the public API is missing")
  endif()
  message("${lib}: ${exported} vkcollide symbols exported, none internal")
endif()
# The installed tool (built unless VKCOLLIDE_BUILD_TOOLS is off) runs from the prefix.
if(EXISTS ${prefix}/bin/vkcollide)
  step(${prefix}/bin/vkcollide detect --help)
  step(${prefix}/bin/vkcollide info)
elseif(SHARED)
  message(FATAL_ERROR "the command-line tool was not installed to ${prefix}/bin")
endif()
