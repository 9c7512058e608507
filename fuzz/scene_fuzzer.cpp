// libFuzzer target: any bytes as a JSON scene (io/json_loader.h), checked as every loader is
// (fuzz/render_check.h).
#include "fuzz/render_check.h"

#include "io/json_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::check_loader(data, size, "fuzz.json", glint::parse_scene);
}
