// Fuzz target (e), differential (docs/fuzzing.md): random requests through the golden model
// (Sampler) and the cycle model (rtl::run_unit), which must agree bit for bit, as `tfu sim`
// compares them (rtl::golden_pixel). The input chooses everything: a small texture (1..24 texels
// per side, RGBA8 / L8 / VS16X2 texels, a MIP chain or none), the sampler (every filter mode, wrap
// mode per axis, border word, LOD bias and clamps, cubic kernel, ROM size and bits, reconstruction,
// level adaptation), the unit (block, sets, ways, banks and mapping, memory latency and bandwidth,
// channel and miss-FIFO depths, filter lanes, shape policy) and the trace (lod, grad or quad mode,
// coordinates mostly in [-2, 2], sometimes any 32-bit pattern: NaN, infinities, denormals, huge).
// A configuration the model refuses (InputError) is skipped; a mismatch aborts with the details.
#include <cstdio>
#include <cstdlib>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

using tfu::fuzz::ByteReader;

tfu::Texture make_texture(ByteReader& in) {
  tfu::Texture tex;
  tex.format = in.pick({tfu::TexelFormat::RGBA8, tfu::TexelFormat::L8, tfu::TexelFormat::VS16X2});
  const int w = static_cast<int>(in.in_range(1, 24)), h = static_cast<int>(in.in_range(1, 24));
  tfu::Image img(w, h);
  for (tfu::Rgba8& t : img.texels) {
    t = {in.byte(), in.byte(), in.byte(), in.byte()};
    if (tex.format == tfu::TexelFormat::L8) t = {t.r, t.r, t.r, 255};
  }
  tex.levels.push_back(std::move(img));
  const uint8_t mips = in.byte() % 3;
  if (mips == 1) tfu::generate_mipmaps(tex, tfu::MipMethod::Box);
  if (mips == 2) tfu::generate_mipmaps(tex, tfu::MipMethod::Edge, 0.5);
  return tex;
}

tfu::SamplerConfig make_sampler(ByteReader& in) {
  tfu::SamplerConfig c;
  const auto& modes = tfu::all_filter_modes();
  c.mode = modes[in.byte() % modes.size()];
  constexpr tfu::WrapMode kWrap[] = {tfu::WrapMode::Repeat, tfu::WrapMode::MirroredRepeat, tfu::WrapMode::ClampToEdge,
                                     tfu::WrapMode::ClampToBorder};
  c.wrap_s = in.pick(kWrap);
  c.wrap_t = in.pick(kWrap);
  c.border = {in.byte(), in.byte(), in.byte(), in.byte()};
  c.lod.bias_q8 = static_cast<int32_t>(in.in_range(-16 * 256, 16 * 256));
  c.lod.min_lod_q8 = in.flag() ? -1000 * 256 : static_cast<int32_t>(in.in_range(-4 * 256, 8 * 256));
  c.lod.max_lod_q8 = in.flag() ? 1000 * 256 : static_cast<int32_t>(in.in_range(-4 * 256, 8 * 256));
  const std::vector<std::string> kernels = tfu::cubic_kernel_names();
  c.kernel = kernels[in.byte() % kernels.size()];
  c.cubic_rom.samples = in.pick({16, 32, 64});
  c.cubic_rom.bits = static_cast<unsigned>(in.in_range(4, 16));
  c.cubic_recon = in.flag() ? tfu::RomRecon::Linear : tfu::RomRecon::Nearest;
  c.cubic_level_adapt = !in.flag();
  return c;
}

tfu::rtl::UnitConfig make_unit(ByteReader& in) {
  tfu::rtl::UnitConfig u;
  u.cache.block = in.flag() ? 8 : 4;
  u.cache.ways = static_cast<int>(in.in_range(1, 8));
  const int sets = static_cast<int>(in.in_range(1, 16));
  u.cache.capacity_bytes = sets * u.cache.ways * u.cache.block * u.cache.block * 4;
  u.cache.banks = in.flag() ? 4 : 1;
  u.cache.bank_mapping = in.flag() ? tfu::rtl::BankMapping::TexelParity : tfu::rtl::BankMapping::BlockParity;
  u.memory.latency = in.pick({0, 1, 7, 100, 1000, 1000000});
  u.memory.bytes_per_cycle = in.pick({1, 3, 16, 64, 65536});
  u.channel_depth = static_cast<int>(in.in_range(1, 4));
  u.miss_fifo_depth = static_cast<int>(in.in_range(1, 16));
  u.filter_lanes = in.pick({1, 2, 4});
  u.shape_policy = in.pick({tfu::rtl::ShapePolicy::Static, tfu::rtl::ShapePolicy::CacheAware, tfu::rtl::ShapePolicy::FullCross});
  u.idle_skip = u.memory.latency > 1000 || !in.flag();  // without skipping, a 10^6-cycle miss is slow
  return u;
}

tfu::Trace make_trace(ByteReader& in) {
  tfu::Trace tr;
  tr.mode = in.pick({tfu::TraceMode::Quad, tfu::TraceMode::Lod, tfu::TraceMode::Grad});
  const int n = tr.mode == tfu::TraceMode::Quad ? 4 * static_cast<int>(in.in_range(1, 8)) : static_cast<int>(in.in_range(1, 32));
  for (int i = 0; i < n; ++i) {
    tfu::TraceRequest r;
    r.s = in.coordinate();
    r.t = in.coordinate();
    if (tr.mode == tfu::TraceMode::Lod) r.lod = in.flag() ? in.raw_float() : static_cast<float>(in.in_range(-64, 192)) / 16.0f;
    if (tr.mode == tfu::TraceMode::Grad) {
      r.dsdx = in.coordinate() / 8;
      r.dtdx = in.coordinate() / 8;
      r.dsdy = in.coordinate() / 8;
      r.dtdy = in.coordinate() / 8;
    }
    tr.requests.push_back(r);
  }
  return tr;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 8192) return 0;
  ByteReader in(data, size);
  const tfu::Texture tex = make_texture(in);
  const tfu::SamplerConfig cfg = make_sampler(in);
  const tfu::rtl::UnitConfig unit = make_unit(in);
  const tfu::Trace trace = make_trace(in);
  tfu::rtl::UnitOutput got;
  try {
    got = tfu::rtl::run_unit(tex, cfg, trace, unit);
  } catch (const tfu::InputError&) {
    return 0;  // a configuration the unit refuses (e.g. a kernel wider than the footprint)
  }
  const tfu::Sampler golden(tex, tfu::rtl::golden_sampler_config(cfg, unit));
  const std::vector<int32_t> lambda = tfu::trace_lambdas(trace, tex.width(), tex.height());
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    const tfu::TraceRequest& r = trace.requests[i];
    const tfu::Rgba8 want = tfu::rtl::golden_pixel(golden, unit, got, r, lambda[i], i);
    const tfu::Rgba8 have = got.pixels[i];
    if (want != have) {
      std::fprintf(stderr,
                   "mismatch: %s, %dx%d %s texture, request %zu (s=%.9g t=%.9g lambda=%d): cycle model %d,%d,%d,%d vs "
                   "golden %d,%d,%d,%d\n",
                   tfu::filter_mode_name(cfg.mode).c_str(), tex.width(), tex.height(), tfu::texel_format_name(tex.format), i,
                   static_cast<double>(r.s), static_cast<double>(r.t), lambda[i], have.r, have.g, have.b, have.a, want.r,
                   want.g, want.b, want.a);
      std::abort();
    }
  }
  return 0;
}
