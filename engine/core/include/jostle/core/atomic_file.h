// jostle/core/atomic_file.h: writing a file so that it is either the old file or the whole new
// one, never half written. The bytes go to a temporary file in the same folder
// ("<path>.<pid>.<n>.tmp"), which is flushed, synced and then renamed over the target by
// commit(). Without commit() (an error, an exception unwinding) the temporary file is removed
// and the target is untouched. Every error is an InputError naming the target path:
// "out/frame_000001.png: cannot write: No space left on device".
// A path that is a link to a regular file replaces the file it points at (the link stays). A
// target that is not a regular file (a device such as /dev/null, a FIFO, a socket, /dev/stdout
// on a pipe) cannot be replaced: it is written in place, and commit() reports any byte that did
// not arrive. A path that stands for one of this process's descriptors (/dev/stdout,
// /dev/stderr, /dev/fd/N, /proc/self/fd/N) is never opened again: the bytes go through the
// descriptor itself, at its offset (after what the program printed there, appending after
// `>>`), unbuffered, so they keep their order with the program's own output to it. A folder
// is an error.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace jostle {

class AtomicFile {
public:
    // Creates the temporary file (with O_EXCL, mode 0666 minus the umask). Throws InputError.
    explicit AtomicFile(std::string path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* data, std::size_t size);
    void write(std::string_view bytes) { write(bytes.data(), bytes.size()); }
    // The write position, and moving it (to patch a header written earlier).
    std::int64_t tell();
    void seek(std::int64_t offset);
    // Pushes buffered bytes into the temporary file (so it can be read back before commit).
    void flush();
    // Flushes, syncs, closes and renames the temporary file over the target.
    void commit();

    const std::string& path() const { return path_; }
    const std::string& temp_path() const { return temp_path_; }  // empty when written in place
    bool in_place() const { return stream_; }  // not a regular file: bytes go out as written

private:
    [[noreturn]] void fail(const std::string& what) const;
    [[noreturn]] void fail_seek(int e) const;
    std::string path_;
    std::string rename_to_;  // path_, or the regular file a link at path_ points at
    std::string temp_path_;  // empty when written in place
    bool stream_ = false;    // written in place (not a regular file)
    int descriptor_ = -1;    // the descriptor of this process the path stands for, if one
    std::int64_t end_ = -1;  // where the bytes end, once seek() has moved back from there
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

// The whole file at once: AtomicFile, write, commit.
void write_file_atomic(const std::string& path, std::string_view bytes);

// Makes, and at once removes, the temporary file AtomicFile(path) would write, so that a path
// an output cannot be written to is AtomicFile's InputError before a long run instead of after
// it, with nothing left behind. A target that is not a regular file (a device, a pipe) is not
// opened: opening a pipe can block, or end its reader's input.
void check_writable(const std::string& path);

// Whether writing `output` would replace the file `other` names (an input, or another
// output), so that a command can refuse before it starts: both name one existing regular file
// (through links and different spellings), or neither exists yet and they are the same path
// made absolute and normal. Devices and pipes never clash (/dev/null may take two outputs).
bool same_file(const std::string& output, const std::string& other);

}  // namespace jostle
