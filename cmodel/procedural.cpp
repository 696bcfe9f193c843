#include "cmodel/procedural.hpp"
#include "cmodel/procedural_truth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <numbers>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"

namespace tfu {
namespace {

constexpr int kMaxProceduralSize = 4096;
constexpr int kTextOversample = 4;  // text: glyphs rendered at 4x the texture resolution

double frac(double x) { return x - std::floor(x); }
double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
std::array<double, 4> grey(double v) { return {v, v, v, 1.0}; }

uint8_t to_unorm8(double v) { return static_cast<uint8_t>(std::lround(clamp01(v) * 255.0)); }

// Periodic (wrap-around) distance along one axis of the unit torus.
double wrapped_delta(double a, double b) {
  const double d = std::fabs(frac(a) - frac(b));
  return std::min(d, 1.0 - d);
}

// 32-bit integer hash (lowbias32, C. Wellons) -> value in [0, 1].
double hash01(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return static_cast<double>(x) / 4294967295.0;
}

// One octave of value noise with a cells x cells periodic lattice, smoothstep-interpolated.
double value_noise(double s, double t, int cells, uint32_t seed) {
  const double x = frac(s) * cells, y = frac(t) * cells;
  const int i0 = static_cast<int>(std::floor(x)), j0 = static_cast<int>(std::floor(y));
  const double fx = x - i0, fy = y - j0;
  const auto lattice = [&](int i, int j) {
    const auto iu = static_cast<uint32_t>(wrap_repeat(i, cells)), ju = static_cast<uint32_t>(wrap_repeat(j, cells));
    return hash01(iu * 73856093U ^ ju * 19349663U ^ seed * 83492791U);
  };
  const auto smooth = [](double f) { return f * f * (3.0 - 2.0 * f); };
  const double wx = smooth(fx), wy = smooth(fy);
  const double top = lattice(i0, j0) * (1 - wx) + lattice(i0 + 1, j0) * wx;
  const double bottom = lattice(i0, j0 + 1) * (1 - wx) + lattice(i0 + 1, j0 + 1) * wx;
  return top * (1 - wy) + bottom * wy;
}

void check_size(const std::string& name, int size) {
  if (size < 1 || size > kMaxProceduralSize)
    throw InputError(fmt::format("procedural texture '{}': size {} outside 1..{}", quote_input(name), size, kMaxProceduralSize));
}

constexpr const char* kTextPhrases[] = {
    "The quick brown fox jumps over the lazy dog. ",
    "Texture filtering: bilinear, trilinear, cubic. ",
    "Edge-preserving magnification (Lee & Jen 2003). ",
    "High-quality filtering on graphics hardware. ",
};
constexpr int kTextPhraseCount = static_cast<int>(std::size(kTextPhrases));

// One line of text starting with phrase `first`, rendered by OpenImageIO into a strip of
// width x height 8-bit coverage with its baseline at row `baseline`.
std::vector<uint8_t> render_text_strip(int first, int width, int height, int baseline, int font_px) {
  std::string line;
  for (int r = 0; r < 8; ++r) line += kTextPhrases[(first + r) % kTextPhraseCount];
  // Only what fits (DejaVu Sans advances are >= 0.3 em): OpenImageIO composites every glyph.
  line.resize(std::min(line.size(), static_cast<size_t>(width / (0.3 * font_px)) + 1));
  OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::UINT8));
  OIIO::ImageBufAlgo::zero(buf);
  const float white[1] = {1.0f};
  if (!OIIO::ImageBufAlgo::render_text(buf, 0, baseline, line, font_px, "DejaVuSans", white))
    throw InputError(fmt::format("procedural texture 'text': cannot render with font DejaVuSans ({}); "
                                 "install fonts-dejavu-core",
                                 buf.geterror()));
  std::vector<uint8_t> strip(static_cast<size_t>(width) * static_cast<size_t>(height));
  if (!buf.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, 1), OIIO::TypeDesc::UINT8, strip.data()))
    throw InputError(fmt::format("procedural texture 'text': {}", buf.geterror()));
  return strip;
}

