// Output files written whole or not at all: a temporary file in the same directory, renamed
// into place, so that a failed or interrupted write never leaves a half-written file.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace glint {

// Writes `bytes` to `path` through a temporary file in the same directory and a rename, so
// that `path` is either untouched or complete. Throws std::runtime_error naming the path.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

// Removes the temporary file of a write in progress, if any: for a signal handler (it only
// calls unlink), when the process is being ended from outside mid-write.
void remove_pending_write() noexcept;

// Writes encode()'s bytes to `path` through write_file_atomically; an encoding failure
// (std::runtime_error) is rethrown naming the path and `format`.
template <class Encode>
void write_encoded(const std::filesystem::path& path, const char* format, const Encode& encode) {
    std::string bytes;
    try {
        bytes = encode();
    } catch (const std::runtime_error& e) {
        throw std::runtime_error("cannot encode " + path.string() + " as " + format + ": " +
                                 e.what());
    }
    write_file_atomically(path, bytes);
}

} // namespace glint
