# Fails when a Catch2 test name holds a ';' (run by CTest once per test executable).
# catch_discover_tests reads the names as a CMake list, so a ';' cuts one name in two: each
# half matches no test case and the test "passes" in 0.00 s having run nothing.
#   cmake -DEXE=<test executable> -P check_test_names.cmake
execute_process(COMMAND "${EXE}" --list-test-names-only OUTPUT_VARIABLE names RESULT_VARIABLE listed)
if(listed LESS 0)
  message(FATAL_ERROR "cannot list the tests of ${EXE}")
endif()
string(FIND "${names}" ";" semicolon)
if(NOT semicolon EQUAL -1)
  # Quote the line that holds it.
  string(SUBSTRING "${names}" 0 ${semicolon} before)
  string(FIND "${before}" "\n" line_start REVERSE)
  math(EXPR line_start "${line_start} + 1")
  string(SUBSTRING "${names}" ${line_start} -1 rest)
  string(FIND "${rest}" "\n" line_end)
  string(SUBSTRING "${rest}" 0 ${line_end} line)
  string(REPLACE ";" "<;>" line "${line}")
  message(FATAL_ERROR "test name holds a ';', which CTest cuts (the test would run nothing): ${line}")
endif()
