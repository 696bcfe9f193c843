// Mesa's texture decoders as an outside reference for the compressed-format tests: OSMesa (Debian's
// libosmesa6, Mesa 22.3.6), a compatibility-profile software context, one per process.
//
// Method: the blocks go in with glCompressedTexImage2D(GL_TEXTURE_2D, 0, internal format, w, h) and
// come back decoded with glGetTexImage(GL_TEXTURE_2D, 0, gl_format, gl_type), GL_PACK_ALIGNMENT 1.
// No sampling, no filtering: glGetTexImage of a compressed image is a pure decode.
//
// Driver: GALLIUM_DRIVER is set to softpipe before the first context (always; an inherited value is
// overwritten so that every run takes the same path), and the context is refused unless GL_RENDERER
// names softpipe. The decoders are Mesa's, not the driver's rasterizer (read in Mesa 22.x,
// src/mesa/state_tracker/st_cb_texture.c st_GetTexSubImage and src/mesa/main/texgetimage.c):
//   - ETC1/ETC2/EAC and ASTC, which softpipe does not sample (st_GetTexSubImage asserts it never
//     sees them): the state tracker keeps the uploaded blocks (st_MapTextureImage maps that copy)
//     and glGetTexImage takes the CPU path, get_tex_rgba_compressed: _mesa_decompress_image
//     (main/texcompress.c) calls the format's fetch function (main/texcompress_etc.c,
//     main/texcompress_astc.cpp) per texel into RGBA float, then _mesa_format_convert packs to
//     gl_format/gl_type (float -> unorm by round-to-nearest: exact for values n/255 and n/65535);
//   - S3TC, RGTC, BPTC: if softpipe samples the format, st_GetTexSubImage decompresses it with a
//     NEAREST blit into an uncompressed texture, and softpipe's texel fetch for a compressed format
//     is src/util/format's unpack (u_format_s3tc.c, u_format_rgtc.c, u_format_bptc.c); if not, the
//     CPU path above, whose fetch functions for these formats are the same util/format code.
//     Which of the two a given format takes was not traced here; both are Mesa's own decoders.
// sRGB formats come back undecoded on the CPU path (get_tex_rgba_compressed reads them as their
// linear twin): the ETC2 sRGB formats read back equal to their linear twins (test_etc2_decode).
// libOSMesa carries no symbols here, so this is read from the source and checked by results (hand-
// derived BC1 and ETC2 blocks decode as derived), not stepped in a debugger.
//
// Mesa 22.3.6 returns wrong texels, without a GL error, when ETC1/ETC2/EAC or ASTC images are read
// back with three components (GL_RGB, GL_BGR; any type): mesa_decode reads those as four
// components and drops the fourth, so every gl_format works.
//
// Read back EAC R11/RG11 as GL_UNSIGNED_SHORT / GL_SHORT (GL_RED or GL_RG) to see all 11 bits; 8-bit
// read-backs of those formats give the nearest 8-bit value (float pack; test_etc2_decode checks
// every 11-bit value).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tfu::test {

// Mesa's own texture decoders, outside the project (OSMesa, Mesa 22.3.6): a compressed image uploaded with
// glCompressedTexImage2D and read back with glGetTexImage(GL_TEXTURE_2D, 0, gl_format, gl_type).
// True when an OSMesa context (compatibility profile, software) can be made in this process.
bool mesa_available();
// The decoded texels, row-major from the first block row, tightly packed (GL_PACK_ALIGNMENT 1);
// std::nullopt when Mesa is not available or refuses the format (glGetError text in *why if given).
std::optional<std::vector<uint8_t>> mesa_decode(uint32_t gl_internal_format, int width, int height,
                                                std::span<const uint8_t> blocks, uint32_t gl_format, uint32_t gl_type,
                                                std::string* why = nullptr);

}  // namespace tfu::test
