# ctest driver: configure, build and test tests/core_only in WORK_DIR. Variables: SOURCE_DIR,
# WORK_DIR, UNITY_WHEEL_DIR, PYTHON (for Unity's wheel), BUILD_TYPE.
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}"
                        "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}" "-DUNITY_WHEEL_DIR=${UNITY_WHEEL_DIR}"
                        "-DPython3_EXECUTABLE=${PYTHON}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the core alone failed (${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}" -j2 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the core does not build without the platform's headers (${rc})")
endif()
execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" --output-on-failure WORKING_DIRECTORY "${WORK_DIR}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the core's unit tests failed without the platform (${rc})")
endif()
