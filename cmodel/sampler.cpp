#include "cmodel/sampler.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "cmodel/datapath.hpp"
#include "cmodel/edge_filter.hpp"
#include "cmodel/error.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/kernels.hpp"
#include "cmodel/unorm.hpp"

namespace tfu {

// ---------------------------------------------------------------- names
namespace {
const char* base_name(BaseFilter b) {
  switch (b) {
    case BaseFilter::Nearest: return "NEAREST";
    case BaseFilter::Linear: return "LINEAR";
    case BaseFilter::Cubic: return "CUBIC";
    case BaseFilter::EdgePreserving: return "EDGE_PRESERVING";
  }
  return "?";
}
}  // namespace

FilterMode filter_mode_from_name(const std::string& name) {
  std::string n;
  for (char ch : name) n += ch == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  for (const FilterMode& m : all_filter_modes())
    if (filter_mode_name(m) == n) return m;
  std::string list;
  for (const FilterMode& m : all_filter_modes()) list += (list.empty() ? "" : ", ") + filter_mode_name(m);
  throw InputError(fmt::format("unknown filter '{}' (expected one of {})", quote_input(name), list));
}

std::string filter_mode_name(FilterMode m) {
  std::string s = base_name(m.base);
  if (m.mip == MipMode::Nearest) s += "_MIPMAP_NEAREST";
  if (m.mip == MipMode::Linear) s += "_MIPMAP_LINEAR";
  return s;
}

const std::vector<FilterMode>& all_filter_modes() {
  static const std::vector<FilterMode> modes = [] {
    std::vector<FilterMode> v;
    for (BaseFilter b : {BaseFilter::Nearest, BaseFilter::Linear, BaseFilter::Cubic, BaseFilter::EdgePreserving})
      for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear}) v.push_back({b, m});
    return v;
  }();
  return modes;
}

std::vector<std::string> cubic_kernel_names() {
  std::vector<std::string> v = FilterKernel::names();
  v.emplace_back(kBsplineInterp);
  return v;
}

std::string checked_cubic_kernel_name(const std::string& name) {
  std::string list;
  for (const std::string& k : cubic_kernel_names()) {
    if (k == name) return name;
    list += (list.empty() ? "" : ", ") + k;
  }
  throw InputError(fmt::format("unknown kernel '{}' (valid: {})", quote_input(name), list));
}

// ---------------------------------------------------------------- B-spline prefilter (offline)
namespace {

// Cubic B-spline interpolation coefficients (Unser's recursive filter, pole z = sqrt(3) - 2) of a
// periodic sequence; mirror boundaries are handled by the caller as a periodic sequence of length 2N.
std::vector<double> bspline_coefficients_periodic(const std::vector<double>& x) {
  const size_t n = x.size();
  if (n == 1) return x;
  const double z = std::sqrt(3.0) - 2.0;
  constexpr int kTerms = 40;  // |z|^40 < 1e-22
  std::vector<double> cp(n), c(n);
  double acc = 0, zk = 1;
  for (int k = 0; k < kTerms; ++k, zk *= z) acc += zk * 6.0 * x[(n - static_cast<size_t>(k) % n) % n];
  cp[0] = acc;
  for (size_t i = 1; i < n; ++i) cp[i] = 6.0 * x[i] + z * cp[i - 1];
  acc = 0;
  zk = z;
  for (int k = 0; k < kTerms; ++k, zk *= z) acc -= zk * cp[(n - 1 + static_cast<size_t>(k)) % n];
  c[n - 1] = acc;
  for (size_t i = n - 1; i-- > 0;) c[i] = z * (c[i + 1] - cp[i]);
  return c;
}

std::vector<double> bspline_coefficients(const std::vector<double>& x, WrapMode wrap) {
  if (wrap == WrapMode::Repeat) return bspline_coefficients_periodic(x);
  // Mirror (half-sample symmetric) extension: x0..xN-1 xN-1..x0, exact for mirrored-repeat, the
  // documented approximation for the clamp modes.
  std::vector<double> ext(x);
  ext.insert(ext.end(), x.rbegin(), x.rend());
  std::vector<double> c = bspline_coefficients_periodic(ext);
  c.resize(x.size());
  return c;
}

// Stored coefficient codes with a per-texture scale and bias (Hadwiger 2004 Sec. 3.2: "we fit them
// into this range using simple scale and bias operations"). The inverse of the B-spline's (1 4 1)/6
// amplifies by up to 3 per axis, so coefficients of data in [0, 1] can reach [-4, 5] in 2D; real
// textures use far less, so the range is fitted to the texture: two registers in Q.12,
//   S = round((c_max - c_min) 2^12),  B = round(255 c_min 2^12)   (c in units of full scale),
// codes q = clamp(round((255 c 2^12 - B) / S)), and the datapath decodes the filtered code sum as
//   out = floor((acc S + B M + M 2^11) / (M 2^12)),  acc = sum w q at weight scale M = 2^b - 1.
using dp::floor_div;
using dp::kBsplineScaleBits;

}  // namespace

// dp::tile_weights_2d (declared in datapath.hpp).
void dp::tile_weights_2d(const TileWeightRom& rom, RomRecon recon, uint32_t fu, uint32_t fv, std::array<int32_t, 16>& w2) {
  const int taps = rom.taps(), m0 = rom.first_tap();
  const unsigned bits = rom.spec().bits;
  std::array<int32_t, 8> wx{}, wy{};
  if (recon == RomRecon::Nearest) {
    rom.weights_nearest(fu, 8, wx.data());
    rom.weights_nearest(fv, 8, wy.data());
  } else {
    rom.weights_linear(fu, 8, 8, wx.data());
    rom.weights_linear(fv, 8, 8, wy.data());
  }
  const auto M = static_cast<int32_t>(unorm::max_code(bits));
  int32_t sum = 0;
  const int centre = -m0;
  for (int j = 0; j < taps; ++j)
    for (int i = 0; i < taps; ++i) {
      if (i == centre && j == centre) continue;
      const int32_t w = tile_weight_multiply(wx[static_cast<size_t>(i)], wy[static_cast<size_t>(j)], bits);
      w2[static_cast<size_t>(j * taps + i)] = w;
      sum += w;
    }
  w2[static_cast<size_t>(centre * taps + centre)] = M - sum;
}

