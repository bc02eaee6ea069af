// The entry point of the AVX2 build of the lane tests: runs them only where
// the processor has AVX2, and otherwise reports a skip (CTest's code 77).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>

int main(int argc, char** argv) {
    if (!__builtin_cpu_supports("avx2")) {
        std::puts("this processor has no AVX2: the eight-lane paths are not tested here");
        return 77;
    }
    return doctest::Context(argc, argv).run();
}
