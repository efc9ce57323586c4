# bowg_engine: the ROS-free BoWG library, its tests, benchmarks and tools.
#
# Included by engine/CMakeLists.txt (standalone build: cmake -S engine -B b)
# and by the catkin package's top-level CMakeLists.txt, where the tests become
# catkin gtests so that catkin_test_results sees them.
set(BOWG_ENGINE_DIR ${CMAKE_CURRENT_LIST_DIR})

# Build switches. The standalone build (engine/CMakeLists.txt) declares them
# as cache options. In the catkin package they are plain variables with the
# same defaults: catkin_make configures all packages of a workspace as one
# CMake project with one cache, where an option not named after the package
# would be global to all of them. A -D on the command line still sets them in
# either build.
if(NOT DEFINED BOWG_ENGINE_TESTS)
  set(BOWG_ENGINE_TESTS ON)
endif()
if(NOT DEFINED BOWG_ENGINE_BENCHMARKS)
  set(BOWG_ENGINE_BENCHMARKS ON)
endif()
if(NOT DEFINED BOWG_SANITIZE)
  set(BOWG_SANITIZE OFF)
endif()

find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs features2d calib3d)
find_package(ZLIB REQUIRED)
# The .bowgvoc loader hashes on a helper thread (std::thread).
find_package(Threads REQUIRED)

if(BOWG_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer)
  link_libraries(-fsanitize=address,undefined)
endif()

include(CheckCXXCompilerFlag)
check_cxx_compiler_flag(-mpopcnt BOWG_HAS_MPOPCNT)

# One folder per pipeline stage (core, features, vocabulary with its file
# formats, database, scoring, detection, parameters); headers and tests mirror
# it. src/ is also an include root for the stage-internal headers
# (e.g. core/yaml_tokens.h), which are not installed.
file(GLOB_RECURSE BOWG_ENGINE_SOURCES ${BOWG_ENGINE_DIR}/src/*.cpp)
add_library(bowg_engine ${BOWG_ENGINE_SOURCES})
target_include_directories(bowg_engine PUBLIC
  $<BUILD_INTERFACE:${BOWG_ENGINE_DIR}/include>)
target_include_directories(bowg_engine PRIVATE ${BOWG_ENGINE_DIR}/src)
# OpenCV's imported targets carry their include directories.
target_link_libraries(bowg_engine PUBLIC ${OpenCV_LIBS} ZLIB::ZLIB Threads::Threads)
target_compile_options(bowg_engine PRIVATE -Wall -Wextra)
if(BOWG_HAS_MPOPCNT)
  # Hardware popcount for the 256-bit Hamming distance (x86-64 only; ARM
  # robots get their own instruction from the compiler's default).
  target_compile_options(bowg_engine PUBLIC -mpopcnt)
endif()
set_target_properties(bowg_engine PROPERTIES POSITION_INDEPENDENT_CODE ON)

# Engine tests: one gtest executable per test/*_test.cpp. Test data written by
# the tests themselves goes to the build tree; shared third-party data is read
# from BOWG_SHARED_DATA_DIR (tests skip with a message where it is absent).
# REALPATH: the catkin workspace reaches the repository through links, one per
# top-level entry (scripts/link_package.sh), so resolve engine/ itself before
# going up: "engine/.." would stay in the workspace.
get_filename_component(BOWG_REPO_DIR ${BOWG_ENGINE_DIR} REALPATH)
get_filename_component(BOWG_REPO_DIR ${BOWG_REPO_DIR} DIRECTORY)
set(BOWG_SHARED_DATA_DIR_DEFAULT ${BOWG_REPO_DIR}/../shared/data)
# Not a cache variable: a stale cached path (e.g. from a workspace that moved)
# would silently turn the data tests into skips. Override with -D.
if(NOT BOWG_SHARED_DATA_DIR)
  set(BOWG_SHARED_DATA_DIR ${BOWG_SHARED_DATA_DIR_DEFAULT})
endif()
message(STATUS "bowg_engine: shared data folder ${BOWG_SHARED_DATA_DIR}")

function(bowg_engine_test name source)
  if(COMMAND catkin_add_gtest)
    catkin_add_gtest(${name} ${source} ${ARGN})
  else()
    find_package(GTest REQUIRED)
    add_executable(${name} ${source} ${ARGN})
    target_link_libraries(${name} GTest::gtest GTest::gtest_main)
    add_test(NAME ${name} COMMAND ${name})
  endif()
  if(TARGET ${name})
    target_link_libraries(${name} bowg_engine)
    if(COMMAND catkin_add_gtest)
      target_link_libraries(${name} gtest_main)
    endif()
    target_compile_definitions(${name} PRIVATE
      BOWG_SHARED_DATA_DIR="${BOWG_SHARED_DATA_DIR}"
      BOWG_TEST_OUTPUT_DIR="${CMAKE_CURRENT_BINARY_DIR}")
    target_include_directories(${name} PRIVATE ${BOWG_ENGINE_DIR}/test ${BOWG_ENGINE_DIR}/src)
  endif()
endfunction()

if(BOWG_ENGINE_TESTS)
  if(NOT COMMAND catkin_add_gtest)
    enable_testing()
  endif()
  file(GLOB_RECURSE BOWG_ENGINE_TEST_SOURCES ${BOWG_ENGINE_DIR}/test/*_test.cpp)
  foreach(test_source ${BOWG_ENGINE_TEST_SOURCES})
    get_filename_component(test_name ${test_source} NAME_WE)
    bowg_engine_test(bowg_${test_name} ${test_source})
  endforeach()
endif()

if(BOWG_ENGINE_BENCHMARKS)
  find_package(benchmark QUIET)
  if(benchmark_FOUND)
    file(GLOB BOWG_BENCH_SOURCES ${BOWG_ENGINE_DIR}/bench/*_bench.cpp)
    foreach(bench_source ${BOWG_BENCH_SOURCES})
      get_filename_component(bench_name ${bench_source} NAME_WE)
      add_executable(bowg_${bench_name} ${bench_source})
      target_link_libraries(bowg_${bench_name} bowg_engine benchmark::benchmark)
      target_compile_definitions(bowg_${bench_name} PRIVATE
        BOWG_SHARED_DATA_DIR="${BOWG_SHARED_DATA_DIR}"
        BOWG_CONFIG_DIR="${BOWG_REPO_DIR}/config")
      # test/ for the synthetic data, src/ for the stage-internal units
      # timed on their own (the AVX2 and portable versions side by side).
      target_include_directories(bowg_${bench_name} PRIVATE ${BOWG_ENGINE_DIR}/test
                                 ${BOWG_ENGINE_DIR}/src)
    endforeach()
  else()
    message(STATUS "bowg_engine: Google Benchmark not found, benchmarks not built")
  endif()
endif()

