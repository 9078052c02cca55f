# Test helpers: unit tests (GoogleTest, MPI-aware main) and program runs,
# each registered once per rank count under mpirun.
find_package(GTest)
if(NOT GTest_FOUND)
  ddc_missing("GoogleTest" "libgtest-dev libgmock-dev")
endif()
find_program(DDC_MPIEXEC NAMES mpirun mpiexec HINTS ${MPIEXEC_EXECUTABLE})

# Environment for every test: oversubscription is fine for iteration counts,
# running as root is the norm in containers and CI.
set(DDC_TEST_ENVIRONMENT
  "OMPI_MCA_rmaps_base_oversubscribe=1"
  "OMPI_ALLOW_RUN_AS_ROOT=1"
  "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
  "OMPI_MCA_btl_vader_single_copy_mechanism=none"
  "OPENBLAS_NUM_THREADS=1"
  "OMP_NUM_THREADS=1"
  # One node: the shared-memory transports only. Probing the network ones
  # (UCX, OFI, PSM, openib, TCP) took 0.2 s of every launch's 0.4 s, and the
  # suite launches mpirun about a thousand times.
  "OMPI_MCA_pml=ob1"
  "OMPI_MCA_btl=self,vader"
  # No binding of ranks to cores: each mpirun binds its ranks from core 0 on
  # without knowing of the others, so two one-rank tests that ctest runs side
  # by side shared core 0 and each took twice its time.
  "OMPI_MCA_hwloc_base_binding_policy=none")
# Per-test time limits (a hang fails instead of stalling the suite).
set(DDC_TEST_TIMEOUT 600)
set(DDC_TEST_TIMEOUT_LONG 900)
if(DDContact_ENABLE_SANITIZERS)
  # A report ends the process with a non-zero status, so the test fails.
  # Leak stacks use the fast (frame-pointer) unwinder: its first frame, the
  # caller of malloc, names the library, which is all the suppressions need.
  # That frame has a module name because the sanitizer build keeps run-time
  # loaded modules mapped (packages/core/src/DDC_SanitizerSupport.cpp).
  list(APPEND DDC_TEST_ENVIRONMENT
    "ASAN_OPTIONS=detect_leaks=1:exitcode=86"
    "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/test/sanitizers/lsan.supp:print_suppressions=0"
    "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=87")
  # Instrumented code runs several times slower.
  set(DDC_TEST_TIMEOUT 3600)
  set(DDC_TEST_TIMEOUT_LONG 5400)
endif()

# ddc_mpi_command(<out-var> <ranks> cmd...) : the command line under mpirun.
function(ddc_mpi_command out np)
  set(${out} ${DDC_MPIEXEC} --oversubscribe -np ${np} ${ARGN} PARENT_SCOPE)
endfunction()

# ddc_add_unit_test(<name> SOURCES a.cpp ... LIBRARIES lib... [RANKS 1 2] [LABELS ...] [ARGS ...])
# Builds <name> with the MPI GoogleTest main; registers <name>_np<R> per rank
# count, labelled unit, running <name> with ARGS (e.g. a --gtest_filter).
function(ddc_add_unit_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBRARIES;RANKS;LABELS;ARGS" ${ARGN})
  add_executable(${name} ${T_SOURCES} ${PROJECT_SOURCE_DIR}/test/support/DDC_TestMain.cpp)
  target_link_libraries(${name} PRIVATE ${T_LIBRARIES} GTest::gmock GTest::gtest DDContact_Trilinos)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/test/support)
  target_compile_definitions(${name} PRIVATE DDC_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  ddc_register_unit_test(${name} ${name} RANKS ${T_RANKS} LABELS unit ${T_LABELS} ARGS ${T_ARGS})
endfunction()

# ddc_register_unit_test(<target> <test> [RANKS 1 2] [LABELS ...] [ARGS ...]):
# <test>_np<R> per rank count runs the unit-test executable <target> with ARGS
# under mpirun (another selection of its tests than <target>_np<R>, e.g. a
# slow study labelled study instead of unit).
function(ddc_register_unit_test target test)
  cmake_parse_arguments(T "" "" "RANKS;LABELS;ARGS" ${ARGN})
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  foreach(np ${T_RANKS})
    ddc_mpi_command(cmd ${np} $<TARGET_FILE:${target}> ${T_ARGS})
    add_test(NAME ${test}_np${np} COMMAND ${cmd})
    set_tests_properties(${test}_np${np} PROPERTIES
      ENVIRONMENT "${DDC_TEST_ENVIRONMENT}" PROCESSORS ${np} TIMEOUT ${DDC_TEST_TIMEOUT}
      LABELS "${T_LABELS}")
  endforeach()
endfunction()
