# Checks that every #include in src/<layer>/ and include/latfrac/<layer>/ points at the
# same layer or one below it (the order of LAYERS, lowest first), and that each file
# starts with a one-line comment saying what it is for.
#
#   cmake -DSOURCE_DIR=... -DLAYERS="base;geometry;..." -P check_layers.cmake
#
# The linker catches a call against the direction (each layer is a shared library linked
# with --no-undefined); this catches the rest: a type, an inline function or a template
# used from a header of a higher layer.
set(failures "")
list(LENGTH LAYERS layer_count)
foreach(layer IN LISTS LAYERS)
  list(FIND LAYERS ${layer} rank)
  file(GLOB_RECURSE files
    ${SOURCE_DIR}/src/${layer}/*.cpp ${SOURCE_DIR}/src/${layer}/*.h
    ${SOURCE_DIR}/include/latfrac/${layer}/*.h)
  foreach(file IN LISTS files)
    file(STRINGS ${file} first_line LIMIT_COUNT 1)
    if(NOT first_line MATCHES "^// [A-Za-z]")
      string(APPEND failures "${file}: the first line should say what the file is for\n")
    endif()
    file(STRINGS ${file} includes REGEX "^#include \"latfrac/[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"latfrac/([a-z_]+)/.*" "\\1" target ${line})
      list(FIND LAYERS ${target} target_rank)
      if(target_rank LESS 0)
        string(APPEND failures "${file}: ${line}: no layer '${target}'\n")
      elseif(target_rank GREATER rank)
        string(APPEND failures "${file}: ${line}: layer '${layer}' may not use '${target}' above it\n")
      endif()
    endforeach()
  endforeach()
endforeach()
file(GLOB stray ${SOURCE_DIR}/src/*.cpp ${SOURCE_DIR}/src/*.h ${SOURCE_DIR}/include/latfrac/*.h)
foreach(file IN LISTS stray)
  string(APPEND failures "${file}: outside every layer's folder\n")
endforeach()
if(failures)
  message(FATAL_ERROR "layering violations:\n${failures}")
endif()
message(STATUS "every include follows the layers: ${LAYERS}")
