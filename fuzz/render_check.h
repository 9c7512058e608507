// What every loader's fuzz target checks (fuzz/*_fuzzer.cpp): a bad input must end in a
// SceneError whose message starts with the file's name; an input that loads must render (shrunk
// to a thumbnail) without crashing or hanging, and to the same image with every acceleration
// structure, which all answer the same queries bit for bit (tests/accel_test.cpp), and with its
// reflected and transmitted rays cast ahead in packets (RenderSettings::packet_levels).
#pragma once

#include "io/error.h"
#include "trace/accel/accel.h"
#include "trace/render.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace glint::fuzz {

// `parse(text, name)` is the loader under test.
template <class Parse>
int check_loader(const std::uint8_t* data, std::size_t size, const std::string& name, Parse parse) {
    Scene scene;
    try {
        scene = parse(std::string(reinterpret_cast<const char*>(data), size), name);
    } catch (const SceneError& e) {
        if (!std::string_view(e.what()).starts_with(name + ":")) {
            std::fprintf(stderr, "error message does not name the file: %s\n", e.what());
            std::abort();
        }
        return 0;
    }
    // A thumbnail: the image size is not what is being fuzzed, and every pixel costs time.
    scene.camera.width = std::min(scene.camera.width, 12);
    scene.camera.height = std::min(scene.camera.height, 9);

    tbb::task_arena one_thread(1);
    one_thread.execute([&] {
        Image first;
        for (const std::string_view accel : EnumNames<AccelKind>::names) {
            const World world(scene, from_name<AccelKind>(accel));
            const Image image = render(world).bytes();
            if (accel == EnumNames<AccelKind>::names[0]) {
                first = image;
            } else if (image.rgb != first.rgb) {
                std::fprintf(stderr, "%s renders a different image from %s\n",
                             std::string(accel).c_str(),
                             std::string(EnumNames<AccelKind>::names[0]).c_str());
                std::abort();
            }
        }
        scene.render.packet_levels = 3;
        if (render(World(scene, AccelKind::bvh)).bytes().rgb != first.rgb) {
            std::fprintf(stderr, "--packet-levels 3 renders a different image\n");
            std::abort();
        }
    });
    return 0;
}

} // namespace glint::fuzz