// Renders `lines` lines of text (coverage, 255 = ink) into an n x n 8-bit buffer. Line k starts
// with phrase k mod 4 and is shifted by one of three horizontal offsets. Glyph rendering through
// OpenImageIO costs about 0.3 us per glyph pixel, so each of the four distinct lines is rendered
// once into a strip and copied (max-composited) into place.
std::vector<uint8_t> render_text_coverage(int n, int lines) {
  const double line_height = static_cast<double>(n) / lines;
  const int font_px = std::max(1, static_cast<int>(0.72 * line_height));
  const int strip_h = static_cast<int>(std::ceil(line_height)) + 2;
  const int strip_baseline = static_cast<int>(0.78 * line_height);
  const int shift = static_cast<int>(0.11 * n), margin = static_cast<int>(0.03 * n);
  const int strip_w = n + 2 * shift;  // line k is drawn at x = margin - shift (k mod 3)
  std::vector<std::vector<uint8_t>> strips;
  for (int r = 0; r < std::min(lines, kTextPhraseCount); ++r)
    strips.push_back(render_text_strip(r, strip_w, strip_h, strip_baseline, font_px));
  std::vector<uint8_t> cov(static_cast<size_t>(n) * static_cast<size_t>(n), 0);
  for (int k = 0; k < lines; ++k) {
    const std::vector<uint8_t>& strip = strips[static_cast<size_t>(k % kTextPhraseCount)];
    const int x0 = margin - shift * (k % 3);
    const int y0 = static_cast<int>((k + 0.78) * line_height) - strip_baseline;
    for (int sy = 0; sy < strip_h; ++sy) {
      const int y = y0 + sy;
      if (y < 0 || y >= n) continue;
      for (int x = std::max(0, x0); x < std::min(n, x0 + strip_w); ++x) {
        uint8_t& dst = cov[static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x)];
        dst = std::max(dst, strip[static_cast<size_t>(sy) * static_cast<size_t>(strip_w) + static_cast<size_t>(x - x0)]);
      }
    }
  }
  return cov;
}

}  // namespace

Texture texture_from_function(const ColourFn& eval, int size) {
  Image img(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const auto c = eval((i + 0.5) / size, (j + 0.5) / size);
      img.at(i, j) = Rgba8{to_unorm8(c[0]), to_unorm8(c[1]), to_unorm8(c[2]), to_unorm8(c[3])};
    }
  Texture tex;
  tex.format = TexelFormat::RGBA8;
  tex.levels.push_back(std::move(img));
  return tex;
}

Procedural make_checkerboard(int size, int cells) {
  check_size("checkerboard", size);
  ColourFn eval = [cells](double s, double t) {
    const auto a = static_cast<int64_t>(std::floor(s * cells)), b = static_cast<int64_t>(std::floor(t * cells));
    return grey(((a + b) & 1) != 0 ? 0.1 : 0.9);
  };
  return {"checkerboard", texture_from_function(eval, size), eval};
}

Rgba8 mip_level_colour(int level) {
  // Hue steps that keep neighbouring levels apart (the trilinear blend of two neighbours is never
  // another level's colour): red, yellow, green, cyan, blue, magenta, white, grey, orange, violet,
  // dark green, brown.
  static constexpr Rgba8 kColours[] = {{255, 0, 0, 255},   {255, 255, 0, 255},   {0, 255, 0, 255},    {0, 255, 255, 255},
                                       {0, 0, 255, 255},   {255, 0, 255, 255},   {255, 255, 255, 255}, {128, 128, 128, 255},
                                       {255, 128, 0, 255}, {128, 0, 255, 255},   {0, 128, 64, 255},    {96, 48, 0, 255}};
  constexpr int n = static_cast<int>(std::size(kColours));
  return kColours[static_cast<size_t>(((level % n) + n) % n)];
}

bool procedural_truth_is_level0_only(const std::string& source) {
  const std::string name = "proc:mip_colours";
  return source.rfind(name, 0) == 0 && (source.size() == name.size() || source[name.size()] == ':');
}

Procedural make_mip_colours(int size) {
  check_size("mip_colours", size);
  if ((size & (size - 1)) != 0) throw InputError(fmt::format("procedural texture 'mip_colours': size {} is not a power of two", size));
  Texture tex;
  tex.format = TexelFormat::RGBA8;
  for (int l = 0, w = size; w >= 1; ++l, w /= 2) {
    Image img(w, w);
    for (Rgba8& t : img.texels) t = mip_level_colour(l);
    tex.levels.push_back(std::move(img));
  }
  const Rgba8 c0 = mip_level_colour(0);
  ColourFn eval = [c0](double, double) {
    return std::array<double, 4>{c0.r / 255.0, c0.g / 255.0, c0.b / 255.0, c0.a / 255.0};
  };
  return {"mip_colours", std::move(tex), eval};
}

Procedural make_zoneplate(int size) {
  check_size("zoneplate", size);
  const double n = size;
  ColourFn eval = [n](double s, double t) {
    const double ds = frac(s) - 0.5, dt = frac(t) - 0.5;
    return grey(0.5 + 0.5 * std::cos(std::numbers::pi * n * (ds * ds + dt * dt)));
  };
  return {"zoneplate", texture_from_function(eval, size), eval};
}

