# CMake toolchain file: bare-metal Cortex-M7 (hard float, FPv5-D16) with arm-none-eabi-gcc
# and newlib-nano. Use with -DCURIO_FIRMWARE_ONLY=ON (see toolchain/build-cortex-m7.sh).
# Executables link with arm-none-eabi-gcc, not g++: the firmware needs no libstdc++ runtime
# (no exceptions, RTTI, heap or iostreams), and Debian's libstdc++-arm-none-eabi-newlib is
# not required. Tests run under QEMU (-M mps2-an500) through CMAKE_CROSSCOMPILING_EMULATOR.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR cortex-m7)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
set(CMAKE_SIZE arm-none-eabi-size)
# The compiler checks cannot link without a startup file and linker script.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CURIO_CORTEX_M7_ARCH_FLAGS "-mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-d16")
set(CMAKE_C_FLAGS_INIT "${CURIO_CORTEX_M7_ARCH_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT
    "${CURIO_CORTEX_M7_ARCH_FLAGS} -fno-exceptions -fno-rtti -fno-threadsafe-statics -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${CURIO_CORTEX_M7_ARCH_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "--specs=nano.specs -Wl,--gc-sections")
set(CMAKE_CXX_LINK_EXECUTABLE
    "<CMAKE_C_COMPILER> <FLAGS> <CMAKE_CXX_LINK_FLAGS> <LINK_FLAGS> <OBJECTS> -o <TARGET> <LINK_LIBRARIES>")

# Never pick up host libraries or headers.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# ctest runs each test ELF as: qemu-system-arm ... -kernel <elf>. Semihosting carries the
# output and the exit status (SYS_EXIT_EXTENDED); -M mps2-an500 is a Cortex-M7 with FPU.
find_program(CURIO_QEMU_SYSTEM_ARM qemu-system-arm)
if(CURIO_QEMU_SYSTEM_ARM)
  set(CMAKE_CROSSCOMPILING_EMULATOR
      ${CURIO_QEMU_SYSTEM_ARM} -M mps2-an500 -nographic -monitor none -serial none
      -semihosting-config enable=on,target=native -kernel)
endif()
