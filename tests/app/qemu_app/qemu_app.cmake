# The controller scenario's libraries (tests/app/qemu_app/controller_run.hpp), for the
# Cortex-M7 image (firmware/app/CMakeLists.txt, cross builds) and its host twin
# (tests/app/qemu_app/CMakeLists.txt): the exploration core and the controller compiled
# with a small archive (CURIO_ARCHIVE_CAPACITY must be the same in every translation unit that
# shares an Archive, so the controller is rebuilt with it too).
#   curio_explore_qapp  firmware/explore, capacity 128 (20 + 50 episodes)
#   curio_app_qapp      firmware/app controller (CURIO_APP_SOURCES), joint-target quantization
#                       and episode outcome on top of it
include_guard(DIRECTORY)
set(CURIO_QAPP_CAPACITY 128)
set(CURIO_QAPP_DIR ${CMAKE_CURRENT_LIST_DIR})

function(curio_qapp_libraries)
  if(TARGET curio_app_qapp)
    return()
  endif()
  curio_explore_library(curio_explore_qapp CAPACITY ${CURIO_QAPP_CAPACITY})
  # libm after every library that calls it: images link with arm-none-eabi-gcc, which
  # resolves in command-line order.
  target_link_libraries(curio_explore_qapp PUBLIC m)
  set(app_dir ${PROJECT_SOURCE_DIR}/firmware/app)
  get_property(app_sources GLOBAL PROPERTY CURIO_APP_SOURCES)
  add_library(curio_app_qapp STATIC ${app_sources} ${app_dir}/joint_target.cpp
                                    ${app_dir}/episode_outcome.cpp)
  target_compile_options(curio_app_qapp PRIVATE ${CURIO_FIRMWARE_FLAGS})
  target_link_libraries(curio_app_qapp PUBLIC curio_explore_qapp curio_protocol curio_nn curio_journal m
                        PRIVATE curio_warnings)
endfunction()
