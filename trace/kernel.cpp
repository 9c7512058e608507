#include "trace/kernel.h"

#include <cstdlib>

namespace glint {
namespace {

bool processor_has(Kernel kernel) {
    switch (kernel) {
    case Kernel::sse:
        return true;
#if defined(__x86_64__) || defined(__i386__)
    case Kernel::avx2:
        return __builtin_cpu_supports("avx2");
    case Kernel::avx512:
        return __builtin_cpu_supports("avx512f");
#else
    default: // no x86: only the portable kernel (SSE's arithmetic, lane by lane)
        return false;
#endif
    }
    return false;
}

Kernel from_environment() {
    const char* requested = std::getenv("GLINT_KERNEL");
    return choose_kernel(requested ? requested : "").kernel;
}

// Read once, on first use: the choice holds for the process.
Kernel active() {
    static const Kernel kernel = from_environment();
    return kernel;
}

} // namespace

std::vector<Kernel> available_kernels() {
    std::vector<Kernel> kernels;
    for (const Kernel k : all_values<Kernel>())
        if (processor_has(k)) kernels.push_back(k);
    return kernels;
}

KernelChoice choose_kernel(std::string_view requested) {
    const Kernel widest = available_kernels().back();
    if (requested.empty()) return {widest, {}};
    const std::optional<Kernel> named = from_name<Kernel>(requested);
    if (!named) {
        std::string names;
        for (const std::string& name : all_names<Kernel>())
            names += (names.empty() ? "" : ", ") + name;
        return {widest, "is not a kernel (" + names + ")"};
    }
    if (!processor_has(*named)) return {widest, "is not supported by this processor"};
    return {*named, {}};
}

Kernel active_kernel() {
    return active();
}

} // namespace glint
