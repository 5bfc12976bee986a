# stewart_fmu(): builds a model folder on the FMU runtime (fmu/runtime) into its .fmu files.
# Included by fmu/CMakeLists.txt and by tests that build a model of their own; defines the
# function and the fmi_headers target once.
include_guard(GLOBAL)

if(NOT FMI_HEADERS_DIR)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  execute_process(
    COMMAND "${Python3_EXECUTABLE}" -c "import fmpy, os; print(os.path.dirname(fmpy.__file__))"
    OUTPUT_VARIABLE _fmpy_dir OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _rc ERROR_QUIET)
  if(NOT _rc EQUAL 0 OR NOT _fmpy_dir)
    message(FATAL_ERROR "fmpy is not importable by ${Python3_EXECUTABLE}: install it or set "
                        "FMI_HEADERS_DIR to a directory with fmi2Functions.h and fmi3Functions.h")
  endif()
  set(FMI_HEADERS_DIR "${_fmpy_dir}/c-code" CACHE PATH
      "Directory with the FMI 2.0 and 3.0 C headers (default: fmpy's c-code)")
endif()
foreach(_h fmi2Functions.h fmi2FunctionTypes.h fmi2TypesPlatform.h fmi3Functions.h
           fmi3FunctionTypes.h fmi3PlatformTypes.h)
  if(NOT EXISTS "${FMI_HEADERS_DIR}/${_h}")
    message(FATAL_ERROR "FMI_HEADERS_DIR=${FMI_HEADERS_DIR} has no ${_h}")
  endif()
endforeach()
# The FMI headers as a target, for the layers and for importers (tests/importer).
add_library(fmi_headers INTERFACE)
target_include_directories(fmi_headers INTERFACE "${FMI_HEADERS_DIR}")