Procedural make_lightmap(int size) {
  check_size("lightmap", size);
  // Low-frequency ambient term plus Gaussian light spots (wrapped distance: period 1). The spots are
  // 2..4 texels wide at size 64, so magnification shows the reconstruction filter's shape.
  struct Spot {
    double s, t, sigma;
    std::array<double, 3> colour;
  };
  static constexpr Spot kSpots[] = {
      {0.30, 0.35, 0.060, {0.85, 0.60, 0.25}},
      {0.72, 0.68, 0.045, {0.30, 0.50, 0.85}},
      {0.16, 0.80, 0.030, {0.80, 0.80, 0.80}},
      {0.62, 0.20, 0.035, {0.35, 0.75, 0.35}},
  };
  ColourFn eval = [](double s, double t) {
    constexpr double two_pi = 2.0 * std::numbers::pi;
    const double ambient = 0.18 + 0.08 * std::cos(two_pi * s) * std::cos(two_pi * t);
    std::array<double, 4> c{ambient, ambient, ambient, 1.0};
    for (const Spot& spot : kSpots) {
      const double ds = wrapped_delta(s, spot.s), dt = wrapped_delta(t, spot.t);
      const double g = std::exp(-(ds * ds + dt * dt) / (2 * spot.sigma * spot.sigma));
      for (size_t i = 0; i < 3; ++i) c[i] += g * spot.colour[i];
    }
    for (size_t i = 0; i < 3; ++i) c[i] = clamp01(c[i]);
    return c;
  };
  return {"lightmap", texture_from_function(eval, size), eval};
}

Procedural make_noise(int size, int cells) {
  check_size("noise", size);
  ColourFn eval = [cells](double s, double t) {
    const double v = 0.65 * value_noise(s, t, cells, 1) + 0.35 * value_noise(s, t, 2 * cells, 2);
    return std::array<double, 4>{v, 0.25 + 0.6 * v * v, 1.0 - 0.7 * v, 1.0};
  };
  return {"noise", texture_from_function(eval, size), eval};
}

Procedural make_text(int size, int lines) {
  check_size("text", size);
  const int n = size * kTextOversample;
  auto cov = std::make_shared<const std::vector<uint8_t>>(render_text_coverage(n, lines));
  // Analytic stand-in: bilinear lookup (repeat wrap) into the 4x-oversampled coverage image.
  ColourFn eval = [cov, n](double s, double t) {
    const double x = frac(s) * n - 0.5, y = frac(t) * n - 0.5;
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    const auto c = [&](int i, int j) {
      return (*cov)[static_cast<size_t>(wrap_repeat(j, n)) * static_cast<size_t>(n) +
                    static_cast<size_t>(wrap_repeat(i, n))] / 255.0;
    };
    const double v = (c(x0, y0) * (1 - fx) + c(x0 + 1, y0) * fx) * (1 - fy) +
                     (c(x0, y0 + 1) * (1 - fx) + c(x0 + 1, y0 + 1) * fx) * fy;
    return grey(1.0 - v);
  };
  // The texels: 4x4 box average of the oversampled coverage (area-weighted glyph coverage).
  Image img(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      int sum = 0;
      for (int y = 0; y < kTextOversample; ++y)
        for (int x = 0; x < kTextOversample; ++x)
          sum += (*cov)[static_cast<size_t>(j * kTextOversample + y) * static_cast<size_t>(n) +
                        static_cast<size_t>(i * kTextOversample + x)];
      const auto v = static_cast<uint8_t>(255 - (sum + kTextOversample * kTextOversample / 2) /
                                                    (kTextOversample * kTextOversample));
      img.at(i, j) = Rgba8{v, v, v, 255};
    }
  Texture tex;
  tex.levels.push_back(std::move(img));
  return {"text", std::move(tex), eval};
}

const std::vector<std::string>& procedural_names() {
  static const std::vector<std::string> names{"checkerboard", "text", "zoneplate", "lightmap", "noise", "mip_colours"};
  return names;
}

namespace {

Procedural make_procedural_texels(const std::string& name, int size) {
  if (name == "checkerboard") return make_checkerboard(size, std::clamp(size / 8, 1, 16));
  if (name == "text") return make_text(size, std::clamp(size / 32, 2, 32));
  if (name == "zoneplate") return make_zoneplate(size);
  if (name == "lightmap") return make_lightmap(size);
  if (name == "noise") return make_noise(size, std::clamp(size / 16, 2, 16));
  if (name == "mip_colours") return make_mip_colours(size);
  throw InputError(fmt::format("unknown procedural texture '{}' ({}valid: {})", quote_input(name),
                               did_you_mean(name, procedural_names()), fmt::join(procedural_names(), ", ")));
}

}  // namespace

Procedural make_procedural(const std::string& name, int size) {
  // Charged before the texels are made, for the chain load_texture_spec generates (cmodel/memory_budget.hpp).
  auto charge = std::make_shared<MemoryCharge>(mip_chain_bytes(size, size),
                                               fmt::format("texture 'proc:{}:{}'", quote_input(name, 40), size), "decoded texels");
  Procedural p = make_procedural_texels(name, size);
  p.texture.memory = std::move(charge);
  return p;
}

}  // namespace tfu
