// A tiny OpenGL 1.x program (GLX, a 64 x 64 window) that makes every call the GL replay executes
// (docs/gl-replay.md), for testbench/gl_replay_test.sh: traced with apitrace under Xvfb, its first
// frame is replayed through both models and the pixels below are checked.
//
// Each check draws into its own 8 x 8 region of the window with flat-coloured textures (every texel
// and every MIP level one colour), so the filtered value is that colour whatever the filter, and the
// expected pixel follows by hand from the GL rules (texture environment, blending, alpha and depth
// tests) in 8-bit codes: products rounded, x * y / 255 to nearest (texenv.hpp), blending as one
// rounding of S sf + D df. The expected values are written to argv[1]: "x y r g b name" per line,
// (x, y) a screen pixel (row 0 on top).
//
//   gl_replay_program CHECKS_FILE [unsupported | bad-s3tc]
// With "unsupported" the frame also enables fog for a draw and calls glLineWidth, which the replay
// must refuse by name; with "bad-s3tc" it replaces a rectangle of an S3TC level that is not made of
// whole 4 x 4 blocks, which the replay must refuse (one line, exit 2).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#include <X11/Xlib.h>

#include <cstdio>
#include <cstring>
#include <vector>

namespace {

constexpr int kSize = 64;

PFNGLACTIVETEXTUREARBPROC active_texture = nullptr;
PFNGLCLIENTACTIVETEXTUREARBPROC client_active_texture = nullptr;
PFNGLLOCKARRAYSEXTPROC lock_arrays = nullptr;
PFNGLUNLOCKARRAYSEXTPROC unlock_arrays = nullptr;
FILE* checks = nullptr;

// One expected pixel: the centre of region (rx, ry) (8 x 8 pixels, GL window coordinates, y up).
void expect(int rx, int ry, int r, int g, int b, const char* name) {
  std::fprintf(checks, "%d %d %d %d %d %s\n", rx * 8 + 4, kSize - 1 - (ry * 8 + 4), r, g, b, name);
}

// A texture of one colour at every level (w x h down to 1 x 1 when mipmapped).
GLuint flat_texture(int w, int h, const unsigned char rgba[4], GLenum internal, bool mipmapped, GLenum min, GLenum wrap) {
  GLuint name = 0;
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  for (int level = 0;; ++level) {
    std::vector<unsigned char> texels(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
    for (size_t i = 0; i < texels.size(); i += 4) std::memcpy(&texels[i], rgba, 4);
    glTexImage2D(GL_TEXTURE_2D, level, static_cast<GLint>(internal), w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    if (!mipmapped || (w == 1 && h == 1)) break;
    w = w > 1 ? w / 2 : 1;
    h = h > 1 ? h / 2 : 1;
  }
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLfloat>(min));
  const bool nearest = min == GL_NEAREST || min == GL_NEAREST_MIPMAP_NEAREST || min == GL_NEAREST_MIPMAP_LINEAR;
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLfloat>(nearest ? GL_NEAREST : GL_LINEAR));
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, static_cast<GLfloat>(wrap));
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, static_cast<GLfloat>(wrap));
  return name;
}

// A quad over region (rx, ry) drawn with glDrawElements from client arrays inside
// glLockArraysEXT, counter-clockwise (front-facing) unless `clockwise`, at depth z, with one colour.
void array_quad(int rx, int ry, float z, const unsigned char colour[4], bool clockwise = false, bool strip = false) {
  const float x0 = static_cast<float>(rx * 8), y0 = static_cast<float>(ry * 8), x1 = x0 + 8, y1 = y0 + 8;
  const float pos[] = {x0, y0, z, 0, x1, y0, z, 0, x1, y1, z, 0, x0, y1, z, 0};  // stride 16, as the engine's
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  unsigned char col[16];
  for (int i = 0; i < 4; ++i) std::memcpy(col + 4 * i, colour, 4);
  glVertexPointer(3, GL_FLOAT, 16, pos);
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, col);
  for (int unit = 1; unit >= 0; --unit) {
    client_active_texture(GL_TEXTURE0_ARB + static_cast<GLenum>(unit));
    glTexCoordPointer(2, GL_FLOAT, 0, uv);
  }
  lock_arrays(0, 4);
  if (strip) {
    const GLushort idx[] = {0, 1, 3, 2};
    glDrawElements(GL_TRIANGLE_STRIP, 4, GL_UNSIGNED_SHORT, idx);
  } else {
    const GLuint ccw[] = {0, 1, 2, 0, 2, 3}, cw[] = {0, 2, 1, 0, 3, 2};
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, clockwise ? cw : ccw);
  }
  unlock_arrays();
}

