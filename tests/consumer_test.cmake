# Installs dla into a scratch prefix, then configures, builds and runs examples/consumer
# against it with find_package(dla): what a C++ user does.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${DLA_BUILD_DIR} --prefix ${prefix}
  RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "cmake --install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${DLA_SOURCE_DIR}/examples/consumer -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "configuring examples/consumer against the installed package failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j 2 RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "building examples/consumer failed")
endif()
execute_process(COMMAND ${WORK_DIR}/build/grow_tree ${WORK_DIR}/tree
  RESULT_VARIABLE failed OUTPUT_VARIABLE out)
if(failed)
  message(FATAL_ERROR "examples/consumer failed: ${out}")
endif()
foreach(ext pov inc csv)
  if(NOT EXISTS ${WORK_DIR}/tree.${ext})
    message(FATAL_ERROR "examples/consumer wrote no tree.${ext}")
  endif()
endforeach()
message(STATUS "${out}")
