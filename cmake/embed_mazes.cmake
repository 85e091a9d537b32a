# The maze files of mazes/, compiled in so that the program runs with no file ("classic" first:
# the default). Writes ${PROJECT_BINARY_DIR}/embedded_mazes.cpp; MARBLE_MAZE_ROOT is the package.
file(GLOB maze_files RELATIVE ${MARBLE_MAZE_ROOT}/mazes ${MARBLE_MAZE_ROOT}/mazes/*.yaml)
list(SORT maze_files)
list(REMOVE_ITEM maze_files classic.yaml)
set(EMBEDDED_MAZE_ENTRIES "")
foreach(maze_file classic.yaml ${maze_files})
  get_filename_component(maze_name ${maze_file} NAME_WE)
  file(READ ${MARBLE_MAZE_ROOT}/mazes/${maze_file} maze_text)
  string(APPEND EMBEDDED_MAZE_ENTRIES "      {\"${maze_name}\", R\"MAZE(${maze_text})MAZE\"},\n")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
    ${MARBLE_MAZE_ROOT}/mazes/${maze_file})
endforeach()
configure_file(${MARBLE_MAZE_ROOT}/src/core/embedded_mazes.cpp.in
  ${PROJECT_BINARY_DIR}/embedded_mazes.cpp @ONLY)
