# tests/tools/check_test_mirror_test.cmake: the mirror check (tools/check_test_mirror.cmake) fails
# on trees that break the rule, naming each offender, and passes once they are mended. The trees
# are written here, under a scratch directory: a source with neither a mirrored test nor a row, a
# row for a source that does not exist, one for a source that has its test, one naming a tests/
# path that does not exist, one without its reason; a build tree, bench/ and fuzz/ are not looked at.
#
#   cmake -DWORK=<scratch directory> -P tests/tools/check_test_mirror_test.cmake
cmake_minimum_required(VERSION 3.25)
get_filename_component(source "${CMAKE_CURRENT_LIST_DIR}/../.." ABSOLUTE)
set(check "${source}/tools/check_test_mirror.cmake")
if(NOT WORK)
  message(FATAL_ERROR "check_test_mirror_test: give a scratch directory, -DWORK=...")
endif()

# Runs the check on WORK: its exit code in <prefix>_rc, what it printed in <prefix>_out.
function(run_check prefix)
  execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK} -P ${check} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE out)
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
endfunction()

# Requires the check to fail on WORK, printing each of ARGN; what it printed in r_out.
function(expect_failure what)
  run_check(r)
  set(r_out "${r_out}" PARENT_SCOPE)
  if(r_rc EQUAL 0)
    message(FATAL_ERROR "check_test_mirror_test: the check passed ${what}:\n${r_out}")
  endif()
  foreach(line IN LISTS ARGN)
    string(FIND "${r_out}" "${line}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "check_test_mirror_test: on ${what} the check did not report\n  ${line}\nIt printed:\n${r_out}")
    endif()
  endforeach()
endfunction()

set(header "| source file | where it is tested | why not beside it |\n|---|---|---|\n")
file(REMOVE_RECURSE "${WORK}")
file(WRITE "${WORK}/lib/a.cpp" "")
file(WRITE "${WORK}/lib/sub/b.cpp" "")
file(WRITE "${WORK}/lib/c.cpp" "")
file(WRITE "${WORK}/lib/d.cpp" "")
file(WRITE "${WORK}/lib/e.cpp" "")
file(WRITE "${WORK}/tests/lib/a_test.cpp" "")
file(WRITE "${WORK}/tests/lib/sub/b_test.cpp" "")
file(WRITE "${WORK}/tests/lib/whole_test.cpp" "")
file(WRITE "${WORK}/tests/helper.cpp" "")                 # tests/ is not mirrored
file(WRITE "${WORK}/bench/x.cpp" "")                      # nor bench/
file(WRITE "${WORK}/fuzz/y.cpp" "")                       # nor fuzz/
file(WRITE "${WORK}/build/CMakeCache.txt" "")             # nor a build tree
file(WRITE "${WORK}/build/CMakeFiles/id.cpp" "")
file(WRITE "${WORK}/tests/README.md" "${header}| `lib/c.cpp` | tests/lib/whole_test.cpp | driven whole |\n")

expect_failure("a source with neither a test nor a row"
               "lib/d.cpp: no test tests/lib/d_test.cpp, and no row in tests/README.md"
               "lib/e.cpp: no test tests/lib/e_test.cpp, and no row in tests/README.md")
string(REGEX MATCHALL "[^\n]*: no test " reported "${r_out}")
list(LENGTH reported count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "check_test_mirror_test: the check reported ${count} sources, not lib/d.cpp and lib/e.cpp:\n"
                      "${r_out}")
endif()

file(WRITE "${WORK}/tests/README.md"
     "${header}| `lib/c.cpp` | tests/lib/whole_test.cpp | driven whole |\n"
     "| lib/d.cpp | tests/lib/gone_test.cpp; tests/lib/ | driven whole |\n"
     "| `lib/e.cpp` | tests/lib/whole_test.cpp |  |\n"
     "| `lib/a.cpp` | tests/lib/whole_test.cpp | has its own now |\n"
     "| `lib/old.cpp` | tests/lib/whole_test.cpp | removed since |\n"
     "| `tests/helper.cpp` | tests/lib/whole_test.cpp | not a source |\n"
     "| `lib/c.cpp` | tests/lib/whole_test.cpp | twice |\n")
expect_failure("a table with rows that are not honest"
               "tests/README.md:4: lib/d.cpp: names tests/lib/gone_test.cpp, which does not exist"
               "tests/README.md:5: lib/e.cpp: the row must say where it is tested and why not beside it"
               "tests/README.md:6: lib/a.cpp: has its mirrored test tests/lib/a_test.cpp (remove its row)"
               "tests/README.md:7: lib/old.cpp: no such source file (remove its row)"
               "tests/README.md:8: tests/helper.cpp: not a source the rule covers"
               "tests/README.md:9: lib/c.cpp: listed twice")
string(FIND "${r_out}" "no test tests/lib/" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "check_test_mirror_test: every source is listed or mirrored, yet:\n${r_out}")
endif()

file(WRITE "${WORK}/tests/README.md"
     "${header}| `lib/c.cpp` | tests/lib/whole_test.cpp | driven whole |\n"
     "| lib/d.cpp | tests/lib/whole_test.cpp; tests/lib/ | driven whole |\n"
     "| `lib/e.cpp` | tests/lib/whole_test.cpp | driven whole |\n")
run_check(mended)
if(NOT mended_rc EQUAL 0)
  message(FATAL_ERROR "check_test_mirror_test: the check failed a tree that keeps the rule:\n${mended_out}")
endif()
string(FIND "${mended_out}" "5 sources, 2 with their mirrored test, 3 listed in tests/README.md" at)
if(at EQUAL -1)
  message(FATAL_ERROR "check_test_mirror_test: the check counted otherwise:\n${mended_out}")
endif()
message("check_test_mirror_test: every way of breaking the rule reported, none once mended")
