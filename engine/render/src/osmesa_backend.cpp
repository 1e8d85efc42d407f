// The OSMesa backend: Mesa's software OpenGL (llvmpipe) renders into a buffer in memory, with
// no window and no GPU. An OpenGL 3.3 core context, one shader, one vertex buffer, the atlas as
// one texture: a frame is one glDrawArrays. The only file that includes GL/OSMesa headers.
#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/glcorearb.h>

#include "backend.h"

namespace jostle::detail {

namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 position;  // image pixels, y down
layout(location = 1) in vec2 uv;       // texels from the sprite's corner
layout(location = 2) in vec4 color;
layout(location = 3) in uvec4 rect;    // the sprite in the atlas: x, y, w, h texels
uniform vec2 viewport;
out vec2 v_uv;
out vec4 v_color;
flat out uvec4 v_rect;
void main() {
    // Image row 0 is the top: y down in pixels is y up in clip space.
    gl_Position = vec4(position.x / viewport.x * 2.0 - 1.0, 1.0 - position.y / viewport.y * 2.0, 0.0, 1.0);
    v_uv = uv;
    v_color = color;
    v_rect = rect;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 v_uv;
in vec4 v_color;
flat in uvec4 v_rect;
uniform sampler2D atlas;
uniform vec2 inv_atlas;
out vec4 out_color;
void main() {
    // The nearest texel, chosen in the sprite's own coordinates and only then placed in the
    // atlas: which texel a pixel shows does not depend on where the sprite was packed (an
    // atlas coordinate's rounding did), and never falls outside the sprite.
    ivec2 size = ivec2(v_rect.zw);
    ivec2 texel = clamp(ivec2(floor(v_uv)), ivec2(0), size - 1) + ivec2(v_rect.xy);
    // Sampled at the texel's centre, exact in the power-of-two atlas (texture() ran a little
    // faster than texelFetch on llvmpipe).
    vec4 c = texture(atlas, (vec2(texel) + 0.5) * inv_atlas) * v_color;
    out_color = vec4(c.rgb * c.a, c.a);  // premultiplied: blending is right over any alpha
}
)";

GLuint compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[1024] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("OSMesa backend: shader does not compile: ") + log);
    }
    return shader;
}

class OsmesaBackend final : public Backend {
public:
    OsmesaBackend() {
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                               OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
        context_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (context_ == nullptr) throw std::runtime_error("OSMesa backend: cannot create an OpenGL 3.3 core context");
        bind(first_buffer_.data(), 1, 1);  // a context needs a buffer before it compiles shaders
        const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
        const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
        program_ = glCreateProgram();
        glAttachShader(program_, vs);
        glAttachShader(program_, fs);
        glLinkProgram(program_);
        glDeleteShader(vs);
        glDeleteShader(fs);
        GLint ok = GL_FALSE;
        glGetProgramiv(program_, GL_LINK_STATUS, &ok);
        if (ok != GL_TRUE) throw std::runtime_error("OSMesa backend: shader program does not link");
        viewport_uniform_ = glGetUniformLocation(program_, "viewport");
        inv_atlas_uniform_ = glGetUniformLocation(program_, "inv_atlas");

        glGenVertexArrays(1, &vao_);
        glBindVertexArray(vao_);
        glGenBuffers(1, &vbo_);
        glBindBuffer(GL_ARRAY_BUFFER, vbo_);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, x)));
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, u)));
        glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, r)));
        glVertexAttribIPointer(3, 4, GL_UNSIGNED_SHORT, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, rect_x)));
        for (GLuint i = 0; i < 4; ++i) glEnableVertexAttribArray(i);

        glGenTextures(1, &texture_);
        glBindTexture(GL_TEXTURE_2D, texture_);
        // Nearest texels: pixel art stays exact, and results do not depend on filtering.
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
    }

    ~OsmesaBackend() override {
        if (context_ != nullptr) OSMesaDestroyContext(context_);
    }

    int render(const Frame& frame, Image& out) override {
        // OSMesa renders into the image's own pixels: no copy of ours after glFinish.
        out.width = frame.width;
        out.height = frame.height;
        out.rgba.resize(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height) * 4u);
        bind(out.rgba.data(), frame.width, frame.height);
        glViewport(0, 0, frame.width, frame.height);
        // The framebuffer holds premultiplied colour (see the blend below).
        const float clear_alpha = frame.clear.a / 255.0f;
        glClearColor(frame.clear.r / 255.0f * clear_alpha, frame.clear.g / 255.0f * clear_alpha,
                     frame.clear.b / 255.0f * clear_alpha, clear_alpha);
        glClear(GL_COLOR_BUFFER_BIT);
        int calls = 0;
        if (frame.vertices != nullptr && !frame.vertices->empty()) {
            if (frame.atlas_version != uploaded_version_) {
                glBindTexture(GL_TEXTURE_2D, texture_);
                glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, frame.atlas->width, frame.atlas->height, 0, GL_RGBA,
                             GL_UNSIGNED_BYTE, frame.atlas->rgba.data());
                uploaded_version_ = frame.atlas_version;
            }
            // Porter-Duff "over" on premultiplied colour (the shader premultiplies): correct
            // whatever the alpha already in the frame; straight-alpha blending is right only
            // over opaque pixels.
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            glUseProgram(program_);
            glUniform2f(viewport_uniform_, static_cast<float>(frame.width), static_cast<float>(frame.height));
            glUniform2f(inv_atlas_uniform_, 1.0f / static_cast<float>(frame.atlas->width), 1.0f / static_cast<float>(frame.atlas->height));
            glBindVertexArray(vao_);
            glBindBuffer(GL_ARRAY_BUFFER, vbo_);
            glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(frame.vertices->size() * sizeof(Vertex)),
                         frame.vertices->data(), GL_STREAM_DRAW);
            glBindTexture(GL_TEXTURE_2D, texture_);
            glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(frame.vertices->size()));
            calls = 1;
        }
        // glFinish waits for llvmpipe and has OSMesa copy the frame into `out` (bound above,
        // top row first): that copy is the readback, the only one.
        glFinish();
        unpremultiply(out.rgba);
        return calls;
    }