namespace {

// Memo of tile_weights_2d for nearest reconstruction: the weights depend only on the two ROM
// addresses, so the software model evaluates the multipliers once per address pair (a pure
// function: bit-identical to computing them per sample, which the tests check), and looks the
// addresses of the 8-bit fractions up in two tables.
struct WeightMemo {
  static constexpr size_t kStride = 16;  // weights per address pair
  int entries = 0;
  std::vector<int32_t> w;                  // [(addr_y * entries + addr_x) * kStride + tap]
  std::array<uint32_t, 256> col{}, row{};  // addr_x and addr_y * entries of each fraction
  const int32_t* weights(uint32_t fu, uint32_t fv) const { return w.data() + kStride * (row[fv] + col[fu]); }
};

}  // namespace

struct Sampler::Impl {
  std::unique_ptr<FilterKernel> kernel;       // CUBIC modes
  std::unique_ptr<TileWeightRom> rom;         // CUBIC modes
  bool prefiltered = false;                   // bspline-interp
  int64_t bspline_scale_q = 0, bspline_bias_q = 0;  // S and B registers (Q.12)
  std::vector<Image> coeff_levels;            // bspline-interp: stored coefficient codes
  std::vector<std::vector<std::array<double, 4>>> coeff_ideal;  // bspline-interp: exact coefficients
  std::unique_ptr<WeightMemo> memo;           // CUBIC with nearest reconstruction and R <= 128
  dp::CubicNormalize norm;                    // CUBIC normalise-and-clamp registers
  Texel4 border{};
  double scale = 255.0;  // channel code -> real
};

// The fast paths of sample() (defined below, after the generic datapath).
struct Sampler::FastPaths {
  enum class Path { Linear8, Cubic8, Edge8 };
  struct Variant {  // what an instantiation is specialized for
    Path path;
    bool mipmapped;  // MipMode other than None
    WrapMode ws, wt;
  };
  template <Variant kV>
  static auto filter(const Sampler& sm, int level, float s, float t);
  template <Variant kV>
  static Rgba8 sample(const Sampler& sm, float s, float t, int32_t lambda);
  template <Variant kV>
  static void batch(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out);  // Linear8 only
  template <Path kP, bool kMip, size_t... k>
  static constexpr std::array<SampleFn, 16> wrap_table(std::index_sequence<k...>);
  template <bool kMip, size_t... k>
  static constexpr std::array<BatchFn, 16> batch_table(std::index_sequence<k...>);
  template <Path kP>
  static SampleFn pick(bool mipmapped, WrapMode ws, WrapMode wt);
  // Chooses sample()'s path once the configuration is known: the fast path where one exists
  // (8-bit formats; for CUBIC also 4 x 4 taps and memoized weights), else the generic datapath;
  // and sample_batch()'s: LINEAR's batch variant where sample() has the LINEAR fast path, else a
  // loop over sample() (CUBIC and EDGE_PRESERVING spend 500+ instructions a sample, against some 20
  // for the call, so a per-variant batch copy of them would double their code for little).
  static void setup(Sampler& sm);
};

// ---------------------------------------------------------------- construction
Sampler::Sampler(const Texture& tex, SamplerConfig cfg) : tex_(tex), cfg_(std::move(cfg)), impl_(new Impl) {
  tex_.validate("texture");
  impl_->border = decode_texel(cfg_.border, tex_.format);
  impl_->scale = tex_.format == TexelFormat::VS16X2 ? 32640.0 : 255.0;
  if (cfg_.edge_cache_block < 4 || cfg_.edge_cache_block > 64 ||
      (cfg_.edge_cache_block & (cfg_.edge_cache_block - 1)) != 0)
    throw InputError(fmt::format("edge cache block {} is not a power of two in 4..64", cfg_.edge_cache_block));
  if (cfg_.lod.min_lod_q8 > cfg_.lod.max_lod_q8) throw InputError("min-lod is above max-lod");
  if (cfg_.mode.base == BaseFilter::Cubic) build_cubic();
  FastPaths::setup(*this);
}

