// atomic_file.cpp: temporary file, fsync, rename (POSIX).
#include "jostle/core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>

#include "jostle/core/error.h"
#include "jostle/core/interrupt.h"

namespace jostle {

namespace {

// What the target is now. A regular file (or nothing yet) is replaced by the renamed
// temporary file. Anything else is written in place, or the rename would put a regular file
// where it was: a device, FIFO or socket (/dev/null, a named pipe), and every path under /dev
// or /proc, whose links (/dev/stdout, /proc/self/fd/1) stand for a descriptor of this process
// even when it is a regular file (replacing that file by name would leave the descriptor, and
// the rest of the output, on the old one).
enum class Target { replaceable, folder, stream };

Target target_of(const std::string& path, std::string& resolved) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return Target::replaceable;  // no such file yet (or unreadable: creating says)
    const bool is_link = S_ISLNK(st.st_mode);
    if (is_link && ::stat(path.c_str(), &st) != 0) return Target::replaceable;  // a dangling link: replaced, as before
    if (S_ISDIR(st.st_mode)) return Target::folder;
    if (path.starts_with("/dev/") || path.starts_with("/proc/") || !S_ISREG(st.st_mode)) return Target::stream;
    if (is_link) {
        // A link to a regular file: the file is replaced and the link stays a link.
        char* real = ::realpath(path.c_str(), nullptr);
        if (real == nullptr) return Target::stream;
        resolved = real;
        std::free(real);
    }
    return Target::replaceable;
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    std::string resolved;
    switch (target_of(path_, resolved)) {
        case Target::folder:
            fail("it is a folder");
        case Target::stream: {
            const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
            if (fd < 0) {
                const int e = errno;
                // Ctrl-C while a named pipe waited for its reader: the run was stopped, not the
                // output refused.
                if (e == EINTR) throw_if_interrupted();
                fail(std::strerror(e));
            }
            file_ = ::fdopen(fd, "wb");
            if (file_ == nullptr) {
                const int e = errno;
                ::close(fd);
                fail(std::strerror(e));
            }
            stream_ = true;
            return;
        }
        case Target::replaceable:
            break;
    }
    // (The link's target, when the path is a link to a regular file.)
    const std::string& place = resolved.empty() ? path_ : resolved;
    rename_to_ = place;
    const std::string prefix = place + "." + std::to_string(::getpid()) + ".";
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = prefix + std::to_string(attempt) + ".tmp";
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            const int e = errno;
            // The temporary file's name (pid, attempt) is no business of the message: say where.
            const std::size_t slash = place.rfind('/');
            const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : place.substr(0, slash);
            fail("cannot create a file in " + folder + ": " + std::strerror(e));
        }
        temp_path_ = std::move(name);
        file_ = ::fdopen(fd, "wb");
        if (file_ == nullptr) {
            const int e = errno;
            ::close(fd);
            ::unlink(temp_path_.c_str());
            temp_path_.clear();
            fail(std::strerror(e));
        }
        return;
    }
    fail("100 temporary files " + prefix + "*.tmp already exist");
}

AtomicFile::~AtomicFile() {
    if (file_ != nullptr) std::fclose(file_);
    if (!committed_ && !temp_path_.empty()) ::unlink(temp_path_.c_str());
}

void AtomicFile::fail(const std::string& what) const {
    throw InputError(SourceLocation{path_, 0, 0}, "cannot write: " + what);
}

void AtomicFile::write(const void* data, std::size_t size) {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::write after commit");
    if (size != 0 && std::fwrite(data, 1, size, file_) != size) {
        const int e = errno;
        fail(std::strerror(e));
    }
}

// A file patched after it is written (an animation's frame count) needs a seekable target.
[[noreturn]] void AtomicFile::fail_seek(int e) const {
    if (e == ESPIPE) fail("a pipe cannot take this file (its header is patched once the rest is written): give a file path");
    fail(std::strerror(e));
}

std::int64_t AtomicFile::tell() {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::tell after commit");
    const long at = std::ftell(file_);
    if (at < 0) fail_seek(errno);
    return at;
}

void AtomicFile::seek(std::int64_t offset) {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::seek after commit");
    if (std::fseek(file_, static_cast<long>(offset), SEEK_SET) != 0) fail_seek(errno);
}

void AtomicFile::flush() {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::flush after commit");
    if (std::fflush(file_) != 0) {
        const int e = errno;
        fail(std::strerror(e));
    }
}

void AtomicFile::commit() {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::commit twice");
    if (stream_) {
        // Written in place: every byte must have gone (a full device says so here).
        const int flushed = std::fflush(file_);
        const int e = errno;
        const int closed = std::fclose(file_);
        file_ = nullptr;
        if (flushed != 0 || closed != 0) fail(std::strerror(flushed != 0 ? e : errno));
        committed_ = true;
        return;
    }
    // Flush to the disk before the rename, so the name never points at data still in flight.
    if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0) {
        const int e = errno;
        fail(std::strerror(e));
    }
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) {
        const int e = errno;
        fail(std::strerror(e));
    }
    if (std::rename(temp_path_.c_str(), rename_to_.c_str()) != 0) {
        const int e = errno;
        fail(e == EISDIR ? std::string("it is a folder") : "cannot put the finished file in its place: " + std::string(std::strerror(e)));
    }
    committed_ = true;
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
    AtomicFile file(path);
    file.write(bytes);
    file.commit();
}

void check_writable(const std::string& path) {
    std::string resolved;
    if (target_of(path, resolved) == Target::stream) return;
    const AtomicFile probe(path);
}

bool same_file(const std::string& output, const std::string& other) {
    if (output.empty() || other.empty()) return false;
    struct stat a {};
    struct stat b {};
    const bool a_exists = ::stat(output.c_str(), &a) == 0;
    const bool b_exists = ::stat(other.c_str(), &b) == 0;
    if (a_exists && b_exists) return S_ISREG(a.st_mode) && S_ISREG(b.st_mode) && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
    if (a_exists || b_exists) return false;
    std::error_code ex, ey;
    const std::filesystem::path x = std::filesystem::absolute(output, ex).lexically_normal();
    const std::filesystem::path y = std::filesystem::absolute(other, ey).lexically_normal();
    return !ex && !ey && x == y;
}

}  // namespace jostle
