# tests/tools/check_layers_test.cmake: the layering check (tools/check_layers.cmake) fails on a tree
# that breaks the layers, naming every include that crosses them (file, line, include) and no
# other, and passes on the same tree once those includes are taken out.
#
#   cmake -DWORK=<scratch directory> -P tests/tools/check_layers_test.cmake
#
# The tree is tests/tools/check_layers/: one small file in each library folder (nothing there is
# compiled). The includes that cross the layers end in "// crosses the layers".
cmake_minimum_required(VERSION 3.25)
get_filename_component(source "${CMAKE_CURRENT_LIST_DIR}/../.." ABSOLUTE)
set(tree "${source}/tests/tools/check_layers")
set(check "${source}/tools/check_layers.cmake")
if(NOT WORK)
  message(FATAL_ERROR "check_layers_test: give a scratch directory, -DWORK=...")
endif()

# Runs the check on `root`: its exit code in <prefix>_rc, what it printed in <prefix>_out.
function(run_check root prefix)
  execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${root} -P ${check} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE out)
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
endfunction()

set(expected
    "vm/numbers/interval.h:6: #include \"vm/program.h\": vm/numbers/ may include only vm/numbers/"
    "image/exr_writer.cpp:5: #include \"../texture/texture.h\": climbs out of its folder"
    "texture/texture_file.cpp:8: #include \"scene/scene.h\": texture/ may include only diag/, image/, texture/"
    "lang/parser.y:6: #include \"texture/texture.h\": lang/ may include only diag/, lang/"
    "compiler/compile.cpp:6: #include \"renderer/render.h\": compiler/ may include only "
    "scene/geometry/surface.h:6: #include \"fuzz/fuzz_util.h\": scene/ may include only "
    "rib/rib.cpp:5: #include \"renderer/render.h\": rib/ may include only ")

run_check("${tree}" broken)
if(broken_rc EQUAL 0)
  message(FATAL_ERROR "check_layers_test: the check passed a tree that breaks the layers:\n${broken_out}")
endif()
foreach(line IN LISTS expected)
  string(FIND "${broken_out}" "${line}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "check_layers_test: the check did not report\n  ${line}\nIt printed:\n${broken_out}")
  endif()
endforeach()
string(REGEX MATCHALL "[^\n]*: #include \"[^\"\n]*\": " reported "${broken_out}")
list(LENGTH reported count)
list(LENGTH expected want)
if(NOT count EQUAL want)
  message(FATAL_ERROR "check_layers_test: the check reported ${count} includes, not the ${want} that cross the "
                      "layers:\n${broken_out}")
endif()

# The same tree without the includes that cross the layers: every other include is allowed.
file(REMOVE_RECURSE "${WORK}")
file(GLOB_RECURSE files RELATIVE "${tree}" "${tree}/*")
foreach(file IN LISTS files)
  file(READ "${tree}/${file}" text)
  string(REGEX REPLACE "[^\n]*// crosses the layers\n" "" text "${text}")
  file(WRITE "${WORK}/${file}" "${text}")
endforeach()
run_check("${WORK}" sound)
if(NOT sound_rc EQUAL 0)
  message(FATAL_ERROR "check_layers_test: the check failed a tree within the layers:\n${sound_out}")
endif()
message("check_layers_test: ${want} includes across the layers reported, none once they are taken out")
