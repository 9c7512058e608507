#include "io/write_file.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace glint {

namespace {

// The temporary file being written, for remove_pending_write (a signal handler reads it).
char pending_[4096];
volatile std::sig_atomic_t pending_set_ = 0;

} // namespace

void remove_pending_write() noexcept {
    if (pending_set_) ::unlink(pending_);
}

void write_file_atomically(const std::filesystem::path& path, const std::string& bytes) {
    const auto fail = [&](const std::string& what) {
        throw std::runtime_error("cannot write " + path.string() + ": " + what);
    };
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
    std::string hidden_name = ".";
    hidden_name += path.filename().string();
    hidden_name += ".XXXXXX";
    std::string temp = (dir / hidden_name).string();
    const int fd = mkstemp(temp.data());
    if (fd < 0) fail(std::strerror(errno));
    if (temp.size() < sizeof pending_) {
        std::memcpy(pending_, temp.c_str(), temp.size() + 1);
        pending_set_ = 1;
    }
    struct Done {
        ~Done() { pending_set_ = 0; }
    } done;
    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const std::string why = std::strerror(errno);
            ::close(fd);
            ::unlink(temp.c_str());
            fail(why);
        }
        written += static_cast<std::size_t>(n);
    }
    // mkstemp creates 0600; give the file the permissions an ordinary new file would get.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    if (::close(fd) != 0 || std::rename(temp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        ::unlink(temp.c_str());
        fail(why);
    }
}

} // namespace glint
