# ctest sanitize.kernel (issue 24 item 9): the system layer and the kernel's driver code built a second time under
# AddressSanitizer + UndefinedBehaviorSanitizer, in every test build, so that the checks the project runs on every
# change (CI included) keep a sanitizer run. The whole suite under the sanitizers (tools/sanitize.sh, README
# "Sanitizers") does not fit CI's ~10 min on 2 cores: its four pair-stepper instantiation units alone take 5-8 min
# of CPU each under ASan at -O2 (measured 2026-11-26 on the 2-core VM). This subset instruments every other source
# of core, kernel, contact, model and physics (compiled into the test program: the system stepper and its
# instantiation, run_system, the System and shear-building builders, modes, validation, tiles' fill and collect,
# batch and single-impact code) and the GoogleTest files that drive them; the pair steppers' four instantiation
# units are linked uninstrumented from pounding_physics (an archive member is pulled only for a symbol nothing
# else defines, so the instrumented units take precedence). -O1 keeps the compile short; the kernel's
# architecture flag keeps the SIMD paths. No stored-bits comparison runs here (identical bits are claimed for the
# Release build only). The pair steppers themselves are instrumented by the full run (tools/sanitize.sh).
option(POUNDING_SANITIZE_KERNEL_TESTS "Build and run the kernel tests under ASan + UBSan too (ctest sanitize.kernel)" ON)
if(NOT POUNDING_SANITIZE_KERNEL_TESTS OR POUNDING_SANITIZE OR NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  return()
endif()
# The GoogleTest files it runs (each also runs uninstrumented as usual); add a kernel-level test here too.
# (test_kernel_linear and test_kernel_impact are left out: 54 s of the subset's 303 s of compile for the pair
# steppers, which are uninstrumented here anyway)
set(POUNDING_SANITIZE_KERNEL_TEST_FILES
    tests/test_kernel_batch.cpp tests/test_kernel_energy.cpp tests/test_kernel_hysteresis.cpp
    tests/model/test_system.cpp tests/model/test_modes.cpp tests/model/test_shear_topology.cpp
    tests/physics/test_system_pair.cpp tests/physics/test_system_validate.cpp tests/physics/test_shear_building.cpp
    tests/physics/test_system_kernel.cpp tests/physics/test_isolation.cpp tests/model/test_hysteresis_traits.cpp)
# linked from pounding_physics, uninstrumented (see above)
set(_san_heavy "instantiate_(central_difference|newmark|rk4|nigam_jennings)\\.cpp$")
set(_san_bits "the sanitize.kernel program: instrumented code at -O1, and identical bits are claimed for the uninstrumented Release build")
set(_san_sources "")
foreach(_lib pounding_core pounding_kernel pounding_contact pounding_model pounding_physics)
  get_target_property(_type ${_lib} TYPE)
  if(_type STREQUAL "STATIC_LIBRARY")
    get_target_property(_src ${_lib} SOURCES)
    list(FILTER _src EXCLUDE REGEX "${_san_heavy}")
    list(APPEND _san_sources ${_src})
  endif()
endforeach()
add_executable(sanitize_kernel ${_san_sources} ${POUNDING_SANITIZE_KERNEL_TEST_FILES})
target_include_directories(sanitize_kernel PRIVATE ${PROJECT_SOURCE_DIR}/include ${PROJECT_BINARY_DIR}/generated
                           ${PROJECT_SOURCE_DIR}/tests)
target_compile_features(sanitize_kernel PRIVATE cxx_std_20)
target_compile_options(sanitize_kernel PRIVATE -O1 -fsanitize=address,undefined -fno-sanitize-recover=all
                       -fno-omit-frame-pointer)
target_link_options(sanitize_kernel PRIVATE -fsanitize=address,undefined)
target_link_libraries(sanitize_kernel PRIVATE GTest::gtest GTest::gtest_main pounding::physics pounding::workloads fmt::fmt Boost::headers
                      Eigen3::Eigen Threads::Threads)
# POUNDING_RELAXED_INLINE: the kernel's forced inlining becomes a hint (include/pounding/kernel/lane.hpp). Forced, the
# instrumented instantiate_system_central_difference.cpp took about 17 min of CPU and 0.9 GB (GCC 12, this 2-core
# VM, 2026-12-07); relaxed, 15 s. What is inlined changes, not what is computed (no bits are claimed here).
target_compile_definitions(sanitize_kernel PRIVATE POUNDING_RELAXED_INLINE POUNDING_TEST_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                           POUNDING_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data"
                           POUNDING_TEST_REAL_RECORDS_DIR="${POUNDING_REAL_RECORDS_DIR}"
                           POUNDING_BITS_NOT_CLAIMED="${_san_bits}")
pounding_kernel_arch(sanitize_kernel)
math(EXPR _san_timeout "300 * ${POUNDING_TIMEOUT_FACTOR}")
add_test(NAME sanitize.kernel COMMAND sanitize_kernel --gtest_brief=1)
# Any report fails the test: UBSan halts, ASan aborts, LeakSanitizer fails the process.
set_tests_properties(sanitize.kernel PROPERTIES LABELS "unit;sanitize" TIMEOUT ${_san_timeout}
                     ENVIRONMENT "POUNDING_BITS_NOT_CLAIMED=${_san_bits};ASAN_OPTIONS=detect_leaks=1:abort_on_error=1;UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1;POUNDING_REAL_RECORDS=${POUNDING_REAL_RECORDS_DIR}")
