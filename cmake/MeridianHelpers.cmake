# meridian_warnings(target): the project's warning set, private to the target.
# -Wno-restrict: GCC 12 reports false positives inside std::string's
# operator+ at -O2 (GCC bug 105329).
# -Wno-subobject-linkage in unity builds: the sources are #included into the batch file, so
# GCC takes them for headers and warns about every test fixture in an anonymous namespace.
function(meridian_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>
    $<$<AND:$<CXX_COMPILER_ID:GNU>,$<BOOL:${CMAKE_UNITY_BUILD}>>:-Wno-subobject-linkage>
    $<$<BOOL:${MERIDIAN_WERROR}>:-Werror>)
endfunction()

# meridian_add_module(name SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Creates library target meridian_<name>, alias and export name Meridian::<name>.
function(meridian_add_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(t meridian_${name})
  add_library(${t} ${M_SOURCES})
  add_library(Meridian::${name} ALIAS ${t})
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${t} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${t} PUBLIC cxx_std_20)
  target_link_libraries(${t} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  meridian_warnings(${t})
  set_property(GLOBAL APPEND PROPERTY MERIDIAN_MODULES ${t})
endfunction()

# meridian_add_test(name SOURCES ... LIBS ... [LABEL label]): one GoogleTest
# executable, each test case registered with CTest under the CTest label
# `label` (default `unit`; e.g. `reference` for cross-checks that run an
# external reference tool, selectable with ctest -L / -LE). Executables labelled
# `montecarlo` are not built when MERIDIAN_MONTECARLO_TESTS is OFF.
function(meridian_add_test name)
  cmake_parse_arguments(T "" "LABEL" "SOURCES;LIBS" ${ARGN})
  if(NOT T_LABEL)
    set(T_LABEL unit)
  endif()
  if(T_LABEL STREQUAL "montecarlo" AND NOT MERIDIAN_MONTECARLO_TESTS)
    return()  # the sanitizer pass does not run them, so it does not build them either
  endif()
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main GTest::gmock)
  meridian_warnings(${name})
  # The test code itself at -O1 in Release (the library it tests keeps -O3): the CI builds
  # it twice within a 30-minute budget, and -O3 bought nothing but compile time here
  # (measured 2026-12-01, user CPU of one file: test_cli.cpp 17.8 s at -O3 against 4.2 s at
  # -O1, test_stochastic.cpp 31.5 s against 15.5 s, test_linear.cpp 27.8 s against 19.5 s).
  # GCC 12 at -O1 warns "may be used uninitialized" inside Eigen's inlined copy constructors
  # (a false positive that -O3's fuller analysis does not raise), hence its -Wno-.
  target_compile_options(${name} PRIVATE "$<$<CONFIG:Release>:-O1;-Wno-maybe-uninitialized>")
  target_compile_definitions(${name} PRIVATE
    MERIDIAN_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    MERIDIAN_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${T_LABEL})
endfunction()
