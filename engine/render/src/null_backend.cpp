// The null backend: draws nothing; the image is the clear colour. For tests and runs that
// need no pixels (the simulation never depends on rendering).
#include "backend.h"

namespace jostle::detail {

namespace {

class NullBackend final : public Backend {
public:
    int render(const Frame& frame, Image& out) override {
        out.width = frame.width;
        out.height = frame.height;
        out.rgba.resize(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height) * 4u);
        for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
            out.rgba[i] = frame.clear.r;
            out.rgba[i + 1] = frame.clear.g;
            out.rgba[i + 2] = frame.clear.b;
            out.rgba[i + 3] = frame.clear.a;
        }
        return 0;
    }
};

}  // namespace

std::unique_ptr<Backend> make_null_backend() { return std::make_unique<NullBackend>(); }

}  // namespace jostle::detail
