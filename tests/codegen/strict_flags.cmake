# The warnings the generated headers are compiled under by check_compile.cmake and
# check_self_contained.cmake.
set(IMPACTGEN_STRICT_FLAGS -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror)
