# curio_add_qemu_test(<name> SOURCES <src>... [LIBRARIES <lib>...] [TIMEOUT <s>]
#                     [LINKER_SCRIPT <file.ld>] [ICOUNT] [IMAGE_ONLY])
#
# Builds a bare-metal test image <name>.elf for CURIO_QEMU_BOARD (set by the toolchain file):
#   mps2-an500 (default)  Cortex-M7: startup, semihosting, linker script for QEMU's mps2-an500,
#                         or LINKER_SCRIPT: a board profile's MEMORY regions, e.g.
#                         toolchain/boards/stm32h743_budget.ld
#   zcu102                the ZynqMP's Cortex-A53 in AArch32 (toolchain/arm-none-eabi-zynqmp.cmake):
#                         start-up and linker script from toolchain/boards/zcu102/; LINKER_SCRIPT
#                         (an MCU budget profile) and ICOUNT do not apply there and are ignored
# from the sources, whose `int main()` returns the test status, and registers it with ctest as
# <name>; ctest runs it under CMAKE_CROSSCOMPILING_EMULATOR (the toolchain file's QEMU command),
# with ICOUNT under `-icount shift=0` (one guest instruction = 1 ns of virtual time: SysTick
# then counts instructions, tests/board/instruction_counter.hpp). Print from the test with
# toolchain/qemu/semihosting.h. IMAGE_ONLY: build the image but register no test (an image
# that needs a peer on its UART, run by a script). Only for cross builds (CMAKE_CROSSCOMPILING).
include_guard(GLOBAL)
set(CURIO_QEMU_BOARD mps2-an500 CACHE STRING "QEMU board of the test images (mps2-an500, zcu102)")

# Global (not directory-scoped): the include_guard skips this file in later directories.
set(CURIO_QEMU_DIR ${CMAKE_CURRENT_LIST_DIR} CACHE INTERNAL "QEMU harness folder")

if(NOT TARGET curio_qemu_runtime)
  # cxx_runtime.cpp: operator delete / __cxa_pure_virtual stubs for images with virtual
  # destructors (never called: the images never allocate).
  if(CURIO_QEMU_BOARD STREQUAL "zcu102")
    enable_language(ASM)
    set(board_dir ${CURIO_QEMU_DIR}/../boards/zcu102)
    set(startup ${board_dir}/startup.S ${board_dir}/startup.c)
  else()
    set(startup ${CURIO_QEMU_DIR}/startup.c)
  endif()
  add_library(curio_qemu_runtime OBJECT ${startup} ${CURIO_QEMU_DIR}/semihosting.c
              ${CURIO_QEMU_DIR}/cxx_runtime.cpp)
  target_include_directories(curio_qemu_runtime PUBLIC ${CURIO_QEMU_DIR})
  target_compile_options(curio_qemu_runtime PRIVATE -Wall -Wextra -Werror
                         $<$<COMPILE_LANGUAGE:CXX>:-fno-exceptions -fno-rtti>)
endif()

function(curio_add_qemu_test name)
  cmake_parse_arguments(ARG "ICOUNT;IMAGE_ONLY" "TIMEOUT;LINKER_SCRIPT" "SOURCES;LIBRARIES" ${ARGN})
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
  if(CURIO_QEMU_BOARD STREQUAL "zcu102")
    set(ARG_LINKER_SCRIPT ${CURIO_QEMU_DIR}/../boards/zcu102/zcu102.ld)
    set(ARG_ICOUNT OFF)
  elseif(NOT ARG_LINKER_SCRIPT)
    set(ARG_LINKER_SCRIPT ${CURIO_QEMU_DIR}/mps2-an500.ld)
  endif()
  # -L: the scripts INCLUDE curio_sections.ld from the harness folder.
  target_link_options(${name} PRIVATE -nostartfiles -L${CURIO_QEMU_DIR} -T${ARG_LINKER_SCRIPT}
                      -Wl,-Map=$<TARGET_FILE_DIR:${name}>/${name}.map)
  set_property(TARGET ${name} APPEND PROPERTY LINK_DEPENDS ${ARG_LINKER_SCRIPT}
                                                           ${CURIO_QEMU_DIR}/curio_sections.ld)
  if(ARG_IMAGE_ONLY)
    return()
  endif()
  if(ARG_ICOUNT)
    set(emulator ${CMAKE_CROSSCOMPILING_EMULATOR})
    list(POP_BACK emulator last)  # the emulator command ends in -kernel
    add_test(NAME ${name}
             COMMAND ${emulator} -icount shift=0 ${last} $<TARGET_FILE:${name}>)
  else()
    add_test(NAME ${name} COMMAND ${name})
  endif()
  set_tests_properties(${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS qemu)
endfunction()