// CUBIC modes: kernel, tile-weight ROM, normalise registers, weight memo and, for bspline-interp,
// the prefiltered coefficient levels.
void Sampler::build_cubic() {
  cfg_.cubic_rom.validate();
  impl_->prefiltered = cfg_.kernel == kBsplineInterp;
  impl_->kernel = std::make_unique<FilterKernel>(
      impl_->prefiltered ? FilterKernel::bspline() : FilterKernel::by_name(cfg_.kernel));
  if (impl_->kernel->width() > 4)
    throw InputError(fmt::format("kernel '{}' is wider than the 4x4 CUBIC footprint", cfg_.kernel));
  impl_->rom = std::make_unique<TileWeightRom>(*impl_->kernel, cfg_.cubic_rom);
  impl_->norm.M = static_cast<int64_t>(unorm::max_code(impl_->rom->spec().bits));
  std::tie(impl_->norm.lo, impl_->norm.hi) = channel_range(tex_.format);
  if (cfg_.memoize_cubic_weights && cfg_.cubic_recon == RomRecon::Nearest && impl_->rom->entries() <= 129) {
    auto memo = std::make_unique<WeightMemo>();
    memo->entries = impl_->rom->entries();
    const auto entries = static_cast<size_t>(memo->entries);
    memo->w.resize(entries * entries * WeightMemo::kStride);
    // One representative fraction per address: the smallest 8-bit f that maps to it.
    std::vector<int> rep(entries, -1);
    for (uint32_t f = 0; f < 256; ++f) {
      const int a = impl_->rom->nearest_address(f, 8);
      if (rep[static_cast<size_t>(a)] < 0) rep[static_cast<size_t>(a)] = static_cast<int>(f);
      memo->col[f] = static_cast<uint32_t>(a);
      memo->row[f] = static_cast<uint32_t>(a) * static_cast<uint32_t>(entries);
    }
    for (size_t ay = 0; ay < entries; ++ay)
      for (size_t ax = 0; ax < entries; ++ax)
        if (rep[ax] >= 0 && rep[ay] >= 0) {
          std::array<int32_t, 16> w2{};
          dp::tile_weights_2d(*impl_->rom, RomRecon::Nearest, static_cast<uint32_t>(rep[ax]),
                              static_cast<uint32_t>(rep[ay]), w2);
          std::copy(w2.begin(), w2.end(), memo->w.begin() + static_cast<ptrdiff_t>((ay * entries + ax) * WeightMemo::kStride));
        }
    impl_->memo = std::move(memo);
  }
  if (!impl_->prefiltered) return;
  if (tex_.format == TexelFormat::VS16X2)
    throw InputError("kernel bspline-interp needs an 8-bit texel format (rgba8 or l8), not vs16x2");
  // Offline prefilter per level (double precision), then quantize with a fitted scale and bias.
  double cmin = 0.0, cmax = 1.0;
  for (const Image& lvl : tex_.levels) {
    const auto w = static_cast<size_t>(lvl.width), h = static_cast<size_t>(lvl.height);
    std::vector<std::array<double, 4>> c(w * h);
    for (size_t i = 0; i < c.size(); ++i)
      c[i] = {lvl.texels[i].r / 255.0, lvl.texels[i].g / 255.0, lvl.texels[i].b / 255.0, lvl.texels[i].a / 255.0};
    for (size_t ch = 0; ch < 4; ++ch) {
      std::vector<double> line;
      for (size_t y = 0; y < h; ++y) {
        line.resize(w);
        for (size_t x = 0; x < w; ++x) line[x] = c[y * w + x][ch];
        line = bspline_coefficients(line, cfg_.wrap_s);
        for (size_t x = 0; x < w; ++x) c[y * w + x][ch] = line[x];
      }
      for (size_t x = 0; x < w; ++x) {
        line.resize(h);
        for (size_t y = 0; y < h; ++y) line[y] = c[y * w + x][ch];
        line = bspline_coefficients(line, cfg_.wrap_t);
        for (size_t y = 0; y < h; ++y) c[y * w + x][ch] = line[y];
      }
    }
    for (const auto& px : c)
      for (double v : px) {
        cmin = std::min(cmin, v);
        cmax = std::max(cmax, v);
      }
    impl_->coeff_ideal.push_back(std::move(c));
  }
  constexpr double one = 1 << kBsplineScaleBits;
  impl_->bspline_scale_q = std::llround(std::ceil((cmax - cmin) * one));
  impl_->bspline_bias_q = std::llround(std::floor(255.0 * cmin * one));
  impl_->norm.prefiltered = true;
  impl_->norm.scale_q = impl_->bspline_scale_q;
  impl_->norm.bias_q = impl_->bspline_bias_q;
  const double S = static_cast<double>(impl_->bspline_scale_q), B = static_cast<double>(impl_->bspline_bias_q);
  const auto code = [S, B, one](double v) {
    return static_cast<uint8_t>(std::clamp(std::floor((255.0 * v * one - B) / S + 0.5), 0.0, 255.0));
  };
  for (size_t l = 0; l < tex_.levels.size(); ++l) {
    const auto& c = impl_->coeff_ideal[l];
    Image q(tex_.levels[l].width, tex_.levels[l].height);
    for (size_t i = 0; i < c.size(); ++i) q.texels[i] = {code(c[i][0]), code(c[i][1]), code(c[i][2]), code(c[i][3])};
    impl_->coeff_levels.push_back(std::move(q));
  }
}

Sampler::~Sampler() = default;

// ---------------------------------------------------------------- LOD -> levels (GL 4.6 Sec. 8.14)
namespace {

// Level select of the LOD unit: the level(s) and the blend weight for lambda after bias and clamp;
// q is the last level.
struct LevelPick {
  int level0 = 0, level1 = 0;
  int blend = 0;  // weight of level1 (Q.8)
};
inline LevelPick select_levels(int32_t lambda_q8, MipMode mip, int q) {
  LevelPick p;
  if (lambda_q8 <= 0) return p;  // c = 0: the magnification filter is the mode's first word
  switch (mip) {
    case MipMode::None: break;
    case MipMode::Nearest: {
      // d = lambda <= 1/2 ? 0 : ceil(lambda + 1/2) - 1
      const int d = lambda_q8 <= 128 ? 0 : (lambda_q8 + 127) >> kLodFracBits;
      p.level0 = p.level1 = std::min(d, q);
      break;
    }
    case MipMode::Linear:
      if (lambda_q8 >= (q << kLodFracBits)) {
        p.level0 = p.level1 = q;
      } else {
        p.level0 = lambda_q8 >> kLodFracBits;
        p.level1 = p.level0 + 1;
        p.blend = lambda_q8 & 255;
      }
      break;
  }
  return p;
}

}  // namespace

LodInfo Sampler::lod_info(int32_t lambda_unclamped) const {
  LodInfo li;
  li.lambda_q8 = lambda_bias_clamp(lambda_unclamped, cfg_.lod);
  li.magnify = li.lambda_q8 <= 0;
  const LevelPick p = select_levels(li.lambda_q8, cfg_.mode.mip, tex_.max_level());
  li.level0 = p.level0;
  li.level1 = p.level1;
  li.blend = p.blend;
  const Image& l0 = tex_.levels[static_cast<size_t>(li.level0)];
  li.level0_width = l0.width;
  li.level0_height = l0.height;
  li.kernel_scale = 1 << li.level0;
  return li;
}

// ---------------------------------------------------------------- texel fetch (wrap unit)
namespace {

using dp::LevelCoord;
using dp::texel_coord;

// Wrapped fetch that reads a given level image (the texture or the B-spline coefficients). The
// wrap unit maps each tap column and row once; a tap outside with clamp-to-border reads `border`.
struct LevelReader {
  const Image& img;
  WrapMode ws, wt;
  TexelFormat fmt;
  Texel4 border;
  int col(int64_t x) const { return wrap_index(ws, x, img.width); }
  int row(int64_t y) const { return wrap_index(wt, y, img.height); }
  Texel4 at(int wx, int wy) const {
    if ((wx | wy) < 0) return border;
    return decode_texel(img.texels[static_cast<size_t>(wy) * static_cast<size_t>(img.width) + static_cast<size_t>(wx)], fmt);
  }
  Texel4 operator()(int64_t x, int64_t y) const { return at(col(x), row(y)); }
};

}  // namespace

