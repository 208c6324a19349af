#include "cli/address_layout.hpp"

#include <cstdlib>

#if defined(__linux__)
#include <sys/personality.h>
#include <unistd.h>
#endif

namespace impactgen::cli
{

void fix_address_layout(char **argv)
{
#if defined(__linux__)
    constexpr const char *guard = "IMPACTGEN_NO_REEXEC";
    if (std::getenv(guard) != nullptr)
        return;
    const int current = personality(0xffffffff); // query only
    if (current == -1 || (current & ADDR_NO_RANDOMIZE) != 0)
        return;
    if (personality(static_cast<unsigned long>(current) | ADDR_NO_RANDOMIZE) == -1)
        return; // not permitted: run with the layout we have
    if (setenv(guard, "1", 1) == 0)
        execv("/proc/self/exe", argv);
    // the exec failed: undo both and run as we are
    unsetenv(guard);
    personality(static_cast<unsigned long>(current));
#else
    (void)argv;
#endif
}

} // namespace impactgen::cli
