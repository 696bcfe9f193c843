// Mesa's decoders through OSMesa (testbench/mesa_decoder.hpp).
#include "testbench/mesa_decoder.hpp"

#include <GL/gl.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <mutex>

namespace tfu::test {
namespace {

using CompressedTexImage2DFn = void (*)(GLenum, GLint, GLenum, GLsizei, GLsizei, GLint, GLsizei, const void*);

// The one context of the process, made on first use; every GL call below runs under mutex(), with the
// context made current on the calling thread for the call and released afterwards.
struct MesaContext {
  OSMesaContext ctx = nullptr;
  std::vector<uint8_t> pbuffer;  // the small colour buffer OSMesaMakeCurrent needs (nothing is drawn)
  CompressedTexImage2DFn compressed_tex_image_2d = nullptr;
  std::string error;  // why no context could be made
};

constexpr int kPbufferSize = 4;

std::mutex& mutex() {
  static std::mutex m;
  return m;
}

// Under mutex().
MesaContext& context() {
  static MesaContext mc = [] {
    MesaContext m;
    setenv("GALLIUM_DRIVER", "softpipe", 1);  // the software rasterizer; see the header
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                           OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
    m.ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (m.ctx == nullptr) {
      m.error = "OSMesaCreateContextAttribs failed";
      return m;
    }
    m.pbuffer.assign(kPbufferSize * kPbufferSize * 4, 0);
    if (!OSMesaMakeCurrent(m.ctx, m.pbuffer.data(), GL_UNSIGNED_BYTE, kPbufferSize, kPbufferSize)) {
      m.error = "OSMesaMakeCurrent failed";
      OSMesaDestroyContext(m.ctx);
      m.ctx = nullptr;
      return m;
    }
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (renderer == nullptr || std::string(renderer).find("softpipe") == std::string::npos) {
      m.error = std::string("GL_RENDERER is not softpipe: ") + (renderer != nullptr ? renderer : "(none)");
      OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
      OSMesaDestroyContext(m.ctx);
      m.ctx = nullptr;
      return m;
    }
    m.compressed_tex_image_2d =
        reinterpret_cast<CompressedTexImage2DFn>(OSMesaGetProcAddress("glCompressedTexImage2D"));
    if (m.compressed_tex_image_2d == nullptr) m.error = "no glCompressedTexImage2D";
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    return m;
  }();
  return mc;
}

const char* gl_error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "GL error";
  }
}

// Bytes of one texel in glGetTexImage's output, 0 for a format or type this helper does not size.
int bytes_per_texel(GLenum format, GLenum type) {
  int components = 0;
  switch (format) {
    case GL_RED: case GL_GREEN: case GL_BLUE: case GL_ALPHA: case GL_LUMINANCE: components = 1; break;
    case GL_LUMINANCE_ALPHA: case 0x8227 /* GL_RG */: components = 2; break;
    case GL_RGB: case 0x80E0 /* GL_BGR */: components = 3; break;
    case GL_RGBA: case 0x80E1 /* GL_BGRA */: components = 4; break;
    default: return 0;
  }
  switch (type) {
    case GL_UNSIGNED_BYTE: case GL_BYTE: return components;
    case GL_UNSIGNED_SHORT: case GL_SHORT: case 0x140B /* GL_HALF_FLOAT */: return 2 * components;
    case GL_UNSIGNED_INT: case GL_INT: case GL_FLOAT: return 4 * components;
    default: return 0;
  }
}

}  // namespace

bool mesa_available() {
  std::lock_guard<std::mutex> lock(mutex());
  const MesaContext& m = context();
  return m.ctx != nullptr && m.compressed_tex_image_2d != nullptr;
}

std::optional<std::vector<uint8_t>> mesa_decode(uint32_t gl_internal_format, int width, int height,
                                                std::span<const uint8_t> blocks, uint32_t gl_format,
                                                uint32_t gl_type, std::string* why) {
  auto fail = [why](std::string text) -> std::optional<std::vector<uint8_t>> {
    if (why != nullptr) *why = std::move(text);
    return std::nullopt;
  };
  const int texel_bytes = bytes_per_texel(gl_format, gl_type);
  if (texel_bytes == 0) return fail("mesa_decode: unsupported read-back format/type");
  if (width <= 0 || height <= 0) return fail("mesa_decode: empty image");

  std::lock_guard<std::mutex> lock(mutex());
  MesaContext& m = context();
  if (m.ctx == nullptr || m.compressed_tex_image_2d == nullptr) return fail("Mesa not available: " + m.error);
  if (!OSMesaMakeCurrent(m.ctx, m.pbuffer.data(), GL_UNSIGNED_BYTE, kPbufferSize, kPbufferSize))
    return fail("OSMesaMakeCurrent failed");
  while (glGetError() != GL_NO_ERROR) {
  }

  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  m.compressed_tex_image_2d(GL_TEXTURE_2D, 0, gl_internal_format, width, height, 0,
                            static_cast<GLsizei>(blocks.size()), blocks.data());
  std::optional<std::vector<uint8_t>> result;
  GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    result = fail(std::string("glCompressedTexImage2D: ") + gl_error_name(err));
  } else {
    // Mesa 22.3.6 decodes ETC1/ETC2/EAC and ASTC wrongly when asked for three components
    // (GL_RGB or GL_BGR, any type): it prints "implementation error: Unexpected format in
    // _mesa_decompress_image()", raises no GL error and returns other texels. So three components
    // are always read as four (GL_RGBA / GL_BGRA, same type) and the fourth is dropped here.
    const bool three = gl_format == GL_RGB || gl_format == 0x80E0 /* GL_BGR */;
    const GLenum read_format = !three ? gl_format : gl_format == GL_RGB ? GL_RGBA : 0x80E1 /* GL_BGRA */;
    const size_t texels = static_cast<size_t>(width) * static_cast<size_t>(height);
    const auto out_bytes = static_cast<size_t>(texel_bytes);
    const size_t read_bytes = three ? out_bytes / 3 * 4 : out_bytes;
    std::vector<uint8_t> read(texels * read_bytes);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, read_format, gl_type, read.data());
    err = glGetError();
    if (err != GL_NO_ERROR) {
      result = fail(std::string("glGetTexImage: ") + gl_error_name(err));
    } else if (!three) {
      result = std::move(read);
    } else {
      std::vector<uint8_t> out(texels * out_bytes);
      for (size_t t = 0; t < texels; ++t)
        std::copy_n(read.begin() + static_cast<std::ptrdiff_t>(t * read_bytes), out_bytes,
                    out.begin() + static_cast<std::ptrdiff_t>(t * out_bytes));
      result = std::move(out);
    }
  }
  glDeleteTextures(1, &tex);
  OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  return result;
}

}  // namespace tfu::test