Texel4 Sampler::fetch(int level, int x, int y) const {
  const LevelReader rd{tex_.levels[static_cast<size_t>(level)], cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  return rd(x, y);
}

namespace {

Texel4 filter_nearest(const LevelReader& rd, float s, float t) {
  // GL: i = floor(s W), j = floor(t H)
  return rd(float_to_fixed(s, static_cast<uint32_t>(rd.img.width), 0),
            float_to_fixed(t, static_cast<uint32_t>(rd.img.height), 0));
}

Texel4 filter_linear(const LevelReader& rd, float s, float t) {
  const LevelCoord u = texel_coord(s, rd.img.width), v = texel_coord(t, rd.img.height);
  const int x0 = rd.col(u.i0), x1 = rd.col(u.i0 + 1), y0 = rd.row(v.i0), y1 = rd.row(v.i0 + 1);
  return dp::bilinear_lerp({rd.at(x0, y0), rd.at(x1, y0), rd.at(x0, y1), rd.at(x1, y1)}, u.f, v.f, rd.fmt);
}

// Accumulated sum c w per channel at weight scale M, for a compile-time tap count (2 or 4).
template <int taps>
std::array<int64_t, 4> filter_tiled_acc_n(const LevelReader& rd, const TileWeightRom& rom, RomRecon recon,
                                          const WeightMemo* memo, float s, float t) {
  const LevelCoord u = texel_coord(s, rd.img.width), v = texel_coord(t, rd.img.height);
  const int m0 = rom.first_tap();
  std::array<int32_t, 16> w2_local;
  const int32_t* w2;
  if (memo) {
    w2 = memo->weights(u.f, v.f);
  } else {
    dp::tile_weights_2d(rom, recon, u.f, v.f, w2_local);
    w2 = w2_local.data();
  }
  std::array<int, 4> col, row;
  wrap_run(rd.ws, u.i0 + m0, taps, rd.img.width, col.data());
  wrap_run(rd.wt, v.i0 + m0, taps, rd.img.height, row.data());
  if (rd.fmt != TexelFormat::VS16X2) {
    // 8-bit channels: |sum c w| <= 255 M (sum |h|)^2 < 2^31 for b <= 16, so 32 bits suffice.
    const Rgba8 border = encode_texel(rd.border, rd.fmt);
    // Two channels per 64-bit word, (R, B) and (G, A), in signed 32-bit lanes: modular arithmetic
    // keeps x = low + high 2^32 exactly, and each lane's true sum is below 2^31 in magnitude, so
    // both lanes are recovered exactly afterwards.
    uint64_t arb = 0, aga = 0;
    for (int j = 0; j < taps; ++j) {
      const int y = row[static_cast<size_t>(j)];
      for (int i = 0; i < taps; ++i) {
        const auto w = static_cast<uint64_t>(static_cast<int64_t>(w2[j * taps + i]));
        const int x = col[static_cast<size_t>(i)];
        const Rgba8 c = (x | y) < 0 ? border
                                    : rd.img.texels[static_cast<size_t>(y) * static_cast<size_t>(rd.img.width) +
                                                    static_cast<size_t>(x)];
        arb += (uint64_t{c.r} | (uint64_t{c.b} << 32)) * w;
        aga += (uint64_t{c.g} | (uint64_t{c.a} << 32)) * w;
      }
    }
    const auto lanes = [](uint64_t x) {
      const auto lo = static_cast<int32_t>(static_cast<uint32_t>(x));
      const auto hi = static_cast<int32_t>(static_cast<uint32_t>((x - static_cast<uint64_t>(static_cast<int64_t>(lo))) >> 32));
      return std::pair<int64_t, int64_t>{lo, hi};
    };
    const auto [r, b] = lanes(arb);
    const auto [g, a] = lanes(aga);
    return {r, g, b, a};
  }
  std::array<int64_t, 4> acc{};
  for (int j = 0; j < taps; ++j)
    for (int i = 0; i < taps; ++i) {
      const int32_t w = w2[j * taps + i];
      if (w == 0) continue;
      const Texel4 c = rd.at(col[static_cast<size_t>(i)], row[static_cast<size_t>(j)]);
      for (size_t ch = 0; ch < 4; ++ch) acc[ch] += int64_t{c[ch]} * w;
    }
  return acc;
}

std::array<int64_t, 4> filter_tiled_acc(const LevelReader& rd, const TileWeightRom& rom, RomRecon recon,
                                        const WeightMemo* memo, float s, float t) {
  return rom.taps() == 4 ? filter_tiled_acc_n<4>(rd, rom, recon, memo, s, t)
                         : filter_tiled_acc_n<2>(rd, rom, recon, memo, s, t);
}

}  // namespace

Texel4 Sampler::sample_level_filter(BaseFilter f, int level, float s, float t) const {
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  switch (f) {
    case BaseFilter::Nearest: return filter_nearest(rd, s, t);
    case BaseFilter::Linear: return filter_linear(rd, s, t);
    case BaseFilter::Cubic: {
      if (impl_->prefiltered) {
        const LevelReader cr{impl_->coeff_levels[static_cast<size_t>(level)], cfg_.wrap_s, cfg_.wrap_t,
                             TexelFormat::RGBA8, {}};
        return dp::cubic_normalize(filter_tiled_acc(cr, *impl_->rom, cfg_.cubic_recon, impl_->memo.get(), s, t), impl_->norm);
      }
      return dp::cubic_normalize(filter_tiled_acc(rd, *impl_->rom, cfg_.cubic_recon, impl_->memo.get(), s, t), impl_->norm);
    }
    case BaseFilter::EdgePreserving: {
      const EdgeFootprint fp = edge_footprint(level, s, t);
      return lee_jen::edge_preserving_interpolate(fp.texels, fp.mask, fp.xf, fp.yf, tex_.format);
    }
  }
  return {};
}

const TileWeightRom* Sampler::cubic_rom() const { return impl_->rom.get(); }
const dp::CubicNormalize& Sampler::cubic_normalize() const { return impl_->norm; }
const Image& Sampler::filtered_level(int level) const {
  return impl_->prefiltered ? impl_->coeff_levels.at(static_cast<size_t>(level)) : tex_.levels.at(static_cast<size_t>(level));
}

EdgeFootprint Sampler::edge_footprint(int level, float s, float t, int mask_override) const {
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  const LevelCoord u = texel_coord(s, img.width), v = texel_coord(t, img.height);
  EdgeFootprint fp;
  fp.xf = u.f;
  fp.yf = v.f;
  // Columns and rows -1..2 around the centre square, wrapped once each.
  wrap_run(cfg_.wrap_s, u.i0 - 1, 4, img.width, fp.col.data());
  wrap_run(cfg_.wrap_t, v.i0 - 1, 4, img.height, fp.row.data());
  fp.mask = lee_jen::kAllTexels;
  if (mask_override >= 0)
    fp.mask = static_cast<lee_jen::TexelMask>(mask_override & lee_jen::kAllTexels);
  else if (cfg_.edge_shape == EdgeShapePolicy::CacheBlock)
    fp.mask = lee_jen::cache_block_mask(fp.col[1], fp.col[2], fp.row[1], fp.row[2], cfg_.edge_cache_block);
  static const auto kPos = [] {
    std::array<lee_jen::TexelPos, lee_jen::kTexels> p{};
    for (int n = 1; n <= lee_jen::kTexels; ++n) p[static_cast<size_t>(n - 1)] = lee_jen::texel_pos(n);
    return p;
  }();
  for (size_t k = 0; k < fp.texels.size(); ++k)
    fp.texels[k] = ((fp.mask >> k) & 1u)
                       ? rd.at(fp.col[static_cast<size_t>(kPos[k].x + 1)], fp.row[static_cast<size_t>(kPos[k].y + 1)])
                       : Texel4{0, 0, 0, 0};
  return fp;
}

Rgba8 Sampler::sample_edge_masks(float s, float t, int32_t lambda, std::array<lee_jen::TexelMask, 2> masks) const {
  if (cfg_.mode.base != BaseFilter::EdgePreserving) throw InputError("sample_edge_masks needs an EDGE_PRESERVING mode");
  const LodInfo li = lod_info(lambda);
  const auto level = [&](int l, lee_jen::TexelMask m) {
    const EdgeFootprint fp = edge_footprint(l, s, t, m);
    return lee_jen::edge_preserving_interpolate(fp.texels, fp.mask, fp.xf, fp.yf, tex_.format);
  };
  Texel4 c = level(li.level0, masks[0]);
  if (li.blend != 0) c = dp::level_blend(c, level(li.level1, masks[1]), li.blend);
  return encode_texel(c, tex_.format);
}

Texel4 Sampler::sample_level(int level, float s, float t) const {
  return sample_level_filter(cfg_.mode.base, level, s, t);
}

Texel4 Sampler::sample_channels(float s, float t, int32_t lambda) const {
  const LodInfo li = lod_info(lambda);
  const Texel4 c0 = sample_level(li.level0, s, t);
  if (li.blend == 0) return c0;
  const Texel4 c1 = sample_level(li.level1, s, t);
  return dp::level_blend(c0, c1, li.blend);
}

Rgba8 Sampler::sample_generic(const Sampler& sm, float s, float t, int32_t lambda) {
  return encode_texel(sm.sample_channels(s, t, lambda), sm.tex_.format);
}

// ---------------------------------------------------------------- fast paths (software speed only)
// sample() of LINEAR, CUBIC and EDGE_PRESERVING runs one instantiation per pair of wrap modes, so
// that the wrap unit and the border select fold away, and reads texel words straight from the
// level. Same arithmetic, bit for bit, as the generic datapath above (sample_channels), which the
// tests compare them with.
namespace {

template <WrapMode kWs, WrapMode kWt>
inline constexpr bool kMayBorder = kWs == WrapMode::ClampToBorder || kWt == WrapMode::ClampToBorder;

// What the fast paths read of a level: the base address of its texel words and its extent (a
// value, so that a batch keeps it in registers: stores of results cannot change it).
struct LevelView {
  const Rgba8* texels;
  int width, height;
  explicit LevelView(const Image& img) : texels(img.texels.data()), width(img.width), height(img.height) {}
};

// Texel word at wrapped (x, y); a clamp-to-border tap (x or y = -1) reads the border word.
template <bool kBorder>
[[gnu::always_inline]] inline Rgba8 texel_word(LevelView img, int x, int y, Rgba8 border) {
  if (kBorder && (x | y) < 0) return border;
  return img.texels[static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x)];
}

// LINEAR on one level of an 8-bit format: address, wrap and the four texel words of lane k of q,
// then the same arithmetic as filter_linear (one rounding of the Q.16 sum) in dp::bilinear_lerp8,
// or in dp::bilinear_lerp8x4 for four lanes. The result of 8-bit inputs is always within 0..255.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline void bilinear8_taps(LevelView img, Rgba8 border, float s, float t, dp::Quad8& q, size_t k) {
  const LevelCoord u = texel_coord(s, img.width), v = texel_coord(t, img.height);
  int xs[2], ys[2];
  dp::wrap_taps<kWs, 2>(u.i0, img.width, xs);
  dp::wrap_taps<kWt, 2>(v.i0, img.height, ys);
  constexpr bool kB = kMayBorder<kWs, kWt>;
  q.a[k] = texel_word<kB>(img, xs[0], ys[0], border);
  q.b[k] = texel_word<kB>(img, xs[1], ys[0], border);
  q.c[k] = texel_word<kB>(img, xs[0], ys[1], border);
  q.d[k] = texel_word<kB>(img, xs[1], ys[1], border);
  q.fu[k] = u.f;
  q.fv[k] = v.f;
}
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline Rgba8 bilinear8(LevelView img, Rgba8 border, float s, float t) {
  dp::Quad8 q;
  bilinear8_taps<kWs, kWt>(img, border, s, t, q, 0);
  return dp::bilinear_lerp8(q.a[0], q.b[0], q.c[0], q.d[0], q.fu[0], q.fv[0]);
}

