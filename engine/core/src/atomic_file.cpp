// atomic_file.cpp: temporary file, fsync, rename (POSIX).
#include "jostle/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "jostle/core/error.h"

namespace jostle {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    const std::string prefix = path_ + "." + std::to_string(::getpid()) + ".";
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = prefix + std::to_string(attempt) + ".tmp";
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            const int e = errno;
            // The temporary file's name (pid, attempt) is no business of the message: say where.
            const std::size_t slash = path_.rfind('/');
            const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path_.substr(0, slash);
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

std::int64_t AtomicFile::tell() {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::tell after commit");
    const long at = std::ftell(file_);
    if (at < 0) {
        const int e = errno;
        fail(std::strerror(e));
    }
    return at;
}

void AtomicFile::seek(std::int64_t offset) {
    JOSTLE_ASSERT(file_ != nullptr, "AtomicFile::seek after commit");
    if (std::fseek(file_, static_cast<long>(offset), SEEK_SET) != 0) {
        const int e = errno;
        fail(std::strerror(e));
    }
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
    if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
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

}  // namespace jostle
