// atomic_file.cpp: temporary file, fsync, rename (POSIX).
#include "jostle/core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
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

// The descriptor that `path`, spelt out, names (/dev/stdout, /dev/fd/N, /proc/self/fd/N,
// /proc/<our pid>/fd/N), else -1.
int descriptor_named(const std::filesystem::path& path) {
    const std::string p = path.lexically_normal().string();
    if (p == "/dev/stdin") return 0;
    if (p == "/dev/stdout") return 1;
    if (p == "/dev/stderr") return 2;
    std::string_view number;
    const std::string own = "/proc/" + std::to_string(::getpid());
    for (const std::string& folder : {std::string("/dev/fd/"), std::string("/proc/self/fd/"), std::string("/proc/thread-self/fd/"),
                                      own + "/fd/"}) {
        if (p.starts_with(folder)) number = std::string_view(p).substr(folder.size());
    }
    // A thread's folder, /proc/<pid>/task/<tid>/fd/N (what /proc/thread-self/fd spells out to):
    // threads share their process's descriptors.
    if (const std::string task = own + "/task/"; number.empty() && p.starts_with(task)) {
        const std::string_view rest = std::string_view(p).substr(task.size());
        const std::size_t slash = rest.find('/');
        if (slash != std::string_view::npos && slash > 0 && rest.substr(0, slash).find_first_not_of("0123456789") == std::string_view::npos &&
            rest.substr(slash).starts_with("/fd/")) {
            number = rest.substr(slash + 4);
        }
    }
    if (number.empty() || number.size() > 9 || number.find_first_not_of("0123456789") != std::string_view::npos) return -1;
    return std::stoi(std::string(number));
}

// The descriptor of this process that `path` stands for, else -1: one of the names above, or
// a link to one (out.scn -> /dev/stdout), or a name in a folder that is one (a link to /dev).
// Opening such a path again would make a new open file: at offset 0 of a redirected stdout
// (overwriting what is there and what the program prints next), and without its O_APPEND
// (`>>`). The links are followed one at a time: the last one, /proc/self/fd/N, names the
// descriptor's file, which is what must not be opened.
int own_descriptor(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path p = fs::absolute(path, ec);
    if (ec) return -1;
    for (int hop = 0; hop < 40; ++hop) {  // 40: the kernel's own limit on links in a path
        if (const int fd = descriptor_named(p); fd >= 0) return fd;
        // The folder spelt out without links ("/dev/fd" is "/proc/<pid>/fd"), the name kept.
        const fs::path folder = fs::canonical(p.parent_path(), ec);
        if (ec) return -1;
        p = folder / p.filename();
        if (const int fd = descriptor_named(p); fd >= 0) return fd;
        if (!fs::is_symlink(fs::symlink_status(p, ec)) || ec) return -1;
        const fs::path target = fs::read_symlink(p, ec);
        if (ec) return -1;
        p = target.is_absolute() ? target : folder / target;
    }
    return -1;
}

// Sends what the program has printed to descriptor fd so far (std::cout's buffer and C's),
// so that bytes written to it directly come after them.
void flush_printed(int fd) {
    if (fd == 1) {
        std::cout.flush();
        std::fflush(stdout);
    } else if (fd == 2) {
        std::clog.flush();
        std::cerr.flush();
        std::fflush(stderr);
    }
}

