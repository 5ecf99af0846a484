# Test helpers. Every test has one tier label (docs/development.md, "Tests"):
#   unit         in-process (memq://), no processes
#   integration  processes: command lines, real processes over udpm:// in a private network
#                namespace, network-namespace hosts joined by veth
#   browser      headless Chromium
#   soak         long fault schedules (kill -9, loss, stopped processes)
#   style        formatting and layering
#   package      the Debian packages made by CPack, used from a fresh prefix
# and may have descriptive ones: multiprocess (real sockets in a namespace), lan, chaos. The
# Release pass runs every tier; the sanitizer pass runs unit and integration.
# Tests that cannot run here (no namespaces, not root) exit 77 and CTest reports them skipped.

set(AHHS_SKIP_RETURN_CODE 77)

# ahhs_add_catch_test(NAME name SOURCES ... [LIBS ...] [LABELS ...])
# One executable; every Catch2 TEST_CASE becomes its own CTest test. A case tagged [wall] waits
# on the wall clock (a timeout, a real-time episode): it is labelled integration, not unit, so
# the unit tier never sleeps.
function(ahhs_add_catch_test)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ahhs_catch_main ${ARG_LIBS} ahhs_warnings)
  set(wall_labels "${ARG_LABELS}")
  list(TRANSFORM wall_labels REPLACE "^unit$" "integration")
  foreach(part "~[wall]" "[wall]")
    set(labels "${ARG_LABELS}")
    if(part STREQUAL "[wall]")
      set(labels "${wall_labels}")
    endif()
    catch_discover_tests(${ARG_NAME}
      TEST_SPEC "${part}"
      TEST_PREFIX "${ARG_NAME}:"
      # A name CTest cannot pass through whole (a semicolon splits it) would match no test case
      # and pass without running anything: make that a failure.
      EXTRA_ARGS --warn NoTests
      WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}
      PROPERTIES LABELS "${labels}" SKIP_RETURN_CODE ${AHHS_SKIP_RETURN_CODE}
                 ENVIRONMENT "AHHS_SOURCE_DIR=${PROJECT_SOURCE_DIR};AHHS_BINARY_DIR=${PROJECT_BINARY_DIR}")
  endforeach()
endfunction()

# ahhs_add_script_test(NAME name COMMAND ... LABELS ... [TIMEOUT s] [COST s]
#                      [PACED | FARM | REALTIME])
# COST: about how many seconds it runs; CTest starts the costliest tests first (a fresh clone has
# no timings of its own). PACED: its processes wait on timeouts (a tenth of a core or less) and
# it checks nothing a loaded machine changes, so it needs no lock against the others (below);
# not for real-time episodes, which do not wait for a late process. FARM: its processes talk
# only through the evaluation farm (a request and a result an episode, a lost one re-issued; no
# lockstep arena, no logger) and it checks nothing a loaded machine changes: it may run beside a
# lockstep test, though not beside another FARM test or a REALTIME one, as it keeps the cores
# busy. REALTIME: it runs real-time episodes, which do not wait for a late process: it runs alone
# (RUN_SERIAL), as a busy test beside it made a module miss a 25-ms tick (below).
function(ahhs_add_script_test)
  cmake_parse_arguments(ARG "PACED;FARM;REALTIME" "NAME;TIMEOUT;COST" "COMMAND;LABELS" ${ARGN})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  add_test(NAME ${ARG_NAME} COMMAND ${ARG_COMMAND})
  set_tests_properties(${ARG_NAME} PROPERTIES
    LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT} SKIP_RETURN_CODE ${AHHS_SKIP_RETURN_CODE}
    ENVIRONMENT "AHHS_SOURCE_DIR=${PROJECT_SOURCE_DIR};AHHS_BINARY_DIR=${PROJECT_BINARY_DIR}")
  if(ARG_COST)
    set_tests_properties(${ARG_NAME} PROPERTIES COST ${ARG_COST})
  endif()
  # Tests of real processes over real sockets run one at a time: two unpaced lockstep arenas at
  # once on a 2-core machine outran lcm-logger and the kernel's socket buffers. One of them may
  # run beside a test of one process or a paced one (a lock, not RUN_SERIAL): most of these
  # tests wait on sockets and lockstep and leave a core idle.
  # A FARM test holds a second lock, ahhs_busy_cores, that keeps two busy farms apart. A REALTIME
  # test runs alone: with any other test beside it (a farm, a report replaying genomes, a
  # compile-heavy style check) two cores have more runnable processes than they run at once, and
  # in a clean clone a module then answered a tick 27.6 ms late (budget 25) and another missed
  # one (only the next pass's build, at nice 19, runs beside it).
  if(ARG_REALTIME)
    set_tests_properties(${ARG_NAME} PROPERTIES RUN_SERIAL TRUE)
  elseif(ARG_FARM)
    set_tests_properties(${ARG_NAME} PROPERTIES RESOURCE_LOCK ahhs_busy_cores)
  elseif(NOT ARG_PACED AND ("multiprocess" IN_LIST ARG_LABELS OR "lan" IN_LIST ARG_LABELS OR
                            "chaos" IN_LIST ARG_LABELS))
    set_tests_properties(${ARG_NAME} PROPERTIES RESOURCE_LOCK ahhs_processes)
  endif()
endfunction()
