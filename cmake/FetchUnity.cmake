# Unity 2.6.1, taken from the PyPI wheel vyperling==0.0.4 (which carries it byte-identical to
# upstream) and checked by sha256. Only unity.c, unity.h and unity_internals.h are extracted, into
# the build tree; nothing third-party is committed. Defines the static library `unity`.
set(UNITY_DIR "${CMAKE_BINARY_DIR}/_deps/unity")
file(MAKE_DIRECTORY "${UNITY_DIR}")
set(_unity_files unity.c unity.h unity_internals.h)
set(_unity_sha256_unity.c b90e735a54cf3b3765ab6caa955d11a1488ee73d9c6152cdc98576c2d17cb871)
set(_unity_sha256_unity.h 9db174d3c2c6424fd35c0980c5941d124c5ebb0f48e8172f997a2aa9554b64ea)
set(_unity_sha256_unity_internals.h fcd8b3f6b412ac0ab599547eb8a30b6d7f3f0af77aab31f7a1822a2a8fc9a2b2)

function(_unity_verified out)
  set(ok TRUE)
  foreach(f IN LISTS _unity_files)
    if(NOT EXISTS "${UNITY_DIR}/${f}")
      set(ok FALSE)
    else()
      file(SHA256 "${UNITY_DIR}/${f}" got)
      if(NOT got STREQUAL _unity_sha256_${f})
        set(ok FALSE)
      endif()
    endif()
  endforeach()
  set(${out} ${ok} PARENT_SCOPE)
endfunction()

_unity_verified(_unity_ok)
set(UNITY_WHEEL_DIR "" CACHE PATH "Folder holding vyperling-0.0.4-*.whl (else it is downloaded from PyPI)")

if(NOT _unity_ok)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  set(_wheel "")
  if(UNITY_WHEEL_DIR)
    file(GLOB _wheel "${UNITY_WHEEL_DIR}/vyperling-0.0.4-*.whl")
  endif()
  if(NOT _wheel)
    set(_wheel_dir "${CMAKE_BINARY_DIR}/_deps/wheel")
    execute_process(
      COMMAND "${Python3_EXECUTABLE}" -m pip download --no-deps --only-binary=:all:
              --disable-pip-version-check -q -d "${_wheel_dir}" vyperling==0.0.4
      RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "Could not download vyperling==0.0.4 (Unity) from PyPI with ${Python3_EXECUTABLE}")
    endif()
    file(GLOB _wheel "${_wheel_dir}/vyperling-0.0.4-*.whl")
  endif()
  if(NOT _wheel)
    message(FATAL_ERROR "No vyperling-0.0.4 wheel found or downloaded")
  endif()
  list(GET _wheel 0 _wheel)
  execute_process(
    COMMAND "${Python3_EXECUTABLE}" -c
      "import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); [open(sys.argv[2] + '/' + n, 'wb').write(z.read('vyperling/c/' + n)) for n in sys.argv[3:]]"
      "${_wheel}" "${UNITY_DIR}" ${_unity_files}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "Could not extract Unity from ${_wheel}")
  endif()
  _unity_verified(_unity_ok)
  if(NOT _unity_ok)
    file(REMOVE ${UNITY_DIR}/unity.c ${UNITY_DIR}/unity.h ${UNITY_DIR}/unity_internals.h)
    message(FATAL_ERROR "Unity from vyperling==0.0.4 does not match the expected sha256; refusing to use it")
  endif()
endif()

add_library(unity STATIC "${UNITY_DIR}/unity.c")
target_include_directories(unity PUBLIC "${UNITY_DIR}")
target_compile_definitions(unity PUBLIC UNITY_INCLUDE_DOUBLE UNITY_DOUBLE_PRECISION=1e-12)
