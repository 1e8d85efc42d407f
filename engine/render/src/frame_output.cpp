// Frame selection and the threaded PNG frame writer (jostle/render/frame_output.h).
#include "jostle/render/frame_output.h"

#include <algorithm>
#include <charconv>
#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <thread>

#include "jostle/core/error.h"

namespace jostle {

// ---------------------------------------------------------------------------------------
// FrameSelection
// ---------------------------------------------------------------------------------------

namespace {

std::optional<std::int64_t> parse_frame(std::string_view s) {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc{} || end != s.data() + s.size() || v < 0) return std::nullopt;
    return v;
}

}  // namespace

std::optional<FrameSelection> FrameSelection::parse(std::string_view text, std::string* error) {
    const auto fail = [&](const std::string& why) -> std::optional<FrameSelection> {
        if (error) *error = "frames '" + std::string(text) + "': " + why;
        return std::nullopt;
    };
    FrameSelection out;
    if (text == "all") return out;
    out.ranges_.clear();
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = text.find(',', start);
        const std::string_view item = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
        if (item.empty()) return fail("expected a frame number or a range A-B, got an empty item");
        const std::size_t dash = item.find('-');
        Range r;
        if (dash == std::string_view::npos) {
            const auto v = parse_frame(item);
            if (!v) return fail("expected a frame number (0 or more), got '" + std::string(item) + "'");
            r = {*v, *v};
        } else {
            const auto a = parse_frame(item.substr(0, dash));
            if (!a) return fail("expected a range A-B with A a frame number, got '" + std::string(item) + "'");
            const std::string_view rest = item.substr(dash + 1);
            if (rest.empty()) {
                r = {*a, INT64_MAX};
            } else {
                const auto b = parse_frame(rest);
                if (!b) return fail("expected a range A-B with B a frame number, got '" + std::string(item) + "'");
                if (*b < *a) return fail("range " + std::string(item) + " ends before it starts");
                r = {*a, *b};
            }
        }
        out.ranges_.push_back(r);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return out;
}

void FrameSelection::set_every(std::int64_t n) {
    JOSTLE_ASSERT(n >= 1, "every must be >= 1");
    every_ = n;
}

bool FrameSelection::contains(std::int64_t frame) const {
    for (const Range& r : ranges_) {
        if (frame >= r.first && frame <= r.last && (frame - r.first) % every_ == 0) return true;
    }
    return false;
}

std::optional<std::int64_t> FrameSelection::last() const {
    std::int64_t last = 0;
    for (const Range& r : ranges_) {
        if (r.last == INT64_MAX) return std::nullopt;
        last = std::max(last, r.last);
    }
    return last;
}

std::string frame_file_name(std::int64_t frame, std::string_view prefix, int digits) {
    std::string number = std::to_string(frame);
    if (static_cast<int>(number.size()) < digits) number.insert(0, static_cast<std::size_t>(digits) - number.size(), '0');
    return std::string(prefix) + number + ".png";
}

// ---------------------------------------------------------------------------------------
// FrameWriter
// ---------------------------------------------------------------------------------------

struct FrameWriter::Impl {
    FrameWriterDesc desc;
    mutable std::mutex mutex;
    std::condition_variable changed;
    std::deque<std::pair<std::string, Image>> queue;
    std::vector<std::string> written;
    std::exception_ptr error;
    bool busy = false;
    bool stopping = false;
    std::thread worker;
    std::vector<std::filesystem::path> created;  // folders the constructor made, deepest first

    void run() {
        std::unique_lock lock(mutex);
        for (;;) {
            changed.wait(lock, [&] { return stopping || !queue.empty(); });
            if (queue.empty()) return;  // stopping, and nothing left
            auto [path, image] = std::move(queue.front());
            queue.pop_front();
            busy = true;
            changed.notify_all();  // a slot is free for write()
            lock.unlock();
            std::exception_ptr failure;
            try {
                write_png_atomic(path, image, desc.encoding);
            } catch (...) {
                failure = std::current_exception();
            }
            lock.lock();
            busy = false;
            if (failure && !error) error = failure;
            if (failure) queue.clear();  // the first error stops the run's output
            changed.notify_all();
        }
    }
};

FrameWriter::FrameWriter(const FrameWriterDesc& desc) : impl_(std::make_unique<Impl>()) {
    impl_->desc = desc;
    std::error_code ec;
    std::filesystem::path folder = std::filesystem::path(desc.folder).lexically_normal();
    if (!folder.has_filename()) folder = folder.parent_path();  // "frames/"
    for (std::filesystem::path p = folder; !p.empty() && p.has_relative_path() && !std::filesystem::exists(p, ec); p = p.parent_path()) {
        impl_->created.push_back(p);
    }
    std::filesystem::create_directories(desc.folder, ec);
    if (ec || !std::filesystem::is_directory(desc.folder)) {
        throw InputError(SourceLocation{desc.folder}, "cannot create the frame folder" + (ec ? ": " + ec.message() : std::string()));
    }
    impl_->worker = std::thread([this] { impl_->run(); });
}

FrameWriter::~FrameWriter() {
    {
        std::lock_guard lock(impl_->mutex);
        impl_->stopping = true;
    }
    impl_->changed.notify_all();
    if (impl_->worker.joinable()) impl_->worker.join();
    // A run that fails (or is stopped) leaves no folder of ours behind that it left empty.
    if (std::uncaught_exceptions() > 0) {
        std::error_code ec;
        for (const std::filesystem::path& folder : impl_->created) {
            if (!std::filesystem::is_empty(folder, ec) || ec || !std::filesystem::remove(folder, ec)) break;
        }
    }
}

void FrameWriter::write(std::int64_t frame, Image image) {
    Impl& w = *impl_;
    const std::string path = (std::filesystem::path(w.desc.folder) / frame_file_name(frame)).string();
    std::unique_lock lock(w.mutex);
    w.changed.wait(lock, [&] { return w.error || static_cast<int>(w.queue.size()) < std::max(w.desc.max_queued, 1); });
    if (w.error) std::rethrow_exception(w.error);
    w.queue.emplace_back(path, std::move(image));
    w.written.push_back(path);
    w.changed.notify_all();
}

void FrameWriter::finish() {
    Impl& w = *impl_;
    std::unique_lock lock(w.mutex);
    w.changed.wait(lock, [&] { return w.queue.empty() && !w.busy; });
    if (w.error) std::rethrow_exception(w.error);
}

std::vector<std::string> FrameWriter::written() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->written;
}

}  // namespace jostle