// Why descriptor fd cannot be written, or "" when it can.
std::string unwritable_descriptor(int fd) {
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags < 0) return "descriptor " + std::to_string(fd) + " is not open";
    if ((flags & O_ACCMODE) == O_RDONLY) return "descriptor " + std::to_string(fd) + " is open for reading only";
    return "";
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    if (const int fd = own_descriptor(path_); fd >= 0) {
        // Written through a copy of the descriptor itself, sharing its offset and O_APPEND,
        // unbuffered and after what was printed to it: the bytes land where the program's
        // own output to it would, in the order the program made them.
        if (const std::string why = unwritable_descriptor(fd); !why.empty()) fail(why);
        const int copy = ::fcntl(fd, F_DUPFD_CLOEXEC, 3);
        if (copy < 0) fail(std::strerror(errno));
        file_ = ::fdopen(copy, "wb");
        if (file_ == nullptr) {
            const int e = errno;
            ::close(copy);
            fail(std::strerror(e));
        }
        std::setvbuf(file_, nullptr, _IONBF, 0);
        descriptor_ = fd;
        stream_ = true;
        return;
    }
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
    // A file being replaced keeps its permissions (a private 0600 file stays private): the new
    // one is made private, so that no one opens it meanwhile, then takes the old one's
    // permission bits (not set-id bits: the contents are new). Best effort: a file system that
    // refuses leaves it private. Its group and other names (hard links) stay the old file's.
    struct stat old{};
    const bool replacing = ::stat(place.c_str(), &old) == 0 && S_ISREG(old.st_mode);
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = prefix + std::to_string(attempt) + ".tmp";
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, replacing ? 0600 : 0666);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            const int e = errno;
            // The temporary file's name (pid, attempt) is no business of the message: say where.
            const std::size_t slash = place.rfind('/');
            const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : place.substr(0, slash);
            fail("cannot create a file in " + folder + ": " + std::strerror(e));
        }
        temp_path_ = std::move(name);
        if (replacing) (void)::fchmod(fd, old.st_mode & 0777);
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
    if (descriptor_ >= 0) flush_printed(descriptor_);
    if (size != 0 && std::fwrite(data, 1, size, file_) != size) {
        const int e = errno;
        // Ctrl-C while a write waited on a full pipe: the run was stopped, not the output
        // refused (the handler does not restart the call).
        if (e == EINTR) throw_if_interrupted();
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
    // A descriptor opened to append (`>> file`) takes every write at its end: a seek back
    // would not patch, it would add the bytes again.
    if (descriptor_ >= 0 && (::fcntl(::fileno(file_), F_GETFL) & O_APPEND) != 0) {
        fail("it is open for appending (>>), and this file's header is patched once the rest is written: give a file path");
    }
    const long at = std::ftell(file_);
    if (at < 0) fail_seek(errno);
    return at;
}

void AtomicFile::seek(std::int64_t offset) {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::seek after commit");
    end_ = std::max(end_, tell());
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
        // Written in place: every byte must have gone (a full device says so here). A
        // descriptor the program shares is left after the last byte written, not after a
        // patched header, or what the program prints next would overwrite the rest.
        int flushed = std::fflush(file_);
        int e = errno;
        if (flushed == 0 && end_ >= 0 && std::ftell(file_) < end_ && std::fseek(file_, static_cast<long>(end_), SEEK_SET) != 0) {
            flushed = -1;
            e = errno;
        }
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
    if (const int fd = own_descriptor(path); fd >= 0) {
        if (const std::string why = unwritable_descriptor(fd); !why.empty()) throw InputError(SourceLocation{path, 0, 0}, "cannot write: " + why);
        return;
    }
    std::string resolved;
    if (target_of(path, resolved) == Target::stream) return;
    const AtomicFile probe(path);
}

bool same_file(const std::string& output, const std::string& other) {
    if (output.empty() || other.empty()) return false;
    struct stat a {};
    struct stat b {};
    // Two of this process's descriptors on one file or pipe (/dev/stdout and /dev/fd/1, or
    // /dev/stderr after 2>&1) are one: the second's bytes would land in the first's, or a
    // script read from it would be what is written. A terminal is not: stdin, stdout and
    // stderr of an interactive shell are all the one terminal, and typing a script there
    // while the scenario is printed there is fine.
    const int fa = own_descriptor(output), fb = own_descriptor(other);
    if (fa >= 0 && fb >= 0) {
        return fa == fb || (::fstat(fa, &a) == 0 && ::fstat(fb, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino &&
                            !S_ISCHR(a.st_mode));
    }
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
