# Fails on a Catch2 test name that would hide its own failure (run by CTest once per test
# executable):
# - a ';': catch_discover_tests reads the names as a CMake list, so a ';' cuts one name in
#   two; each half matches no test case and the test "passes" in 0.00 s having run nothing.
# - a ": " at column 77 or later: Catch2's console reporter indents a failing test's wrapped
#   name past its first ": ", and where that indent reaches the 79-column width it aborts on
#   an assertion (TextFlow: m_width > m_indent) before printing what failed.
#   cmake -DEXE=<test executable> -P check_test_names.cmake
execute_process(COMMAND "${EXE}" --list-test-names-only OUTPUT_VARIABLE names RESULT_VARIABLE listed)
if(listed LESS 0)
  message(FATAL_ERROR "cannot list the tests of ${EXE}")
endif()
set(console_width 79)  # Catch2's CATCH_CONFIG_CONSOLE_WIDTH (80) less one
# One name per line, walked with string operations only (list operations would split at
# the ';' this looks for, and a '[' binds list items).
set(rest "${names}")
while(NOT rest STREQUAL "")
  string(FIND "${rest}" "\n" line_end)
  if(line_end EQUAL -1)
    set(line "${rest}")
    set(rest "")
  else()
    string(SUBSTRING "${rest}" 0 ${line_end} line)
    math(EXPR next "${line_end} + 1")
    string(SUBSTRING "${rest}" ${next} -1 rest)
  endif()
  string(FIND "${line}" ";" semicolon)
  if(NOT semicolon EQUAL -1)
    string(REPLACE ";" "<;>" line "${line}")
    message(FATAL_ERROR "test name holds a ';', which CTest cuts (the test would run nothing): ${line}")
  endif()
  string(FIND "${line}" ": " colon)
  if(NOT colon EQUAL -1)
    math(EXPR indent "${colon} + 2")
    if(NOT indent LESS console_width)
      message(FATAL_ERROR "test name's first \": \" is at column ${colon}: Catch2's console reporter "
                          "would abort instead of reporting its failure (move it before column 77): ${line}")
    endif()
  endif()
endwhile()
