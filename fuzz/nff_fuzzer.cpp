// libFuzzer target: any bytes as an NFF scene (io/nff_loader.h), checked as every loader is
// (fuzz/render_check.h). Seeds: small SPD scenes and the heads of two larger ones.
#include "fuzz/render_check.h"

#include "io/nff_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::check_loader(data, size, "fuzz.nff", glint::parse_nff);
}
