# Configures, builds and runs tests/consumer against this checkout, either
# through add_subdirectory() or through find_package() after an install.
# Called by CTest with SOURCE_DIR, WORK_DIR, MAIN_BUILD_DIR, CXX_COMPILER, MODE, and
# optionally AVX2=ON (add_subdirectory with ACTIONSTRING_AVX2, checked in main.cpp).
function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "step failed (${result}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

set(build_dir ${WORK_DIR}/${MODE})
if(AVX2)
  set(build_dir ${WORK_DIR}/${MODE}_avx2)
endif()
file(REMOVE_RECURSE ${build_dir})
set(configure_args -S ${SOURCE_DIR}/tests/consumer -B ${build_dir}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCONSUMER_MODE=${MODE} -DCMAKE_BUILD_TYPE=Release)
if(MODE STREQUAL "package")
  set(prefix ${WORK_DIR}/prefix)
  file(REMOVE_RECURSE ${prefix})
  run_step(${CMAKE_COMMAND} --install ${MAIN_BUILD_DIR} --prefix ${prefix})
  list(APPEND configure_args -DCMAKE_PREFIX_PATH=${prefix})
else()
  list(APPEND configure_args -DACTIONSTRING_SOURCE_DIR=${SOURCE_DIR})
  if(AVX2)
    list(APPEND configure_args -DACTIONSTRING_AVX2=ON -DCONSUMER_EXPECT_WIDE=ON)
  endif()
endif()
run_step(${CMAKE_COMMAND} ${configure_args})
run_step(${CMAKE_COMMAND} --build ${build_dir})
run_step(${build_dir}/consumer)
message(STATUS "consumer (${MODE}, AVX2 ${AVX2}) built and ran")