// CUBIC (4 x 4 taps) on one level of 8-bit texel words with memoized weights: filter_tiled_acc_n
// with the wrap modes fixed, then the normalise stage.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline Rgba8 cubic8(LevelView img, Rgba8 border, const WeightMemo& memo,
                                            const dp::CubicNormalize& norm, float s, float t) {
  const LevelCoord u = texel_coord(s, img.width), v = texel_coord(t, img.height);
  const int32_t* w = memo.weights(u.f, v.f);
  int col[4], row[4];
  dp::wrap_taps<kWs, 4>(u.i0 - 1, img.width, col);  // taps -1 .. 2
  dp::wrap_taps<kWt, 4>(v.i0 - 1, img.height, row);
  // (R, B) and (G, A) in signed 32-bit lanes, as in filter_tiled_acc_n: modular arithmetic keeps
  // x = low + high 2^32 exactly and each lane's true sum is below 2^31 in magnitude.
  // One row of taps per iteration (kept as a loop: fully unrolled, the compiler spills the 16
  // addresses and weights).
  uint64_t arb = 0, aga = 0;
#pragma GCC unroll 1
  for (int j = 0; j < 4; ++j) {
    const int32_t* wr = w + 4 * j;
    for (int i = 0; i < 4; ++i) {
      const Rgba8 c = texel_word<kMayBorder<kWs, kWt>>(img, col[i], row[j], border);
      const auto wt = static_cast<uint64_t>(static_cast<int64_t>(wr[i]));
      arb += dp::word_lanes_rb(c) * wt;  // (R, B) and (G, A) in 32-bit lanes
      aga += dp::word_lanes_ga(c) * wt;
    }
  }
  const auto lo = [](uint64_t x) { return static_cast<int64_t>(static_cast<int32_t>(static_cast<uint32_t>(x))); };
  const auto hi = [&lo](uint64_t x) {
    return static_cast<int64_t>(static_cast<int32_t>(static_cast<uint32_t>((x - static_cast<uint64_t>(lo(x))) >> 32)));
  };
  const std::array<int64_t, 4> acc{lo(arb), lo(aga), hi(arb), hi(aga)};
  if (norm.M == 255 && !norm.prefiltered) {
    // dp::cubic_normalize of the default 8-bit ROM: clamp(floor((2 acc + 255) / 510)) to 0..255; a
    // negative numerator clamps to 0, so only non-negative ones are divided (truncation = floor).
    const auto n8 = [](int64_t a) {
      const int64_t n = 2 * a + 255;
      return static_cast<uint8_t>(n < 0 ? 0 : std::min<int64_t>(n / 510, 255));
    };
    return {n8(acc[0]), n8(acc[1]), n8(acc[2]), n8(acc[3])};
  }
  const Texel4 c = dp::cubic_normalize(acc, norm);  // within 0..255
  return {static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]), static_cast<uint8_t>(c[3])};
}

