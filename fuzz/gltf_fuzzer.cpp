// libFuzzer target: any bytes as a glTF or GLB model (io/gltf_loader.h), checked as every
// loader is (fuzz/render_check.h): a model that loads is rendered. No file beside it can be read
// (an external buffer or image is refused, as a missing one is). Its seeds are written by
// tests/gltf_seeds.cpp from tests/gltf_builder.h (the fuzz.gltf_seeds test), not downloaded.
#include "fuzz/render_check.h"
#include "io/gltf_loader.h"

namespace {

glint::Scene gltf_scene(const std::string& input, const std::string& name) {
    return glint::parse_gltf(input, name, [](const std::string&, std::string& why) {
        why = "the fuzzer reads no files";
        return std::optional<std::string>();
    });
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::check_loader(data, size, "fuzz.gltf", gltf_scene);
}
