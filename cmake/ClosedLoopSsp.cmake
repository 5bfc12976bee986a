# The closed loop of docs/closed-loop.md as SSP archives, one per FMI version:
# build/ssp/<v>/closed_loop.ssp = scenes/closed_loop/SystemStructure.ssd (written from the OSP
# structure by scripts/osp_to_ssd.py) + resources/ with the four FMUs of build/fmus/<v>.
# Packed with cmake -E tar (no tool beyond CMake at build time).
set(_ssd "${PROJECT_SOURCE_DIR}/scenes/closed_loop/SystemStructure.ssd")
set(_units StewartScene StewartPlatform StewartController StewartPlant)
set(_archives "")
foreach(version 2.0 3.0)
  string(SUBSTRING ${version} 0 1 _major)
  set(_dir "${CMAKE_BINARY_DIR}/ssp/${version}/closed_loop")
  set(_archive "${CMAKE_BINARY_DIR}/ssp/${version}/closed_loop.ssp")
  set(_fmus "")
  set(_targets "")
  foreach(unit ${_units})
    list(APPEND _fmus "${CMAKE_BINARY_DIR}/fmus/${version}/${unit}.fmu")
    list(APPEND _targets ${unit}_fmu${_major})
  endforeach()
  add_custom_command(OUTPUT "${_archive}"
    COMMAND ${CMAKE_COMMAND} -E rm -rf "${_dir}"
    COMMAND ${CMAKE_COMMAND} -E make_directory "${_dir}/resources"
    COMMAND ${CMAKE_COMMAND} -E copy "${_ssd}" "${_dir}/SystemStructure.ssd"
    COMMAND ${CMAKE_COMMAND} -E copy ${_fmus} "${_dir}/resources/"
    COMMAND ${CMAKE_COMMAND} -E chdir "${_dir}"
            ${CMAKE_COMMAND} -E tar cf "${_archive}" --format=zip SystemStructure.ssd resources
    DEPENDS "${_ssd}" ${_fmus} ${_targets}
    COMMENT "Packing ${_archive}")
  list(APPEND _archives "${_archive}")
endforeach()
add_custom_target(closed_loop_ssp ALL DEPENDS ${_archives})