// EDGE_PRESERVING on one level of an 8-bit format: the cross footprint (edge_footprint with the
// wrap modes fixed and no override; texels outside the shape are read but not used), then the
// Lee & Jen datapath.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline Texel4 edge8(LevelView img, Rgba8 border, TexelFormat fmt, bool cache_block,
                                           int block, float s, float t) {
  const LevelCoord u = texel_coord(s, img.width), v = texel_coord(t, img.height);
  int col[4], row[4];
  dp::wrap_taps<kWs, 4>(u.i0 - 1, img.width, col);  // columns and rows -1 .. 2
  dp::wrap_taps<kWt, 4>(v.i0 - 1, img.height, row);
  const lee_jen::TexelMask mask =
      cache_block ? lee_jen::cache_block_mask(col[1], col[2], row[1], row[2], block) : lee_jen::kAllTexels;
  std::array<Texel4, lee_jen::kTexels> c;
  for (size_t k = 0; k < c.size(); ++k) {
    const lee_jen::TexelPos p = lee_jen::kTexelPos[k];
    const Rgba8 w = texel_word<kMayBorder<kWs, kWt>>(img, col[p.x + 1], row[p.y + 1], border);
    c[k] = ((mask >> k) & 1u) ? Texel4{w.r, w.g, w.b, w.a} : Texel4{0, 0, 0, 0};
  }
  return lee_jen::edge_preserving_interpolate(c, mask, u.f, v.f, fmt);
}

// Trilinear blend unit (dp::level_blend) and output encoding, for the 8-bit paths' texel words
// (channels within 0..255, so encoding is the identity) and for datapath channels.
inline Rgba8 blend_levels(Rgba8 a, Rgba8 b, int f) { return dp::level_blend8(a, b, f); }
inline Texel4 blend_levels(const Texel4& a, const Texel4& b, int f) { return dp::level_blend(a, b, f); }
inline Rgba8 output_word(Rgba8 c, TexelFormat) { return c; }
inline Rgba8 output_word(const Texel4& c, TexelFormat fmt) { return encode_texel(c, fmt); }

// Level select of the LOD unit and the blend unit around a filter of one level, f(level).
template <class F>
[[gnu::always_inline]] inline auto filter_levels(int32_t lambda, const LodParams& lod, MipMode mip, int q, F&& f) {
  const LevelPick p = select_levels(lambda_bias_clamp(lambda, lod), mip, q);
  const auto c0 = f(p.level0);
  if (p.blend == 0) return c0;
  return blend_levels(c0, f(p.level1), p.blend);
}

}  // namespace

// The mode's filter on one level.
template <Sampler::FastPaths::Variant kV>
[[gnu::always_inline]] inline auto Sampler::FastPaths::filter(const Sampler& sm, int l, float s, float t) {
  const auto level = static_cast<size_t>(l);
  const Impl& im = *sm.impl_;
  if constexpr (kV.path == Path::Linear8) {
    return bilinear8<kV.ws, kV.wt>(LevelView(sm.tex_.levels[level]), sm.cfg_.border, s, t);
  } else if constexpr (kV.path == Path::Cubic8) {
    if (im.prefiltered) return cubic8<kV.ws, kV.wt>(LevelView(im.coeff_levels[level]), Rgba8{}, *im.memo, im.norm, s, t);
    return cubic8<kV.ws, kV.wt>(LevelView(sm.tex_.levels[level]), sm.cfg_.border, *im.memo, im.norm, s, t);
  } else {
    return edge8<kV.ws, kV.wt>(LevelView(sm.tex_.levels[level]), sm.cfg_.border, sm.tex_.format,
                               sm.cfg_.edge_shape == EdgeShapePolicy::CacheBlock, sm.cfg_.edge_cache_block, s, t);
  }
}

