// A libFuzzer target with planted faults, for fuzz.replay.self-test only (fuzz/replay-self-test):
// an input that begins "planted-crash" reads past its heap buffer (AddressSanitizer stops the
// run), one that begins "planted-hang" never returns, and one that begins "planted-leak" leaks.
// Any other input passes.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    if (input.starts_with("planted-crash")) {
        char* copy = new char[size];
        std::memcpy(copy, data, size);
        volatile char past_the_end = copy[size];
        (void)past_the_end;
        delete[] copy;
    } else if (input.starts_with("planted-hang")) {
        volatile bool forever = true;
        while (forever) {
        }
    } else if (input.starts_with("planted-leak")) {
        static char* volatile leaked;
        leaked = new char[64];
        leaked = nullptr;
    }
    return 0;
}
