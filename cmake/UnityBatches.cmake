# fremond_unity_batches(OUT PREFIX SIZE SOURCES...): writes source files PREFIX_0.cpp, PREFIX_1.cpp,
# ... in the current build folder, each including SIZE of SOURCES, and sets OUT to their list.
# A batch compiles the templates its files share (Eigen's, GoogleTest's, pybind11's) once, not
# once a file. Unlike CMake's UNITY_BUILD, the batches include their files by paths relative to
# the build folder, so a clone in another folder compiles them from the compiler cache of the last.
function(fremond_unity_batches out prefix size)
  set(batches "")
  list(LENGTH ARGN count)
  if(count EQUAL 0)
    set(${out} "" PARENT_SCOPE)
    return()
  endif()
  math(EXPR last "${count} - 1")
  foreach(first RANGE 0 ${last} ${size})
    list(SUBLIST ARGN ${first} ${size} sources)
    set(content "")
    foreach(source IN LISTS sources)
      file(RELATIVE_PATH relative ${CMAKE_CURRENT_BINARY_DIR} ${source})
      string(APPEND content "#include \"${relative}\"\n")
    endforeach()
    math(EXPR index "${first} / ${size}")
    set(batch ${CMAKE_CURRENT_BINARY_DIR}/${prefix}_${index}.cpp)
    file(CONFIGURE OUTPUT ${batch} CONTENT "${content}")
    list(APPEND batches ${batch})
  endforeach()
  set(${out} ${batches} PARENT_SCOPE)
endfunction()
