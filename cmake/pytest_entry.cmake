# dla_add_pytest(NAME FILE [PYTHONPATH DIR...] [ENVIRONMENT VAR=VALUE...] [ARGS WORD...]): one
# ctest entry that runs a pytest file, with pytest's ARGS (a -k selection) before it. It is Failed when any test in it fails or errs, Skipped only when every
# test in it skipped (tests/python/ctest_exit.py then exits 77), and Passed otherwise, with
# pytest's -rs naming each skip. tests/ctest_truth.cmake checks this wiring on a project of its
# own.
set(DLA_PYTEST_PLUGIN_DIR ${CMAKE_CURRENT_LIST_DIR}/../tests/python)
function(dla_add_pytest name file)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "" "PYTHONPATH;ENVIRONMENT;ARGS")
  add_test(NAME ${name} COMMAND ${Python3_EXECUTABLE} -m pytest -q -rs -p no:cacheprovider -p ctest_exit ${arg_ARGS}
                                ${file})
  list(APPEND arg_PYTHONPATH ${DLA_PYTEST_PLUGIN_DIR})
  list(JOIN arg_PYTHONPATH ":" path)
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "PYTHONPATH=${path};${arg_ENVIRONMENT}")
endfunction()
