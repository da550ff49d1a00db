# The test install_example (tests/CMakeLists.txt), run as `cmake -P`: installs the build tree
# into a fresh prefix under WORK_DIR, builds examples/ against the installed package
# (find_package(meshvid)), checks that none of the encoder's internal folders was installed,
# runs both examples, and builds mvid_info once more with
# `pkg-config --cflags --libs meshvid` alone.
# Variables: BINARY_DIR, SOURCE_DIR, WORK_DIR, GENERATOR, CXX_COMPILER, LAUNCHER (may be empty),
# GOLDEN (a .mvid for mvid_info).
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${command}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${prefix})

# The encoder's stages are internal: only its root headers (the public API) are installed.
file(GLOB installed_encoder_folders LIST_DIRECTORIES true
     ${prefix}/include/meshvid/codec/enc/*/)
foreach(folder ${installed_encoder_folders})
  if(IS_DIRECTORY ${folder})
    message(FATAL_ERROR "an internal encoder folder was installed: ${folder}")
  endif()
endforeach()

# Nothing of the source tree may be needed: the package must stand alone.
set(launcher_flags "")
if(LAUNCHER)
  set(launcher_flags -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER} ${launcher_flags}
    -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/encode_decode)
run(${WORK_DIR}/build/mvid_info ${GOLDEN})

# pkg-config: the decoder example from meshvid.pc's flags only.
find_program(PKG_CONFIG pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} "")
file(GLOB_RECURSE pc_files ${prefix}/*/meshvid.pc)
list(GET pc_files 0 pc_file)
get_filename_component(pc_dir ${pc_file} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
execute_process(COMMAND ${PKG_CONFIG} --cflags --libs meshvid
                RESULT_VARIABLE rc OUTPUT_VARIABLE flags ERROR_VARIABLE err
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config meshvid failed: ${err}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${LAUNCHER} ${CXX_COMPILER} -O1 ${SOURCE_DIR}/examples/mvid_info.cc ${flags}
    -o ${WORK_DIR}/mvid_info_pc)
run(${WORK_DIR}/mvid_info_pc ${GOLDEN})