# stewart_fmu(<NAME> <MODEL_DIR> [LIBRARIES <libs>...] [OUTPUT_DIR <dir>])
# Builds the model in MODEL_DIR (config.h with FMU_MODEL_IDENTIFIER = "<NAME>", variables.def, and
# every *.c there) on the runtime into:
#   <NAME>_table    static: the variable table (variables.c), for importers and tests
#   <NAME>_model    static: runtime + model + table, linked with LIBRARIES (default: stewart);
#                   the one place the FMU sources are compiled (the .so files, the fuzz targets)
#   <NAME>_fmi2_layer, <NAME>_fmi3_layer   object libraries: the FMI 2 / FMI 3 translations
#   <NAME>_fmi2, <NAME>_fmi3               the shared objects (fmu/<NAME>/fmi<v>/<NAME>.so)
#   <NAME>_fmu2, <NAME>_fmu3               the packed .fmu files (OUTPUT_DIR/<v>.0/<NAME>.fmu,
#                                          OUTPUT_DIR defaults to build/fmus)
#   fmu/<NAME>/modelDescription2.xml, modelDescription3.xml   generated from variables.def
function(stewart_fmu name model_dir)
  cmake_parse_arguments(PARSE_ARGV 2 FMU "" "OUTPUT_DIR" "LIBRARIES")
  if(NOT FMU_LIBRARIES)
    set(FMU_LIBRARIES stewart)
  endif()
  if(NOT FMU_OUTPUT_DIR)
    set(FMU_OUTPUT_DIR "${CMAKE_BINARY_DIR}/fmus")
  endif()
  set(FMU_RUNTIME_DIR "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/runtime")
  set(_fmu_warnings -Wall -Wextra -Werror=override-init -Werror=implicit-function-declaration)
  get_filename_component(model_dir "${model_dir}" ABSOLUTE)
  file(GLOB model_sources CONFIGURE_DEPENDS "${model_dir}/*.c")
  set(out "${CMAKE_BINARY_DIR}/fmu/${name}")
  file(RELATIVE_PATH def_path "${PROJECT_SOURCE_DIR}" "${model_dir}/variables.def")

  add_library(${name}_table STATIC "${FMU_RUNTIME_DIR}/variables.c")
  target_include_directories(${name}_table PUBLIC "${FMU_RUNTIME_DIR}" "${model_dir}")
  target_link_libraries(${name}_table PUBLIC ${FMU_LIBRARIES})  # config.h includes its headers
  target_compile_options(${name}_table PRIVATE ${_fmu_warnings})
  set_property(TARGET ${name}_table APPEND PROPERTY OBJECT_DEPENDS "${model_dir}/variables.def")

  add_library(${name}_model STATIC
    "${FMU_RUNTIME_DIR}/instance.c" "${FMU_RUNTIME_DIR}/do_step.c" "${FMU_RUNTIME_DIR}/call_table.c"
    "${FMU_RUNTIME_DIR}/logging.c" "${FMU_RUNTIME_DIR}/values.c" "${FMU_RUNTIME_DIR}/state.c"
    "${FMU_RUNTIME_DIR}/model_exchange.c" "${FMU_RUNTIME_DIR}/derivatives.c"
    "${FMU_RUNTIME_DIR}/bindings.c"
    ${model_sources})
  target_link_libraries(${name}_model PUBLIC ${name}_table ${FMU_LIBRARIES} m)
  target_compile_options(${name}_model PRIVATE ${_fmu_warnings})
  set_property(TARGET ${name}_model APPEND PROPERTY OBJECT_DEPENDS "${model_dir}/variables.def")

  foreach(version 2 3)
    add_library(${name}_fmi${version}_layer OBJECT "${FMU_RUNTIME_DIR}/fmi${version}_functions.c"
                "${FMU_RUNTIME_DIR}/fmi${version}_me_functions.c")
    target_link_libraries(${name}_fmi${version}_layer PUBLIC ${name}_model fmi_headers)
    target_compile_options(${name}_fmi${version}_layer PRIVATE ${_fmu_warnings})
  endforeach()

  # Both model descriptions, from the model's variable table and start values.
  add_executable(${name}_gen_model_description "${FMU_RUNTIME_DIR}/gen_model_description.c")
  target_link_libraries(${name}_gen_model_description PRIVATE ${name}_model)
  target_compile_definitions(${name}_gen_model_description PRIVATE
    "FMU_VARIABLES_SOURCE=\"${def_path}\"")
  target_compile_options(${name}_gen_model_description PRIVATE ${_fmu_warnings})
  set_target_properties(${name}_gen_model_description PROPERTIES LINKER_LANGUAGE CXX)
  add_custom_command(OUTPUT "${out}/modelDescription2.xml" "${out}/modelDescription3.xml"
    COMMAND ${name}_gen_model_description 2 "${out}/modelDescription2.xml"
    COMMAND ${name}_gen_model_description 3 "${out}/modelDescription3.xml"
    DEPENDS ${name}_gen_model_description "${model_dir}/variables.def"
    COMMENT "Generating the FMI 2.0 and 3.0 model descriptions of ${name} from ${def_path}")

  foreach(version 2 3)
    if(version EQUAL 2)
      set(platform linux64)
    else()
      set(platform x86_64-linux)
    endif()
    set(tgt ${name}_fmi${version})
    add_library(${tgt} SHARED $<TARGET_OBJECTS:${name}_fmi${version}_layer>)
    target_link_libraries(${tgt} PRIVATE ${name}_model)
    set_target_properties(${tgt} PROPERTIES
      OUTPUT_NAME ${name}
      PREFIX ""
      LINKER_LANGUAGE CXX
      LIBRARY_OUTPUT_DIRECTORY "${out}/fmi${version}")
    target_link_options(${tgt} PRIVATE
      "-Wl,--version-script=${FMU_RUNTIME_DIR}/version.map"
      -Wl,--exclude-libs,ALL -Wl,--no-undefined -Wl,--as-needed)
    set_property(TARGET ${tgt} APPEND PROPERTY LINK_DEPENDS "${FMU_RUNTIME_DIR}/version.map")

    set(stage "${out}/stage${version}")
    set(fmu "${FMU_OUTPUT_DIR}/${version}.0/${name}.fmu")
    add_custom_command(OUTPUT "${fmu}"
      COMMAND ${CMAKE_COMMAND} -E rm -rf "${stage}"
      COMMAND ${CMAKE_COMMAND} -E make_directory "${stage}/binaries/${platform}" "${FMU_OUTPUT_DIR}/${version}.0"
      COMMAND ${CMAKE_COMMAND} -E copy "${out}/modelDescription${version}.xml"
              "${stage}/modelDescription.xml"
      COMMAND ${CMAKE_COMMAND} -E copy "$<TARGET_FILE:${tgt}>" "${stage}/binaries/${platform}/${name}.so"
      COMMAND ${CMAKE_COMMAND} -E rm -f "${fmu}"
      COMMAND ${CMAKE_COMMAND} -E chdir "${stage}"
              ${CMAKE_COMMAND} -E tar cf "${fmu}" --format=zip modelDescription.xml binaries
      DEPENDS ${tgt} "${out}/modelDescription${version}.xml"
      COMMENT "Packing ${fmu}")
    add_custom_target(${name}_fmu${version} ALL DEPENDS "${fmu}")
  endforeach()
endfunction()