private:
    // Premultiplied to straight RGBA, rounded; opaque pixels (the common case) stay as they
    // are, fully transparent ones become (0, 0, 0, 0). Two pixels at a time are checked for
    // being opaque, so opaque frames cost one pass of 8-byte loads.
    static void unpremultiply(std::vector<std::uint8_t>& rgba) {
        constexpr std::uint64_t kAlphas = 0xff000000ff000000u;  // little-endian RGBA: A is byte 3
        std::size_t i = 0;
        for (; i + 8 <= rgba.size(); i += 8) {
            std::uint64_t two;
            std::memcpy(&two, rgba.data() + i, 8);
            if ((two & kAlphas) == kAlphas) continue;
            unpremultiply_pixel(rgba.data() + i);
            unpremultiply_pixel(rgba.data() + i + 4);
        }
        for (; i < rgba.size(); i += 4) unpremultiply_pixel(rgba.data() + i);
    }
    static void unpremultiply_pixel(std::uint8_t* p) {
        const unsigned a = p[3];
        if (a == 255u) return;
        for (std::size_t c = 0; c < 3; ++c) {
            p[c] = a == 0u ? 0 : static_cast<std::uint8_t>(std::min(255u, (p[c] * 255u + a / 2u) / a));
        }
    }

    // Makes the context current on `pixels` (width * height RGBA, top row first).
    void bind(std::uint8_t* pixels, int width, int height) {
        if (!OSMesaMakeCurrent(context_, pixels, GL_UNSIGNED_BYTE, width, height)) {
            throw std::runtime_error("OSMesa backend: cannot bind a " + std::to_string(width) + "x" + std::to_string(height) + " buffer");
        }
        OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 of the buffer is the image's top row
    }

    OSMesaContext context_ = nullptr;
    std::array<std::uint8_t, 4> first_buffer_{};
    GLuint program_ = 0;
    GLint viewport_uniform_ = -1;
    GLint inv_atlas_uniform_ = -1;
    GLuint vao_ = 0;
    GLuint vbo_ = 0;
    GLuint texture_ = 0;
    std::uint64_t uploaded_version_ = 0;
};

}  // namespace

std::unique_ptr<Backend> make_osmesa_backend() { return std::make_unique<OsmesaBackend>(); }

}  // namespace jostle::detail