// One filtered colour: level select, the filter on one or two levels, blend, encode.
template <Sampler::FastPaths::Variant kV>
Rgba8 Sampler::FastPaths::sample(const Sampler& sm, float s, float t, int32_t lambda) {
  const TexelFormat fmt = sm.tex_.format;
  if constexpr (!kV.mipmapped) {
    return output_word(filter<kV>(sm, 0, s, t), fmt);  // GL: no MIP-mapping -> level 0
  } else {
    return output_word(filter_levels(lambda, sm.cfg_.lod, sm.cfg_.mode.mip, sm.tex_.max_level(),
                                     [&](int l) { return filter<kV>(sm, l, s, t); }),
                       fmt);
  }
}

// sample<kV> over a batch, LINEAR on 8-bit formats: the sampler's registers are read once, and four
// requests at a time share the 4-lane lerp unit (their address, wrap and texel fetch are
// independent, so the core overlaps them). MIP-mapped, each lane selects its own levels; the
// second level's lerp runs when some lane blends, and the blend unit only for those lanes (as
// filter_levels). A remainder of 1..3 requests goes through the scalar units.
template <Sampler::FastPaths::Variant kV>
void Sampler::FastPaths::batch(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out) {
  static_assert(kV.path == Path::Linear8);
  const Rgba8 border = sm.cfg_.border;
  size_t i = 0;
  if constexpr (!kV.mipmapped) {
    const LevelView img(sm.tex_.levels[0]);
    dp::Quad8 q;  // every lane is written before each use
    for (; i + 4 <= n; i += 4) {
      for (size_t k = 0; k < 4; ++k) bilinear8_taps<kV.ws, kV.wt>(img, border, req[i + k].s, req[i + k].t, q, k);
      dp::bilinear_lerp8x4(q, out + i);
    }
    for (; i < n; ++i) out[i] = bilinear8<kV.ws, kV.wt>(img, border, req[i].s, req[i].t);
  } else {
    const Image* levels = sm.tex_.levels.data();
    const LodParams lod = sm.cfg_.lod;
    const MipMode mip = sm.cfg_.mode.mip;
    const int top = sm.tex_.max_level();
    dp::Quad8 q0, q1;  // level0 and level1 taps; q1's lanes are used only where the lane blends
    std::array<Rgba8, 4> c1;
    for (; i + 4 <= n; i += 4) {
      std::array<int, 4> blend;
      int any = 0;
      for (size_t k = 0; k < 4; ++k) {
        const SampleRequest& r = req[i + k];
        const LevelPick p = select_levels(lambda_bias_clamp(r.lambda_q8, lod), mip, top);
        bilinear8_taps<kV.ws, kV.wt>(LevelView(levels[p.level0]), border, r.s, r.t, q0, k);
        if (p.blend != 0) bilinear8_taps<kV.ws, kV.wt>(LevelView(levels[p.level1]), border, r.s, r.t, q1, k);
        blend[k] = p.blend;
        any |= p.blend;
      }
      dp::bilinear_lerp8x4(q0, out + i);
      if (any == 0) continue;
      dp::bilinear_lerp8x4(q1, c1.data());
      for (size_t k = 0; k < 4; ++k)
        if (blend[k] != 0) out[i + k] = dp::level_blend8(out[i + k], c1[k], blend[k]);
    }
    for (; i < n; ++i) {
      const float s = req[i].s, t = req[i].t;
      out[i] = filter_levels(req[i].lambda_q8, lod, mip, top,
                             [&](int l) { return bilinear8<kV.ws, kV.wt>(LevelView(levels[l]), border, s, t); });
    }
  }
}

void Sampler::batch_generic(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out) {
  const SampleFn f = sm.sample_fn_;
  for (size_t i = 0; i < n; ++i) out[i] = f(sm, req[i].s, req[i].t, req[i].lambda_q8);
}

// sample<kV> for the 16 pairs of wrap modes, indexed by 4 wrap_s + wrap_t.
template <Sampler::FastPaths::Path kP, bool kMip, size_t... k>
constexpr std::array<Sampler::SampleFn, 16> Sampler::FastPaths::wrap_table(std::index_sequence<k...>) {
  return {&sample<Variant{kP, kMip, static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)}>...};
}

// batch<kV> of LINEAR for the 16 pairs of wrap modes, indexed by 4 wrap_s + wrap_t.
template <bool kMip, size_t... k>
constexpr std::array<Sampler::BatchFn, 16> Sampler::FastPaths::batch_table(std::index_sequence<k...>) {
  return {&batch<Variant{Path::Linear8, kMip, static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)}>...};
}

template <Sampler::FastPaths::Path kP>
Sampler::SampleFn Sampler::FastPaths::pick(bool mipmapped, WrapMode ws, WrapMode wt) {
  const auto k = static_cast<size_t>(4 * static_cast<int>(ws) + static_cast<int>(wt));
  return mipmapped ? wrap_table<kP, true>(std::make_index_sequence<16>())[k]
                   : wrap_table<kP, false>(std::make_index_sequence<16>())[k];
}

void Sampler::FastPaths::setup(Sampler& sm) {
  const Impl& im = *sm.impl_;
  const WrapMode ws = sm.cfg_.wrap_s, wt = sm.cfg_.wrap_t;
  const bool mip = sm.cfg_.mode.mip != MipMode::None;
  const bool bytes = sm.tex_.format != TexelFormat::VS16X2;
  sm.sample_fn_ = &sample_generic;
  sm.batch_fn_ = &batch_generic;
  switch (sm.cfg_.mode.base) {
    case BaseFilter::Nearest: break;
    case BaseFilter::Linear:
      if (bytes) {
        sm.sample_fn_ = pick<Path::Linear8>(mip, ws, wt);
        const auto k = static_cast<size_t>(4 * static_cast<int>(ws) + static_cast<int>(wt));
        sm.batch_fn_ = mip ? batch_table<true>(std::make_index_sequence<16>())[k]
                           : batch_table<false>(std::make_index_sequence<16>())[k];
      }
      break;
    case BaseFilter::Cubic:
      if (bytes && im.memo && im.rom->taps() == 4) sm.sample_fn_ = pick<Path::Cubic8>(mip, ws, wt);
      break;
    case BaseFilter::EdgePreserving:
      if (bytes) sm.sample_fn_ = pick<Path::Edge8>(mip, ws, wt);
      break;
  }
}


