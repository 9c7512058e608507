// Which instruction set the tracer's SIMD kernels use (the BVH's box tests, single rays and
// packets): chosen once per process at start-up from what the processor has, so that the default
// build runs on any x86-64 and still uses AVX2 where it is present. Every kernel answers every
// query exactly alike (tests/kernel_test.cpp); only the speed differs.
#pragma once

#include "trace/names.h"

#include <string>
#include <string_view>
#include <vector>

namespace glint {

enum class Kernel : unsigned char {
    sse,    // 128-bit: every x86-64 processor has it (the portable kernel)
    avx2,   // 256-bit: an eight-wide node's boxes, or eight rays of a packet, an instruction
    avx512, // 512-bit for packets: a child's box against all 16 rays an instruction; single
            // rays as avx2 (a node is eight boxes wide)
};

template <> struct EnumNames<Kernel> {
    static constexpr auto names = name_table("sse", "avx2", "avx512");
};

// The kernels this processor can run, narrowest first.
std::vector<Kernel> available_kernels();

// The kernel in use: the widest available, unless the environment variable GLINT_KERNEL names
// another (sse, avx2 or avx512). glint's commands refuse a name that is not a kernel, or one the
// processor lacks, before any work (exit 2: app/main.cpp); elsewhere (the test and benchmark
// programs run directly) such a name leaves the widest in use.
Kernel active_kernel();

// What active_kernel() would be for GLINT_KERNEL = `requested` (empty: unset); an error message
// for a name that is not a kernel or one the processor lacks.
struct KernelChoice {
    Kernel kernel;
    std::string problem; // empty when the choice stands
};
KernelChoice choose_kernel(std::string_view requested);

} // namespace glint
