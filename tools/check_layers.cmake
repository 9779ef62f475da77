# tools/check_layers.cmake: the layering check. Every library folder may include (#include "folder/...")
# only itself and the folders it links, as CMake does: directly or through them. Every library
# puts the source root on the include path, so an include that crosses the layers would compile;
# this script is what refuses it. It fails naming each file, line and include that breaks the
# table below, and an include that climbs out of its folder ("../").
#
#   cmake -DROOT=<source tree> -P tools/check_layers.cmake
#
# ROOT defaults to the tree this script is in. CTest runs it on the source tree and on a small
# tree that breaks the layers (tests/tools/check_layers_test.cmake), to check that it fails there.

cmake_minimum_required(VERSION 3.25)

# The library folders, lowest first, each with the folders it links (its target_link_libraries):
# it may include those and whatever they may include. A folder may only link folders listed before
# it, so the layers have no cycle. A subfolder that is a library of its own (vm/numbers) is a layer
# of its own: its files are its, not its parent's.
set(AFFRAY_LAYERS
    "diag:"                                  # affray_diag
    "vm/numbers:"                            # affray_numbers
    "image: diag"                            # affray_image (and the module affray_image_io)
    "texture: image"                         # affray_texture
    "lang: diag"                             # affray_lang
    "vm: vm/numbers texture diag"            # affray_vm
    "compiler: lang vm"                      # affray_compiler
    "scene: diag vm"                         # affray_scene
    "renderer: diag image scene compiler vm" # affray_renderer
    "rib: diag scene"                        # affray_rib
    "tools: rib renderer compiler vm lang image")  # affray_cli and the affray program

# The files checked: C++ sources and headers, and the Flex and Bison sources (their C++ blocks).
set(AFFRAY_LAYER_SOURCES *.h *.hh *.hpp *.inl *.cpp *.cc *.l *.y)

if(NOT ROOT)
  get_filename_component(ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
endif()
get_filename_component(ROOT "${ROOT}" ABSOLUTE)

# The table: LAYERS (in order) and, for each layer L, LINKS_<L> (its direct links).
set(LAYERS "")
foreach(entry IN LISTS AFFRAY_LAYERS)
  if(NOT entry MATCHES "^([a-z_/]+):(.*)$")
    message(FATAL_ERROR "check_layers: the table's entry '${entry}' is not 'folder: folders it links'")
  endif()
  set(layer "${CMAKE_MATCH_1}")
  string(REGEX MATCHALL "[^ \t]+" links "${CMAKE_MATCH_2}")
  foreach(link IN LISTS links)
    if(NOT link IN_LIST LAYERS)
      message(FATAL_ERROR "check_layers: in the table, ${layer} links ${link}, which is not a folder listed before it")
    endif()
  endforeach()
  list(APPEND LAYERS "${layer}")
  set("LINKS_${layer}" "${links}")
endforeach()

# ALLOWED_<L>: L itself and every layer L reaches through its links, in the table's order.
foreach(layer IN LISTS LAYERS)
  set(reached "${layer}")
  foreach(link IN LISTS "LINKS_${layer}")
    list(APPEND reached ${ALLOWED_${link}})
  endforeach()
  set(allowed "")
  foreach(other IN LISTS LAYERS)
    if(other IN_LIST reached)
      list(APPEND allowed "${other}")
    endif()
  endforeach()
  set("ALLOWED_${layer}" "${allowed}")
endforeach()

# The layer a path (of a file, or of an include) belongs to: the longest layer that is a prefix
# of its folders; else its first folder when that is a folder of ROOT (tests/, fuzz/, bench/...,
# which no library may include); else "" (an include of a file beside the includer, or of a
# generated file such as lang's parser.hh).
function(layer_of path out)
  set(best "")
  foreach(layer IN LISTS LAYERS)
    string(LENGTH "${layer}" n)
    string(LENGTH "${best}" b)
    string(SUBSTRING "${path}/" 0 ${n} head)
    string(SUBSTRING "${path}/" ${n} 1 next)
    if(head STREQUAL layer AND next STREQUAL "/" AND n GREATER b)
      set(best "${layer}")
    endif()
  endforeach()
  if(best STREQUAL "" AND path MATCHES "^([^/]+)/" AND IS_DIRECTORY "${ROOT}/${CMAKE_MATCH_1}")
    set(best "${CMAKE_MATCH_1}")
  endif()
  set(${out} "${best}" PARENT_SCOPE)
endfunction()

# The number of the line at offset `at` of `text` (1 for the first).
function(line_at text at out)
  string(SUBSTRING "${text}" 0 ${at} before)
  string(REGEX MATCHALL "\n" breaks "${before}")
  list(LENGTH breaks n)
  math(EXPR n "${n} + 1")
  set(${out} ${n} PARENT_SCOPE)
endfunction()

set(violations 0)
set(scanned 0)
foreach(layer IN LISTS LAYERS)
  if(NOT IS_DIRECTORY "${ROOT}/${layer}")
    message(FATAL_ERROR "check_layers: the table's folder ${layer}/ is not in ${ROOT}")
  endif()
  set(globs "")
  foreach(pattern IN LISTS AFFRAY_LAYER_SOURCES)
    list(APPEND globs "${ROOT}/${layer}/${pattern}")
  endforeach()
  file(GLOB_RECURSE files RELATIVE "${ROOT}" ${globs})
  list(SORT files)
  string(REPLACE ";" "/, " may "${ALLOWED_${layer}}/")
  foreach(file IN LISTS files)
    layer_of("${file}" owner)
    if(NOT owner STREQUAL layer)
      continue()  # a file of a sublayer (vm/numbers/ under vm/), checked as that layer's
    endif()
    math(EXPR scanned "${scanned} + 1")
    # A newline before the text, so that every include line is matched from the newline ending
    # the line before it (CMake's ^ matches only at the start of the text).
    file(READ "${ROOT}/${file}" text)
    string(PREPEND text "\n")
    string(REGEX MATCHALL "\n[ \t]*#[ \t]*include[ \t]*\"[^\"\n]*\"" includes "${text}")
    set(from 0)  # where the search for the next include starts, past the one before
    foreach(include IN LISTS includes)
      string(SUBSTRING "${text}" ${from} -1 rest)
      string(FIND "${rest}" "${include}" at)
      math(EXPR at "${from} + ${at}")
      string(LENGTH "${include}" n)
      math(EXPR from "${at} + ${n}")
      string(REGEX REPLACE ".*\"([^\"]*)\"$" "\\1" path "${include}")
      set(why "")
      if(path MATCHES "(^|/)\\.\\.(/|$)")
        set(why "climbs out of its folder (includes are written from the source root)")
      else()
        layer_of("${path}" target)
        if(NOT target STREQUAL "" AND NOT target IN_LIST ALLOWED_${layer})
          set(why "${layer}/ may include only ${may}")
        endif()
      endif()
      if(NOT why STREQUAL "")
        line_at("${text}" ${at} line)  # counts the newline put before the text, not the match's own
        message("${file}:${line}: #include \"${path}\": ${why}")
        math(EXPR violations "${violations} + 1")
      endif()
    endforeach()
  endforeach()
endforeach()

if(violations GREATER 0)
  message(FATAL_ERROR "check_layers: ${violations} include(s) cross the layers (the table is at the top of "
                      "tools/check_layers.cmake)")
endif()
message("check_layers: ${scanned} files, every include within the layers")
