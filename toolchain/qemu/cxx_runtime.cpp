// The little C++ runtime a bare-metal test image needs without libstdc++ (images link with
// arm-none-eabi-gcc): classes with virtual destructors (hal::CanBus, hal::Clock) make the
// compiler emit deleting destructors that reference operator delete, although nothing is ever
// allocated or deleted; a pure virtual call cannot happen in a correct program. All of them
// end the test loudly if they are ever reached.
#include <cstddef>

#include "toolchain/qemu/semihosting.h"

namespace {
[[noreturn]] void unexpected(const char* what) {
  curio_semihost_print("FAULT: ");
  curio_semihost_print(what);
  curio_semihost_print(" called in a heap-free image\n");
  curio_semihost_exit(4);
}
}  // namespace

void operator delete(void*) noexcept { unexpected("operator delete"); }
void operator delete(void*, std::size_t) noexcept { unexpected("operator delete"); }

extern "C" void __cxa_pure_virtual() { unexpected("pure virtual function"); }
