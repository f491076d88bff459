# CMake toolchain file: bare-metal AArch32 (ARMv8-A, VFP) on a Cortex-A53 of the Xilinx ZynqMP
# (QEMU 7.2's xlnx-zcu102), with arm-none-eabi-gcc and newlib-nano. Use with
# -DCURIO_FIRMWARE_ONLY=ON (the `zynqmp` preset). Why an A53 and not the Cortex-R5F the chip
# also has: QEMU 7.2 never releases the R5F from reset and wires no interrupt to it
# (docs/deploy.md, "The ZynqMP board"). The image starts in AArch64 EL3; a six-instruction
# stub (toolchain/boards/zcu102/startup.S) drops to AArch32 Secure SVC, where the firmware runs.
#   -mno-unaligned-access: with the MMU off every data access is Device memory, where an
#   unaligned access faults on the hardware (QEMU 7.2 does not check; the chip does).
#   -mfpu=fp-armv8: scalar VFP only. AArch32 Advanced SIMD flushes denormals to zero, and the
#   firmware's floats must stay bit-identical to the host's.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR cortex-a53)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
set(CMAKE_SIZE arm-none-eabi-size)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CURIO_ZYNQMP_ARCH_FLAGS
    "-mcpu=cortex-a53 -mthumb -mfloat-abi=hard -mfpu=fp-armv8 -mno-unaligned-access")
set(CMAKE_C_FLAGS_INIT "${CURIO_ZYNQMP_ARCH_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT
    "${CURIO_ZYNQMP_ARCH_FLAGS} -fno-exceptions -fno-rtti -fno-threadsafe-statics -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${CURIO_ZYNQMP_ARCH_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "--specs=nano.specs -Wl,--gc-sections")
set(CMAKE_CXX_LINK_EXECUTABLE
    "<CMAKE_C_COMPILER> <FLAGS> <CMAKE_CXX_LINK_FLAGS> <LINK_FLAGS> <OBJECTS> -o <TARGET> <LINK_LIBRARIES>")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The board the QEMU harness (toolchain/qemu/curio_qemu_test.cmake) builds test images for.
set(CURIO_QEMU_BOARD zcu102 CACHE STRING "QEMU board of the test images")
# ctest runs each test ELF through the board's launcher (semihosting carries the output and
# the exit status; UART0 goes to stdout).
set(CMAKE_CROSSCOMPILING_EMULATOR ${CMAKE_CURRENT_LIST_DIR}/boards/zcu102/run-zcu102.sh)