// The same quad with glBegin / glEnd (the engine's 2D path), colour from glColor4f. Two corners
// are given by the vector forms the engine's sky box uses (glVertex2fv, glTexCoord2fv and
// glVertex3fv with z = 0): the same quad, so the same expected pixels.
void immediate_quad(int rx, int ry, float r, float g, float b, float a) {
  const float x0 = static_cast<float>(rx * 8), y0 = static_cast<float>(ry * 8);
  const float corner0[2] = {x0, y0}, st1[2] = {1, 0}, corner1[3] = {x0 + 8, y0, 0};
  glColor4f(r, g, b, a);
  glBegin(GL_QUADS);
  glTexCoord2f(0, 0), glVertex2fv(corner0);
  glTexCoord2fv(st1), glVertex3fv(corner1);
  glTexCoord2f(1, 1), glVertex2f(x0 + 8, y0 + 8);
  glTexCoord2f(0, 1), glVertex2f(x0, y0 + 8);
  glEnd();
}

void draw_frame(bool with_unsupported, bool with_bad_s3tc) {
  const unsigned char orange[4] = {200, 100, 50, 255}, red_half[4] = {255, 0, 0, 128}, grey[4] = {128, 128, 128, 255},
                      dark[4] = {10, 20, 30, 255}, green_low[4] = {0, 255, 0, 100}, white[4] = {255, 255, 255, 255},
                      tint[4] = {128, 255, 64, 255}, blue[4] = {0, 0, 255, 255};
  const GLuint A = flat_texture(4, 4, orange, GL_RGBA, true, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT);
  const GLuint B = flat_texture(2, 2, red_half, GL_RGBA, false, GL_LINEAR, GL_CLAMP_TO_EDGE);
  const GLuint C = flat_texture(8, 4, grey, GL_RGB, true, GL_LINEAR_MIPMAP_NEAREST, GL_REPEAT);
  const GLuint D = flat_texture(4, 4, dark, GL_RGB, true, GL_NEAREST_MIPMAP_NEAREST, GL_CLAMP_TO_EDGE);
  const GLuint E = flat_texture(1, 1, green_low, GL_RGBA, false, GL_NEAREST, GL_REPEAT);
  const GLuint F = flat_texture(4, 4, orange, GL_RGBA, true, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, 4.0f);
  // A 2 x 2 texture of four colours, NEAREST: texel (0, 0), the first uploaded, is at s, t = 0 (bottom left).
  GLuint G = 0;
  glGenTextures(1, &G);
  glBindTexture(GL_TEXTURE_2D, G);
  const unsigned char checker[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, checker);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  glViewport(0, 0, kSize, kSize);
  glScissor(0, 0, kSize, kSize);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, kSize, 0, kSize, -1, 1);  // window coordinates; window depth (1 - z) / 2: z = 1 near, -1 far
  glMatrixMode(GL_MODELVIEW);
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  glLoadMatrixf(identity);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1);
  glDepthRange(0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glShadeModel(GL_SMOOTH);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glEnable(GL_TEXTURE_2D);
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);

  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(0, 0, 0, white);
  expect(0, 0, 200, 100, 50, "modulate-white");
  array_quad(1, 0, 0, tint);  // 200*128/255 = 100.4, 100*255/255, 50*64/255 = 12.5(5)
  expect(1, 0, 100, 100, 13, "modulate-vertex-colour");

  array_quad(2, 0, 0, white);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glBindTexture(GL_TEXTURE_2D, B);
  array_quad(2, 0, 0, white);  // (255*128 + 200*127) / 255 = 227.6; 100*127/255 = 49.8; 50*127/255 = 24.9
  expect(2, 0, 228, 50, 25, "blend-src-alpha");
  glDisable(GL_BLEND);

  // Two units: A on unit 0, C (RGB) on unit 1, both MODULATE: 200*128/255 = 100.4, 100*128/255 = 50.2, 50*128/255 = 25.1.
  active_texture(GL_TEXTURE1_ARB);
  client_active_texture(GL_TEXTURE1_ARB);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glEnable(GL_TEXTURE_2D);
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glBindTexture(GL_TEXTURE_2D, C);
  active_texture(GL_TEXTURE0_ARB);
  client_active_texture(GL_TEXTURE0_ARB);
  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(3, 0, 0, white);
  expect(3, 0, 100, 50, 25, "two-units-modulate");
  active_texture(GL_TEXTURE1_ARB);
  client_active_texture(GL_TEXTURE1_ARB);
  glDisable(GL_TEXTURE_2D);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  active_texture(GL_TEXTURE0_ARB);
  client_active_texture(GL_TEXTURE0_ARB);

  // 2D through glBegin / glEnd: ADD of D (10, 20, 30) to the colour 100/255.
  glDisableClientState(GL_COLOR_ARRAY);
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_ADD);
  glBindTexture(GL_TEXTURE_2D, D);
  immediate_quad(4, 0, 100 / 255.0f, 100 / 255.0f, 100 / 255.0f, 1);
  expect(4, 0, 110, 120, 130, "add-immediate");
  // DECAL of B (alpha 128) over blue: 255*128/255 = 128, 0, 255*127/255 = 127.
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_DECAL);
  glBindTexture(GL_TEXTURE_2D, B);
  immediate_quad(5, 0, 0, 0, 1, 1);
  expect(5, 0, 128, 0, 127, "decal");
  // REPLACE of an RGB texture.
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glBindTexture(GL_TEXTURE_2D, D);
  immediate_quad(6, 0, 1, 1, 1, 1);
  expect(6, 0, 10, 20, 30, "replace");
  glEnableClientState(GL_COLOR_ARRAY);
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);

  // Depth: A near (z = 0.5), then D farther (z = -0.5) with LESS: A stays.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(7, 0, 0.5f, white);
  glBindTexture(GL_TEXTURE_2D, D);
  array_quad(7, 0, -0.5f, white);
  expect(7, 0, 200, 100, 50, "depth-less");
  // Polygon offset: A at z = 0, then D at the same depth pulled forward by glPolygonOffset(-1, -2): D wins.
  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(0, 1, 0, white);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1, -2);
  glBindTexture(GL_TEXTURE_2D, D);
  array_quad(0, 1, 0, white);
  glDisable(GL_POLYGON_OFFSET_FILL);
  expect(0, 1, 10, 20, 30, "polygon-offset");
  // Depth mask off: D drawn near without writing depth, then A farther still passes.
  glDepthMask(GL_FALSE);
  array_quad(1, 1, 0.5f, white);
  glDepthMask(GL_TRUE);
  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(1, 1, -0.5f, white);
  expect(1, 1, 200, 100, 50, "depth-mask");
  glDisable(GL_DEPTH_TEST);

  // Culling: back faces culled; the clockwise quad disappears, the counter-clockwise one stays.
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  array_quad(2, 1, 0, white, true);
  expect(2, 1, 0, 0, 0, "cull-back");
  array_quad(3, 1, 0, white, false, true);  // a triangle strip of unsigned shorts
  expect(3, 1, 200, 100, 50, "cull-front-kept-strip");
  glCullFace(GL_FRONT);
  array_quad(4, 1, 0, white);
  expect(4, 1, 0, 0, 0, "cull-front");
  glDisable(GL_CULL_FACE);

  // Alpha test GEQUAL 0.5 (reference 128): E (alpha 100) fails over A, B (alpha 128) passes.
  array_quad(5, 1, 0, white);
  glEnable(GL_ALPHA_TEST);
  glAlphaFunc(GL_GEQUAL, 0.5f);
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glBindTexture(GL_TEXTURE_2D, E);
  array_quad(5, 1, 0, white);
  expect(5, 1, 200, 100, 50, "alpha-test-fail");
  glBindTexture(GL_TEXTURE_2D, B);
  array_quad(6, 1, 0, white);
  expect(6, 1, 255, 0, 0, "alpha-test-pass");
  glDisable(GL_ALPHA_TEST);

  // Additive blending (ONE, ONE): A then D: 210, 120, 80.
  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(7, 1, 0, white);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBindTexture(GL_TEXTURE_2D, D);
  array_quad(7, 1, 0, white);
  expect(7, 1, 210, 120, 80, "blend-one-one");
  // Multiplicative blending (DST_COLOR, ZERO): A then C: 100, 50, 25.
  glDisable(GL_BLEND);
  glBindTexture(GL_TEXTURE_2D, A);
  array_quad(0, 2, 0, white);
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);
  glBindTexture(GL_TEXTURE_2D, C);
  array_quad(0, 2, 0, white);
  expect(0, 2, 100, 50, 25, "blend-dst-colour");
  glDisable(GL_BLEND);
  glTexEnvf(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);

  // Anisotropic sampler (max 4) on a flat texture; NEAREST texels of G in the screen's corners.
  glBindTexture(GL_TEXTURE_2D, F);
  array_quad(1, 2, 0, white);
  expect(1, 2, 200, 100, 50, "anisotropic");
  glBindTexture(GL_TEXTURE_2D, G);
  array_quad(2, 2, 0, white);
  std::fprintf(checks, "%d %d 255 0 0 nearest-bottom-left\n", 2 * 8 + 1, kSize - 1 - (2 * 8 + 1));
  std::fprintf(checks, "%d %d 0 0 255 nearest-top-left\n", 2 * 8 + 1, kSize - 1 - (2 * 8 + 6));
  std::fprintf(checks, "%d %d 255 255 255 nearest-top-right\n", 2 * 8 + 6, kSize - 1 - (2 * 8 + 6));

  // glTexSubImage2D: G's top-right texel replaced by grey (128, 128, 128); the other texels stay.
  const unsigned char grey_texel[4] = {128, 128, 128, 255};
  glTexSubImage2D(GL_TEXTURE_2D, 0, 1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, grey_texel);
  array_quad(6, 2, 0, white);
  std::fprintf(checks, "%d %d 128 128 128 sub-image-top-right\n", 6 * 8 + 6, kSize - 1 - (2 * 8 + 6));
  std::fprintf(checks, "%d %d 0 0 255 sub-image-top-left-kept\n", 6 * 8 + 1, kSize - 1 - (2 * 8 + 6));

  // Scissored clear: region (3, 2) only, to 0.2, 0.4, 0.6 (51, 102, 153).
  glEnable(GL_SCISSOR_TEST);
  glScissor(3 * 8, 2 * 8, 8, 8);
  glClearColor(0.2f, 0.4f, 0.6f, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  expect(3, 2, 51, 102, 153, "scissor-clear");
  expect(4, 2, 0, 0, 0, "outside-scissor");

  // Texturing off: the vertex colour.
  glDisable(GL_TEXTURE_2D);
  array_quad(5, 2, 0, blue);
  expect(5, 2, 0, 0, 255, "untextured");
  glEnable(GL_TEXTURE_2D);

  // S3TC internal formats (GL_EXT_texture_compression_s3tc) with RGBA data: the driver compresses.
  // Flat blocks of 565-exact colours (0 or 255 per channel) decode exactly whatever the encoder; the
  // alpha is the format's: RGB DXT1 reads 1.0, RGBA DXT1 keeps 1 bit (alpha < 128: code 3,
  // transparent black), DXT3 4 bits (100 -> round(100 * 15 / 255) = 6 -> 6 * 17 = 102), DXT5 8 bits
  // (100 exactly: an endpoint). Each blended (SRC_ALPHA, ONE_MINUS_SRC_ALPHA) over A's orange (200, 100, 50).
  const unsigned char white_alpha0[4] = {255, 255, 255, 0}, red_alpha100[4] = {255, 0, 0, 100},
                      white_alpha200[4] = {255, 255, 255, 200}, white_alpha100[4] = {255, 255, 255, 100};
  const GLuint H =
      flat_texture(4, 4, white_alpha0, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, true, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT);
  const GLuint I =
      flat_texture(4, 4, red_alpha100, GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, true, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT);
  const GLuint J = flat_texture(8, 8, white_alpha200, GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, false, GL_LINEAR, GL_REPEAT);
  const GLuint K =
      flat_texture(4, 4, white_alpha100, GL_COMPRESSED_RGBA_S3TC_DXT3_EXT, true, GL_NEAREST_MIPMAP_NEAREST, GL_REPEAT);
  const GLuint L = flat_texture(4, 4, white_alpha100, GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, true, GL_LINEAR_MIPMAP_NEAREST,
                                GL_CLAMP_TO_EDGE);
  const GLuint s3tc[4] = {H, I, J, K};
  const char* s3tc_names[4] = {"s3tc-dxt1-rgb-alpha-1", "s3tc-dxt1-rgba-transparent", "s3tc-dxt1-rgba-opaque",
                               "s3tc-dxt3-alpha-102"};
  // 255 (alpha 1); (200, 100, 50) (alpha 0: the destination stays); 255 (alpha 200 -> 255);
  // (255 * 102 + {200, 100, 50} * 153) / 255 = 222, 162, 132 exactly.
  const int s3tc_expected[4][3] = {{255, 255, 255}, {200, 100, 50}, {255, 255, 255}, {222, 162, 132}};
  for (int i = 0; i < 5; ++i) {
    const int rx = i, ry = 3;
    glBindTexture(GL_TEXTURE_2D, A);
    array_quad(rx, ry, 0, white);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glBindTexture(GL_TEXTURE_2D, i < 4 ? s3tc[i] : L);
    array_quad(rx, ry, 0, white);
    glDisable(GL_BLEND);
    if (i < 4) expect(rx, ry, s3tc_expected[i][0], s3tc_expected[i][1], s3tc_expected[i][2], s3tc_names[i]);
  }
  // DXT5: (255 * 100 + {200, 100, 50} * 155) / 255 = 221.57, 160.78, 130.39 -> 222, 161, 130.
  expect(4, 3, 222, 161, 130, "s3tc-dxt5-alpha-100");
  // glTexSubImage2D on whole blocks of an S3TC level: J's top-right 4 x 4 block black (NEAREST: texel
  // (x, y) under pixel (x, y) of the region); the other blocks stay white.
  glBindTexture(GL_TEXTURE_2D, J);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  std::vector<unsigned char> black_block(4 * 4 * 4, 0);
  for (size_t i = 3; i < black_block.size(); i += 4) black_block[i] = 255;
  glTexSubImage2D(GL_TEXTURE_2D, 0, 4, 4, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, black_block.data());
  array_quad(5, 3, 0, white);
  std::fprintf(checks, "%d %d 0 0 0 s3tc-sub-image-top-right\n", 5 * 8 + 6, kSize - 1 - (3 * 8 + 6));
  std::fprintf(checks, "%d %d 255 255 255 s3tc-sub-image-bottom-left-kept\n", 5 * 8 + 1, kSize - 1 - (3 * 8 + 1));
  if (with_bad_s3tc) {  // a sub-image of an S3TC level off the 4 x 4 grid: GL_INVALID_OPERATION, refused
    glTexSubImage2D(GL_TEXTURE_2D, 0, 2, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, black_block.data());
    array_quad(6, 3, 0, white);
  }

  if (with_unsupported) {
    glEnable(GL_FOG);
    glBindTexture(GL_TEXTURE_2D, A);
    array_quad(7, 2, 0, white);
    glDisable(GL_FOG);
    glLineWidth(2);
  }
  glDeleteTextures(1, &E);
  glFinish();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: gl_replay_program CHECKS_FILE [unsupported | bad-s3tc]\n");
    return 2;
  }
  const bool with_unsupported = argc > 2 && std::strcmp(argv[2], "unsupported") == 0;
  const bool with_bad_s3tc = argc > 2 && std::strcmp(argv[2], "bad-s3tc") == 0;
  checks = std::fopen(argv[1], "w");
  if (!checks) return 2;
  Display* dpy = XOpenDisplay(nullptr);
  if (!dpy) {
    std::fprintf(stderr, "gl_replay_program: no X display\n");
    return 2;
  }
  int attribs[] = {GLX_RGBA, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24, None};
  XVisualInfo* vi = glXChooseVisual(dpy, DefaultScreen(dpy), attribs);
  if (!vi) {
    std::fprintf(stderr, "gl_replay_program: no RGB visual with a depth buffer\n");
    return 2;
  }
  XSetWindowAttributes swa{};
  swa.colormap = XCreateColormap(dpy, RootWindow(dpy, vi->screen), vi->visual, AllocNone);
  const Window win = XCreateWindow(dpy, RootWindow(dpy, vi->screen), 0, 0, kSize, kSize, 0, vi->depth, InputOutput, vi->visual,
                                   CWColormap, &swa);
  XMapWindow(dpy, win);
  GLXContext ctx = glXCreateContext(dpy, vi, nullptr, True);
  glXMakeCurrent(dpy, win, ctx);
  active_texture = reinterpret_cast<PFNGLACTIVETEXTUREARBPROC>(glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glActiveTextureARB")));
  client_active_texture = reinterpret_cast<PFNGLCLIENTACTIVETEXTUREARBPROC>(
      glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glClientActiveTextureARB")));
  lock_arrays = reinterpret_cast<PFNGLLOCKARRAYSEXTPROC>(glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glLockArraysEXT")));
  unlock_arrays = reinterpret_cast<PFNGLUNLOCKARRAYSEXTPROC>(glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glUnlockArraysEXT")));
  if (!active_texture || !client_active_texture || !lock_arrays || !unlock_arrays) {
    std::fprintf(stderr, "gl_replay_program: GL_ARB_multitexture or GL_EXT_compiled_vertex_array missing\n");
    return 2;
  }
  draw_frame(with_unsupported, with_bad_s3tc);
  glXSwapBuffers(dpy, win);
  glXMakeCurrent(dpy, None, nullptr);
  glXDestroyContext(dpy, ctx);
  XDestroyWindow(dpy, win);
  XCloseDisplay(dpy);
  std::fclose(checks);
  return 0;
}
