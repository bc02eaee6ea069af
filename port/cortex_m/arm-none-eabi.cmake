# CMake toolchain file: Cortex-M4F with single-precision FPU, bare metal,
# Debian's gcc-arm-none-eabi + libnewlib-arm-none-eabi + libstdc++-arm-none-eabi-newlib.
#   cmake -S port/firmware -B build/firmware -DCMAKE_TOOLCHAIN_FILE=port/cortex_m/arm-none-eabi.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
find_program(CMAKE_OBJCOPY arm-none-eabi-objcopy)
find_program(CMAKE_SIZE arm-none-eabi-size)
find_program(ACTIONSTRING_ARM_NM arm-none-eabi-nm)

# Compiler checks link a program; there is no start-up code until ours.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(ACTIONSTRING_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
set(CMAKE_C_FLAGS_INIT "${ACTIONSTRING_CPU_FLAGS} -ffunction-sections -fdata-sections")
# -ffp-contract=off: no fused multiply-add, so floats round as on the host.
set(CMAKE_CXX_FLAGS_INIT "${ACTIONSTRING_CPU_FLAGS} -ffunction-sections -fdata-sections -ffp-contract=off -fno-math-errno -fno-exceptions -fno-rtti -fno-threadsafe-statics -fno-use-cxa-atexit")
set(CMAKE_ASM_FLAGS_INIT "${ACTIONSTRING_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${ACTIONSTRING_CPU_FLAGS} -nostartfiles -Wl,--gc-sections")

# Header-only dependencies (Eigen) come from the host's include folders.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
