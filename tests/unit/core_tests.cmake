# The core's unit tests. They see the core's headers only (mbs/mbs.h, and csrc/ for the white-box
# test's "core/..." headers), never the platform's: included by tests/CMakeLists.txt and by the
# stand-alone project tests/core_only, which has no platform at all.
set(_core_test_dir ${CMAKE_CURRENT_LIST_DIR})

# Every joint type against finite differences; bad input named.
add_executable(test_joints ${_core_test_dir}/test_joints.c)
target_link_libraries(test_joints PRIVATE mbs unity m)
set_target_properties(test_joints PROPERTIES LINKER_LANGUAGE CXX)
add_test(NAME test_joints COMMAND test_joints)

# White-box test of the bordered-block linear solver (C++, internal headers).
add_executable(test_block_solver ${_core_test_dir}/test_block_solver.cpp)
target_link_libraries(test_block_solver PRIVATE mbs unity Eigen3::Eigen)
target_include_directories(test_block_solver PRIVATE ${_core_test_dir}/../../csrc)
add_test(NAME test_block_solver COMMAND test_block_solver)
