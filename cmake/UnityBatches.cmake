# fremond_unity_batches(OUT PREFIX SIZE SOURCES...): writes source files PREFIX_0.cpp, PREFIX_1.cpp,
# ... in the current build folder, each including SIZE of SOURCES, and sets OUT to their list.
# A batch compiles the templates its files share (Eigen's, GoogleTest's, pybind11's) once, not
# once a file. Unlike CMake's UNITY_BUILD, the batches include their files by paths relative to
# the build folder, so a clone in another folder compiles them from the compiler cache of the last.
function(fremond_unity_batches out prefix size)
  set(batches "")
  set(content "")
  set(count 0)
  set(index 0)
  foreach(source IN LISTS ARGN)
    file(RELATIVE_PATH relative ${CMAKE_CURRENT_BINARY_DIR} ${source})
    string(APPEND content "#include \"${relative}\"\n")
    math(EXPR count "${count} + 1")
    if(count EQUAL size)
      file(CONFIGURE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${prefix}_${index}.cpp CONTENT "${content}")
      list(APPEND batches ${CMAKE_CURRENT_BINARY_DIR}/${prefix}_${index}.cpp)
      math(EXPR index "${index} + 1")
      set(content "")
      set(count 0)
    endif()
  endforeach()
  if(count GREATER 0)
    file(CONFIGURE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${prefix}_${index}.cpp CONTENT "${content}")
    list(APPEND batches ${CMAKE_CURRENT_BINARY_DIR}/${prefix}_${index}.cpp)
  endif()
  set(${out} ${batches} PARENT_SCOPE)
endfunction()
