# The test `package`: installs the package into a prefix inside the build tree, then
# configures, builds and runs the project of test/package against it, as a user would.
#
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DCXX_COMPILER=...
#         [-DBUILD_TYPE=...] -P test_package.cmake

foreach(variable BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "test_package.cmake: ${variable} is not set")
  endif()
endforeach()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

set(prefix ${WORK_DIR}/prefix)
set(user_build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${step} failed (${result}): ${ARGN}")
  endif()
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
file(GLOB_RECURSE config_files ${prefix}/*/CGAL_Spherical_parameterizationConfig*.cmake)
foreach(file ${prefix}/include/CGAL/spherical_parameterize.h
             ${prefix}/include/CGAL/Spherical_parameterization/Spherical_parameterizer_3.h)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()
message(STATUS "installed into ${prefix}; package files: ${config_files}")

# What a user project does not check: the target's headers are those of the prefix, and the
# version file refuses a version that the package does not provide.
set(checks ${WORK_DIR}/checks)
file(WRITE ${checks}/CMakeLists.txt [=[
cmake_minimum_required(VERSION 3.16)
project(Spherical_parameterization_package_checks LANGUAGES CXX)
find_package(CGAL_Spherical_parameterization 99 QUIET)
if(CGAL_Spherical_parameterization_FOUND)
  message(FATAL_ERROR "find_package(CGAL_Spherical_parameterization 99) found version ${CGAL_Spherical_parameterization_VERSION}")
endif()
find_package(CGAL_Spherical_parameterization REQUIRED)
get_target_property(include_dirs CGAL::Spherical_parameterization INTERFACE_INCLUDE_DIRECTORIES)
if(NOT "${EXPECTED_PREFIX}/include" IN_LIST include_dirs)
  message(FATAL_ERROR "CGAL::Spherical_parameterization includes ${include_dirs}, not ${EXPECTED_PREFIX}/include")
endif()
]=])
run("checks" ${CMAKE_COMMAND} -S ${checks} -B ${checks}/build -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DEXPECTED_PREFIX=${prefix})

# The user project. Only the prefix is given: the package must not come from the source or
# build tree.
run("configure" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/package -B ${user_build} -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
run("build" ${CMAKE_COMMAND} --build ${user_build} --parallel 1)
find_program(program map_to_sphere PATHS ${user_build} ${user_build}/${BUILD_TYPE} NO_DEFAULT_PATH)
if(NOT program)
  message(FATAL_ERROR "map_to_sphere not built in ${user_build}")
endif()
run("run" ${program})
