# The sanitizer pass (ctest's `sanitizers` test): builds the project with AddressSanitizer and
# UndefinedBehaviorSanitizer in its own folder and runs the unit tests there; builds the unit
# tests with ThreadSanitizer in another and runs those of the threaded growth; then fuzzes
# every mesh reader, the command line, analyze's CSV reader and the leaf reader for
# FUZZ_SECONDS each from the seed corpus. With clang the fuzzers are built too; without it the
# pass says so and fuzzes nothing.
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -DFUZZ_SECONDS=15 -P tests/sanitizers.cmake
find_program(CLANGXX NAMES clang++ clang++-14)
set(compiler)
if(CLANGXX)
  # Line tables are all a sanitizer's report needs, and build much faster than full debug info.
  set(compiler -DCMAKE_CXX_COMPILER=${CLANGXX} -DDLA_FUZZ=ON "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG")
else()
  message(WARNING "clang++ is missing (the README's setup installs it): the mesh readers are not fuzzed")
endif()

# Each step says how long it took, so that CI's log shows where the pass's time goes.
function(step what)
  string(TIMESTAMP start "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE failed)
  string(TIMESTAMP end "%s")
  math(EXPR seconds "${end} - ${start}")
  message(STATUS "sanitizers: ${what} took ${seconds} s")
  if(failed)
    message(FATAL_ERROR "failed (${failed}): ${ARGN}")
  endif()
endfunction()

step("configuring ASan and UBSan" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -DCMAKE_BUILD_TYPE=RelWithDebInfo ${compiler}
     -DDLA_SANITIZE=ON -DDLA_BUILD_BENCH=OFF -DDLA_BUILD_EXAMPLES=OFF -DDLA_BUILD_PYTHON=OFF)
step("building with ASan and UBSan" ${CMAKE_COMMAND} --build ${WORK_DIR} -j2)
# Left to the plain build, as nothing the sanitizers add to: the consumer example, which
# installs a package; the real clients (Blender, PrusaSlicer, admesh, the glTF validator,
# Chromium, the gallery's renders), which read files that the writers' own tests write here too;
# the two tests of scale (a million particles, a glb past 4 GiB), minutes under ASan for the
# code that smaller runs take; the full tier (the property test at length, the statistics).
set(plain_only "^(consumer_example|gallery_small|Blender\\..*|PrusaSlicer\\..*|Admesh\\..*|GltfValidator\\..*|Chromium\\..*|Cli\\.TheGridHoldsAMillionParticlesIn2D|LookFiles\\.AGlbPastItsFourGigabytesIsRefusedBeforeItIsWritten)$")
step("the tests under ASan and UBSan" ${CMAKE_CTEST_COMMAND} --test-dir ${WORK_DIR} --output-on-failure -j2 -E ${plain_only} -LE full)

# Walkers on several threads share the index while one of them attaches, a spare core measures
# the distances to the mesh as they attach, the look shares out the rest, and an aggregate's
# large clusters test their steps on a crew: TSan checks that
# every word they share is read and written atomically. The TSan build compiles only the files
# these tests are in (tests/CMakeLists.txt, DLA_TSAN): a test named here must be in one of them.
set(tsan_dir ${WORK_DIR}-thread)
step("configuring TSan" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${tsan_dir} -DCMAKE_BUILD_TYPE=RelWithDebInfo ${compiler}
     -DDLA_FUZZ=OFF -DDLA_TSAN=ON -DDLA_BUILD_BENCH=OFF -DDLA_BUILD_EXAMPLES=OFF -DDLA_BUILD_PYTHON=OFF)
step("building with TSan" ${CMAKE_COMMAND} --build ${tsan_dir} -j2 --target dla_tests)
step("the threaded tests under TSan" ${CMAKE_COMMAND} -E env TSAN_OPTIONS=halt_on_error=1
     ${tsan_dir}/tests/dla_tests --gtest_filter=Threads.*:Constraint.SameResultOnEveryThreadCount:ParticleFeed.*:GrowRecorded.*:Attributes.BoundaryDistance*:Attributes.ClosestTriangles*:Aggregate.TheSameAggregateOnAnyThreadCount)

if(CLANGXX)
  foreach(format stl off obj ply points cli csv leaf)
    set(corpus ${WORK_DIR}/fuzz_corpus/${format})
    file(MAKE_DIRECTORY ${corpus})
    step("fuzzing ${format}" ${WORK_DIR}/tests/fuzz/fuzz_${format} -max_total_time=${FUZZ_SECONDS} -rss_limit_mb=2048 -timeout=10
         -print_final_stats=1 ${corpus} ${SOURCE_DIR}/tests/fuzz/corpus/${format})
  endforeach()
endif()