// ---------------------------------------------------------------- double-precision ideal
std::array<double, 4> Sampler::sample_ideal(double s, double t, double lambda) const {
  // Non-finite coordinates as the datapath treats them (docs/sampler.md): NaN -> 0, +-Inf
  // saturates (here at +-2^40, far outside any texture, so every index below stays finite).
  const auto saturate = [](double c) { return std::isnan(c) ? 0.0 : std::clamp(c, -0x1p40, 0x1p40); };
  s = saturate(s);
  t = saturate(t);
  // Same level selection as GL, in real arithmetic.
  lambda = std::clamp(lambda + cfg_.lod.bias_q8 / 256.0, cfg_.lod.min_lod_q8 / 256.0, cfg_.lod.max_lod_q8 / 256.0);
  const int q = tex_.max_level();
  int l0 = 0, l1 = 0;
  double blend = 0;
  if (lambda > 0) {
    if (cfg_.mode.mip == MipMode::Nearest) {
      l0 = l1 = std::min(lambda <= 0.5 ? 0 : static_cast<int>(std::ceil(lambda + 0.5)) - 1, q);
    } else if (cfg_.mode.mip == MipMode::Linear) {
      if (lambda >= q) {
        l0 = l1 = q;
      } else {
        l0 = static_cast<int>(std::floor(lambda));
        l1 = l0 + 1;
        blend = lambda - l0;
      }
    }
  }
  const double sc = impl_->scale;
  const auto real_texel = [&](int level, int64_t x, int64_t y) {
    const Texel4 c = fetch(level, static_cast<int>(std::clamp<int64_t>(x, INT32_MIN / 2, INT32_MAX / 2)),
                           static_cast<int>(std::clamp<int64_t>(y, INT32_MIN / 2, INT32_MAX / 2)));
    return std::array<double, 4>{c[0] / sc, c[1] / sc, c[2] / sc, c[3] / sc};
  };
  const auto level_sample = [&](int level) -> std::array<double, 4> {
    const Image& img = tex_.levels[static_cast<size_t>(level)];
    const double u = s * img.width - 0.5, v = t * img.height - 0.5;
    const double fi = std::floor(u), fj = std::floor(v);
    const double fu = u - fi, fv = v - fj;
    const auto i0 = static_cast<int64_t>(std::clamp(fi, -1e15, 1e15));
    const auto j0 = static_cast<int64_t>(std::clamp(fj, -1e15, 1e15));
    std::array<double, 4> out{};
    switch (cfg_.mode.base) {
      case BaseFilter::Nearest:
        return real_texel(level, static_cast<int64_t>(std::floor(s * img.width)),
                          static_cast<int64_t>(std::floor(t * img.height)));
      case BaseFilter::Linear: {
        const std::array<double, 4> w{(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
        const std::array<std::array<double, 4>, 4> c{real_texel(level, i0, j0), real_texel(level, i0 + 1, j0),
                                                     real_texel(level, i0, j0 + 1), real_texel(level, i0 + 1, j0 + 1)};
        for (size_t ch = 0; ch < 4; ++ch)
          for (size_t k = 0; k < 4; ++k) out[ch] += w[k] * c[k][ch];
        return out;
      }
      case BaseFilter::Cubic: {
        const FilterKernel& h = *impl_->kernel;
        const int taps = impl_->rom->taps(), m0 = impl_->rom->first_tap();
        // Without level adaptation the kernel keeps its level-0 footprint: distances in level-L
        // texels are scaled by 2^L before evaluating h (Hadwiger 2004 Sec. 3.2).
        const double k = cfg_.cubic_level_adapt ? 1.0 : std::ldexp(1.0, level);
        double wsum = 0;
        for (int j = 0; j < taps; ++j)
          for (int i = 0; i < taps; ++i) {
            const double w = h(k * (fu - (m0 + i))) * h(k * (fv - (m0 + j)));
            if (w == 0) continue;
            wsum += w;
            std::array<double, 4> c;
            if (impl_->prefiltered) {
              const auto& cl = impl_->coeff_ideal[static_cast<size_t>(level)];
              const int xi = wrap_index(cfg_.wrap_s, i0 + m0 + i, img.width);
              const int yj = wrap_index(cfg_.wrap_t, j0 + m0 + j, img.height);
              c = (xi < 0 || yj < 0) ? std::array<double, 4>{}
                                     : cl[static_cast<size_t>(yj) * static_cast<size_t>(img.width) +
                                          static_cast<size_t>(xi)];
            } else {
              c = real_texel(level, i0 + m0 + i, j0 + m0 + j);
            }
            for (size_t ch = 0; ch < 4; ++ch) out[ch] += w * c[ch];
          }
        if (!cfg_.cubic_level_adapt && wsum > 0)
          for (auto& x : out) x /= wsum;  // the unadapted kernel is renormalised (best case for it)
        const double lo = tex_.format == TexelFormat::VS16X2 ? -1.0 : 0.0;
        for (auto& x : out) x = std::clamp(x, lo, 1.0);
        return out;
      }
      case BaseFilter::EdgePreserving: {
        std::array<std::array<double, 4>, lee_jen::kTexels> c{};
        lee_jen::TexelMask mask = lee_jen::kAllTexels;
        if (cfg_.edge_shape == EdgeShapePolicy::CacheBlock)
          mask = lee_jen::cache_block_mask(wrap_index(cfg_.wrap_s, i0, img.width),
                                           wrap_index(cfg_.wrap_s, i0 + 1, img.width),
                                           wrap_index(cfg_.wrap_t, j0, img.height),
                                           wrap_index(cfg_.wrap_t, j0 + 1, img.height), cfg_.edge_cache_block);
        for (int n = 1; n <= lee_jen::kTexels; ++n) {
          const lee_jen::TexelPos p = lee_jen::texel_pos(n);
          c[static_cast<size_t>(n - 1)] = real_texel(level, i0 + p.x, j0 + p.y);
        }
        return lee_jen::edge_preserving_ideal(c, mask, fu, fv, tex_.format);
      }
    }
    return out;
  };
  std::array<double, 4> a = level_sample(l0);
  if (blend > 0) {
    const std::array<double, 4> b = level_sample(l1);
    for (size_t ch = 0; ch < 4; ++ch) a[ch] = (1 - blend) * a[ch] + blend * b[ch];
  }
  return a;
}

}  // namespace tfu
