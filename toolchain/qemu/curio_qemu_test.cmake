# curio_add_qemu_test(<name> SOURCES <src>... [LIBRARIES <lib>...] [TIMEOUT <s>] [IMAGE_ONLY])
#
# Builds a bare-metal Cortex-M7 test image <name>.elf (startup, semihosting, linker script
# for QEMU's mps2-an500) from the sources, whose `int main()` returns the test status, and
# registers it with ctest as <name>; ctest runs it under CMAKE_CROSSCOMPILING_EMULATOR
# (qemu-system-arm, set by toolchain/arm-none-eabi-cortex-m7.cmake). Print from the test with
# toolchain/qemu/semihosting.h. IMAGE_ONLY: build the image but register no test (an image
# that needs a peer on its UART, run by a script). Only for cross builds (CMAKE_CROSSCOMPILING).
include_guard(GLOBAL)

# Global (not directory-scoped): the include_guard skips this file in later directories.
set(CURIO_QEMU_DIR ${CMAKE_CURRENT_LIST_DIR} CACHE INTERNAL "QEMU harness folder")

if(NOT TARGET curio_qemu_runtime)
  # cxx_runtime.cpp: operator delete / __cxa_pure_virtual stubs for images with virtual
  # destructors (never called: the images never allocate).
  add_library(curio_qemu_runtime OBJECT ${CURIO_QEMU_DIR}/startup.c ${CURIO_QEMU_DIR}/semihosting.c
              ${CURIO_QEMU_DIR}/cxx_runtime.cpp)
  target_include_directories(curio_qemu_runtime PUBLIC ${CURIO_QEMU_DIR})
  target_compile_options(curio_qemu_runtime PRIVATE -Wall -Wextra -Werror
                         $<$<COMPILE_LANGUAGE:CXX>:-fno-exceptions -fno-rtti>)
endif()

function(curio_add_qemu_test name)
  cmake_parse_arguments(ARG "IMAGE_ONLY" "TIMEOUT" "SOURCES;LIBRARIES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "curio_add_qemu_test(${name}): no SOURCES")
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 60)
  endif()
  add_executable(${name} ${ARG_SOURCES} $<TARGET_OBJECTS:curio_qemu_runtime>)
  set_target_properties(${name} PROPERTIES SUFFIX .elf)
  target_include_directories(${name} PRIVATE ${CURIO_QEMU_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_LIBRARIES} m)
  target_link_options(${name} PRIVATE -nostartfiles -T${CURIO_QEMU_DIR}/mps2-an500.ld
                      -Wl,-Map=$<TARGET_FILE_DIR:${name}>/${name}.map)
  set_property(TARGET ${name} APPEND PROPERTY LINK_DEPENDS ${CURIO_QEMU_DIR}/mps2-an500.ld)
  if(ARG_IMAGE_ONLY)
    return()
  endif()
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS qemu)
endfunction()
