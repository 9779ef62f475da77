# tools/check_test_mirror.cmake: the tests mirror the sources. Every C++ source (*.cpp) outside
# tests/, bench/ and fuzz/ has its test beside it in the mirrored tree, tests/<path>_test.cpp
# (vm/numbers/affine.cpp: tests/vm/numbers/affine_test.cpp), or a row in the table of
# tests/README.md saying where it is tested and why not there:
#
#   | `tools/main.cpp` | tests/tools/cli_test.cpp, the golden tests | thin entry point |
#
# The table is kept honest too: a row must name a source that exists and has no mirrored test,
# once, with both other columns filled in, and every tests/... path a row names must exist.
# It fails listing every offender.
#
#   cmake -DROOT=<source tree> -P tools/check_test_mirror.cmake
#
# ROOT defaults to the tree this script is in. CTest runs it on the source tree and on small trees
# that break the rule each way (tests/tools/check_test_mirror_test.cmake), to check that it fails.

cmake_minimum_required(VERSION 3.25)

# Top-level folders whose sources are not mirrored: the tests themselves, the benchmarks and the
# fuzz targets (each a driver of code the tests cover).
set(AFFRAY_UNMIRRORED tests bench fuzz)

if(NOT ROOT)
  get_filename_component(ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
endif()
get_filename_component(ROOT "${ROOT}" ABSOLUTE)
set(table "${ROOT}/tests/README.md")

# The sources: *.cpp under every top-level folder but those above, hidden ones and build trees
# (a folder holding a CMakeCache.txt, such as build/), and at the top itself.
file(GLOB sources RELATIVE "${ROOT}" "${ROOT}/*.cpp")
file(GLOB tops RELATIVE "${ROOT}" "${ROOT}/*")
foreach(top IN LISTS tops)
  if(NOT IS_DIRECTORY "${ROOT}/${top}" OR top IN_LIST AFFRAY_UNMIRRORED OR top MATCHES "^\\."
     OR EXISTS "${ROOT}/${top}/CMakeCache.txt")
    continue()
  endif()
  file(GLOB_RECURSE found RELATIVE "${ROOT}" "${ROOT}/${top}/*.cpp")
  list(APPEND sources ${found})
endforeach()
list(SORT sources)

# The table's rows: "| source | where | why |" with the source ending in .cpp (in backquotes or
# not); the header and separator rows name no .cpp file.
set(listed "")
set(problems "")
set(lines "")
if(EXISTS "${table}")
  # One list element per line: the characters a CMake list gives a meaning to are replaced first.
  file(READ "${table}" text)
  string(REPLACE ";" "," text "${text}")
  string(REPLACE "[" "(" text "${text}")
  string(REPLACE "]" ")" text "${text}")
  string(REPLACE "\\" "/" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
endif()
set(number 0)
foreach(line IN LISTS lines)
  math(EXPR number "${number} + 1")
  if(NOT line MATCHES "^[ \t]*\\|[ \t]*`?([^|` \t]+\\.cpp)`?[ \t]*\\|([^|]*)\\|([^|]*)\\|[ \t]*$")
    continue()
  endif()
  set(file "${CMAKE_MATCH_1}")
  set(where "${CMAKE_MATCH_2}")
  set(why "${CMAKE_MATCH_3}")
  set(at "tests/README.md:${number}: ${file}")
  if(file IN_LIST listed)
    list(APPEND problems "${at}: listed twice")
  endif()
  list(APPEND listed "${file}")
  if(NOT file IN_LIST sources)
    if(EXISTS "${ROOT}/${file}")
      list(APPEND problems "${at}: not a source the rule covers (tests/, bench/ and fuzz/ are not mirrored)")
    else()
      list(APPEND problems "${at}: no such source file (remove its row)")
    endif()
  else()
    string(REGEX REPLACE "\\.cpp$" "_test.cpp" mirror "tests/${file}")
    if(EXISTS "${ROOT}/${mirror}")
      list(APPEND problems "${at}: has its mirrored test ${mirror} (remove its row)")
    endif()
  endif()
  if(where MATCHES "^[ \t]*$" OR why MATCHES "^[ \t]*$")
    list(APPEND problems "${at}: the row must say where it is tested and why not beside it")
  endif()
  string(REGEX MATCHALL "tests/[A-Za-z0-9_./-]*[A-Za-z0-9_/]" named "${where}")
  foreach(path IN LISTS named)
    if(NOT EXISTS "${ROOT}/${path}")
      list(APPEND problems "${at}: names ${path}, which does not exist")
    endif()
  endforeach()
endforeach()

set(mirrored 0)
foreach(file IN LISTS sources)
  string(REGEX REPLACE "\\.cpp$" "_test.cpp" mirror "tests/${file}")
  if(EXISTS "${ROOT}/${mirror}")
    math(EXPR mirrored "${mirrored} + 1")
  elseif(NOT file IN_LIST listed)
    list(APPEND problems "${file}: no test ${mirror}, and no row in tests/README.md saying where it is tested")
  endif()
endforeach()

list(LENGTH sources total)
list(LENGTH listed rows)
if(problems)
  list(LENGTH problems count)
  string(REPLACE ";" "\n" text "${problems}")
  message("${text}")
  message(FATAL_ERROR "check_test_mirror: ${count} problem(s); every source needs tests/<path>_test.cpp or a row "
                      "in tests/README.md, and every row a source without one (see tools/check_test_mirror.cmake)")
endif()
message("check_test_mirror: ${total} sources, ${mirrored} with their mirrored test, ${rows} listed in tests/README.md")
