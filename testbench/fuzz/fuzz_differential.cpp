// Fuzz target (e), differential (docs/fuzzing.md): random frames and requests through the golden
// model (GoldenUnit) and the cycle model (rtl::run_unit), which must agree bit for bit, as `tfu sim`
// compares them (rtl::golden_outputs, rtl::first_mismatch); and through the cycle model's timing
// recurrences (rtl::run_unit_recurrence), which must give the clocked run's pixels, cycles and
// statistics. The input chooses everything:
//   textures   1 or 2, each 1..24 texels per side, RGBA8 / L8 / VS16X2 texels, tiled or linear rows,
//              no MIP chain, a box or an edge-preserving chain; SRGBA8 texels (a format byte of 224..239;
//              sRGB codes decoded to linear before filtering, docs/srgb.md) with no chain or a box
//              chain; or block-compressed (a format byte of 240 and up: corpus inputs below keep their
//              meaning): every unsigned block format (cmodel/block_formats.hpp), the input's bytes as
//              its blocks (illegal ASTC encodings included), one level or the whole chain, sRGB and the
//              BC interpolation rules, and (bit 3 of the rules byte) the texels declared SRGBA8
//   samplers   1..3 descriptors: every filter mode, wrap mode per axis, border word, LOD bias and
//              min / max clamps (each within +-16 levels or unbounded), cubic kernel (bspline-interp
//              included: the driver's coefficient texture), ROM samples and bits, reconstruction,
//              level adaptation, edge shape policy (static, cross, cache-aware), max anisotropy
//              1..16 and its rounding
//   unit       cache line 64 / 256 / 1024 bytes, 1..16 sets of 1..8 ways, 1 or 4 banks, both bank
//              mappings, memory latency 0..10^5 and bandwidth 1..65536 bytes per cycle, channel
//              depth 1..4, miss FIFO 1..16, line buffer 15 + sets, 1 / 2 / 4 filter lanes (the same byte's high bits:
//              what the cache holds of compressed textures, 1..4 decoders of 1..8 texels per clock, latency 0 or 3),
//              idle skipping on or off
//   requests   lod, grad or quad mode; each request (each quad) names a texture and a sampler;
//              coordinates mostly in [-2, 2], sometimes any 32-bit pattern (NaN, infinities,
//              denormals, huge values)
//   paths      the fast-path switch (cmodel/fast_paths.hpp), drawn after the requests (past the
//              input's end: on): off runs the plain datapaths of both models and the golden
//              compare against the plain golden datapath; restored after the run
//   names      each texture's name (its spec, as a file or archive spells it), drawn last
//              (ByteReader::name: control characters, bytes that are not UTF-8, very long, path
//              separators and `..`, the line formats' own characters)
//   depths     the filter datapaths' pipeline depths (filter.edge_stages 3 or 8, filter.bilinear_stages
//              2, 3 or 4), drawn after the names (past the input's end: the defaults)
// A configuration the models refuse (InputError) is skipped; a mismatch aborts with the details.
// Names must reach every output intact or be refused: the statistics' JSON parses back with each
// texture's name (a name that is not UTF-8: with U+FFFD, cmodel/json_output.hpp), and the frame's
// trace bindings (describe_frame, write_trace) are refused with an InputError exactly when a name
// cannot be written (a control character, an empty spec), else read back to the same names.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/block_formats.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/trace.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

using tfu::fuzz::ByteReader;

std::shared_ptr<tfu::Texture> make_compressed_texture(ByteReader& in) {
  std::vector<tfu::BlockFormat> formats;
  for (const tfu::BlockFormatInfo& i : tfu::kBlockFormats)
    if (tfu::unit_filterable(i.format)) formats.push_back(i.format);
  tfu::BlockImage image;
  image.format = formats[in.byte() % formats.size()];
  image.srgb = in.flag();
  const int w = static_cast<int>(in.in_range(1, 24)), h = static_cast<int>(in.in_range(1, 24));
  const int levels = in.flag() ? tfu::mip_level_count(w, h) : 1;
  for (int l = 0; l < levels; ++l) {
    tfu::BlockLevel bl{tfu::mip_extent(w, l), tfu::mip_extent(h, l), {}};
    bl.blocks.resize(tfu::block_level_bytes(image.format, bl.width, bl.height));
    for (uint8_t& b : bl.blocks) b = in.byte();
    image.levels.push_back(std::move(bl));
  }
  const uint8_t rules = in.byte();
  const tfu::BlockDecodeRules r{
      {static_cast<tfu::Bc1Interpolation>(rules % 4), static_cast<tfu::Bc4Interpolation>((rules >> 2) & 1)},
      image.srgb};
  auto tex = std::make_shared<tfu::Texture>(tfu::texture_from_block_image(image, r, "fuzz"));
  if ((rules >> 3) & 1) tex->format = tfu::TexelFormat::SRGBA8;
  return tex;
}

std::shared_ptr<tfu::Texture> make_texture(ByteReader& in) {
  auto tex = std::make_shared<tfu::Texture>();
  const uint8_t format = in.byte();
  if (format >= 240) return make_compressed_texture(in);
  constexpr tfu::TexelFormat kFormats[] = {tfu::TexelFormat::RGBA8, tfu::TexelFormat::L8, tfu::TexelFormat::VS16X2};
  tex->format = format >= 224 ? tfu::TexelFormat::SRGBA8 : kFormats[format % 3];
  tex->layout = in.flag() ? tfu::MemoryLayout::Linear : tfu::MemoryLayout::Tiled;
  const int w = static_cast<int>(in.in_range(1, 24)), h = static_cast<int>(in.in_range(1, 24));
  tfu::Image img(w, h);
  for (tfu::Rgba8& t : img.texels) {
    t = {in.byte(), in.byte(), in.byte(), in.byte()};
    if (tex->format == tfu::TexelFormat::L8) t = {t.r, t.r, t.r, 255};
  }
  tex->levels.push_back(std::move(img));
  const uint8_t mips = in.byte() % 3;
  if (mips == 1) tfu::generate_mipmaps(*tex, tfu::MipMethod::Box);
  if (mips == 2 && tex->format != tfu::TexelFormat::SRGBA8) tfu::generate_mipmaps(*tex, tfu::MipMethod::Edge, 0.5);
  return tex;
}

int32_t lod_q8(ByteReader& in, int32_t unbounded) {
  return in.flag() ? unbounded : static_cast<int32_t>(in.in_range(-16 * 256, 16 * 256));
}

tfu::SamplerDescriptor make_sampler(ByteReader& in) {
  tfu::SamplerDescriptor c;
  const auto& modes = tfu::all_filter_modes();
  c.mode = modes[in.byte() % modes.size()];
  constexpr tfu::WrapMode kWrap[] = {tfu::WrapMode::Repeat, tfu::WrapMode::MirroredRepeat, tfu::WrapMode::ClampToEdge,
                                     tfu::WrapMode::ClampToBorder};
  c.wrap_s = in.pick(kWrap);
  c.wrap_t = in.pick(kWrap);
  c.border = {in.byte(), in.byte(), in.byte(), in.byte()};
  c.lod.bias_q8 = static_cast<int32_t>(in.in_range(-16 * 256, 16 * 256));
  c.lod.min_lod_q8 = lod_q8(in, -1000 * 256);
  c.lod.max_lod_q8 = lod_q8(in, 1000 * 256);
  const auto& kernels = tfu::cubic_kernel_names();
  c.kernel = kernels[in.byte() % kernels.size()];
  c.cubic_rom.samples = in.pick({16, 32, 64, 512});
  c.cubic_rom.bits = static_cast<unsigned>(in.in_range(4, 16));
  c.cubic_recon = in.flag() ? tfu::RomRecon::Linear : tfu::RomRecon::Nearest;
  c.cubic_level_adapt = !in.flag();
  c.edge_shape = in.pick({tfu::EdgeShape::Static, tfu::EdgeShape::Cross, tfu::EdgeShape::CacheAware});
  c.max_aniso = static_cast<int>(in.in_range(1, 16));
  c.aniso_rounding = in.flag() ? tfu::AnisoRounding::PowerOfTwo : tfu::AnisoRounding::Integer;
  c.aniso_threshold = static_cast<int>(in.in_range(0, 7));
  c.aniso_axes = in.flag() ? tfu::AnisoAxes::Ellipse : tfu::AnisoAxes::Screen;
  return c;
}

tfu::rtl::UnitConfig make_unit(ByteReader& in, tfu::rtl::ClockedOptions& clocked) {
  tfu::rtl::UnitConfig u;
  u.cache.line_bytes = in.pick({64, 256, 1024});
  u.cache.ways = static_cast<int>(in.in_range(1, 8));
  const int sets = static_cast<int>(in.in_range(1, 16));
  u.cache.capacity_bytes = sets * u.cache.ways * u.cache.line_bytes;
  u.cache.banks = in.flag() ? 4 : 1;
  u.cache.bank_mapping = in.flag() ? tfu::rtl::BankMapping::TexelParity : tfu::rtl::BankMapping::BlockParity;
  u.memory.latency = in.pick({0, 1, 7, 100, 1000, 100000});
  u.memory.bytes_per_cycle = in.pick({1, 3, 16, 64, 65536});
  u.channel_depth = static_cast<int>(in.in_range(1, 4));
  u.miss_fifo_depth = static_cast<int>(in.in_range(1, 16));
  u.line_buffer_depth = tfu::rtl::kMaxFootprintLines - 1 + sets;  // 16..31 slots (no byte of its own): it binds often
  const uint8_t lanes = in.byte();
  constexpr int kLanes[] = {1, 2, 4};
  u.filter_lanes = kLanes[lanes % 3];
  u.cache.holds = (lanes >> 2) & 1 ? tfu::rtl::CacheHolds::Decoded : tfu::rtl::CacheHolds::Compressed;
  u.decoder.units = 1 + ((lanes >> 3) & 3);
  u.decoder.texels_per_clock = 1 << ((lanes >> 5) & 3);
  u.decoder.latency = 3 * (lanes >> 7);
  clocked.idle_skip = u.memory.latency > 1000 || !in.flag();  // without skipping, a 10^5-cycle miss is slow
  return u;
}

// Requests over the frame's (texture, sampler) pairs; textures bound through FrameBuilder::bind
// (a bspline-interp sampler reads the coefficient texture the driver made).
tfu::Trace make_trace(ByteReader& in, tfu::FrameBuilder& fb, int textures, int samplers) {
  tfu::Trace tr;
  tr.source = "fuzz";
  tr.mode = in.pick({tfu::TraceMode::Quad, tfu::TraceMode::Lod, tfu::TraceMode::Grad});
  const int n = tr.mode == tfu::TraceMode::Quad ? 4 * static_cast<int>(in.in_range(1, 8)) : static_cast<int>(in.in_range(1, 32));
  int texture = 0, sampler = 0;
  for (int i = 0; i < n; ++i) {
    if (tr.mode != tfu::TraceMode::Quad || i % 4 == 0) {  // a quad's four pixels share texture and sampler
      texture = static_cast<int>(in.in_range(0, textures - 1));
      sampler = static_cast<int>(in.in_range(0, samplers - 1));
    }
    tfu::TraceRequest r;
    r.texture = static_cast<uint16_t>(fb.bind(texture, sampler));
    r.sampler = static_cast<uint8_t>(sampler);
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

bool is_utf8(const std::string& s) {
  try {
    (void)nlohmann::json(s).dump();  // the strict writer throws on a byte that is not UTF-8
    return true;
  } catch (const nlohmann::json::type_error&) {
    return false;
  }
}

// The names' way into the statistics and the trace (see the header).
void check_names(const tfu::Frame& frame, const tfu::Trace& trace, const std::string& stats_json) {
  const nlohmann::json stats = nlohmann::json::parse(stats_json);  // must not throw
  for (const nlohmann::json& row : stats["tables"]["textures"]) {
    const std::string label = row["name"].get<std::string>();
    const size_t k = static_cast<size_t>(row["index"].get<uint64_t>());
    if (k >= frame.textures.size()) std::abort();
    const std::string& name = frame.textures[k].name;
    if (is_utf8(name) && label != fmt::format("{} {}", k, name)) {
      std::fprintf(stderr, "texture %zu's name did not reach the statistics intact\n", k);
      std::abort();
    }
  }
  tfu::Trace described = trace;
  tfu::describe_frame(frame, described);
  bool writable = true;
  for (const tfu::TraceBinding& b : described.textures) writable = writable && !b.spec.empty() && !tfu::has_control_characters(b.spec);
  std::ostringstream out;
  try {
    tfu::write_trace(out, described);
  } catch (const tfu::InputError&) {
    if (writable) std::abort();  // a name the trace could carry was refused
    if (!out.str().empty()) std::abort();  // nothing is written before the refusal
    return;
  }
  if (!writable) std::abort();  // a name that breaks the line format was written
  std::istringstream in(out.str());
  const tfu::Trace back = tfu::parse_trace(in, "written.trace");  // must not throw
  if (back.textures.size() != described.textures.size()) std::abort();
  for (size_t i = 0; i < back.textures.size(); ++i)
    if (back.textures[i].spec != described.textures[i].spec || back.textures[i].params != described.textures[i].params) {
      std::fprintf(stderr, "texture binding %zu did not read back as written\n", i);
      std::abort();
    }
}

// Sets the fast-path switch for one run and restores it after.
struct FastPathsForRun {
  bool saved = tfu::fast_paths_enabled();
  explicit FastPathsForRun(bool on) { tfu::set_fast_paths(on); }
  ~FastPathsForRun() { tfu::set_fast_paths(saved); }
  FastPathsForRun(const FastPathsForRun&) = delete;
  FastPathsForRun& operator=(const FastPathsForRun&) = delete;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 8192) return 0;
  ByteReader in(data, size);
  tfu::rtl::ClockedOptions clocked;
  tfu::rtl::UnitConfig unit = make_unit(in, clocked);
  tfu::Frame frame;
  tfu::Trace trace;
  bool plain = false;
  try {
    tfu::FrameBuilder fb(unit.cache.line_bytes);
    const int textures = 1 + (in.byte() & 1);
    std::vector<int> placed;
    for (int k = 0; k < textures; ++k) placed.push_back(fb.add_texture(make_texture(in), {"fuzz", {}}));
    const int samplers = static_cast<int>(in.in_range(1, 3));
    for (int k = 0; k < samplers; ++k) fb.add_sampler(make_sampler(in), false);
    trace = make_trace(in, fb, textures, samplers);
    plain = in.flag();
    frame = fb.finish();
    for (const int k : placed) {  // names last: the inputs of the corpus keep their meaning
      tfu::FrameTexture& t = frame.textures[static_cast<size_t>(k)];
      t.name = t.spec.source = in.name();
    }
    // The datapaths' pipeline depths after the names (past the input's end: the defaults), so that
    // the corpus's inputs keep their meaning.
    const uint8_t depth = in.byte();
    unit.filter.edge_stages = depth & 1 ? 8 : 3;
    unit.filter.bilinear_stages = 2 + (depth >> 1) % 3;
  } catch (const tfu::InputError&) {
    return 0;  // a descriptor the driver refuses (e.g. a ROM the kernel does not fit)
  }
  const FastPathsForRun paths(!plain);
  tfu::rtl::UnitOutput got;
  try {
    got = tfu::rtl::run_unit(frame, trace, unit, tfu::rtl::VcdOptions{}, clocked);
  } catch (const tfu::InputError&) {
    return 0;  // a frame the unit refuses
  }
  const tfu::GoldenUnit golden(frame);
  const std::string mismatch = tfu::rtl::first_mismatch(trace, tfu::rtl::golden_outputs(golden, trace, got), got);
  if (!mismatch.empty()) {
    const tfu::TraceRequest& r0 = trace.requests.front();
    const tfu::SamplerDescriptor& s0 = frame.regs.samplers[r0.sampler];
    std::fprintf(stderr, "mismatch (%s trace, first sampler %s, line %d bytes, fast paths %s): %s\n",
                 tfu::trace_mode_name(trace.mode), tfu::filter_mode_name(s0.mode).c_str(), unit.cache.line_bytes,
                 plain ? "off" : "on", mismatch.c_str());
    std::abort();
  }
  // The statistics as JSON once (with a 10^5-cycle memory the latency histograms are long).
  const std::string got_stats = got.stats.json_text();
  check_names(frame, trace, got_stats);
  // The timing recurrences (rtl/unit_recurrence.cpp) must give the clocked run's pixels, cycles
  // and statistics.
  const tfu::rtl::UnitOutput rec = tfu::rtl::run_unit_recurrence(frame, trace, unit);
  if (rec.pixels != got.pixels || rec.response_cycle != got.response_cycle || rec.cycles != got.cycles ||
      rec.edge_shapes != got.edge_shapes || rec.stats.json_text() != got_stats) {
    // Where they part: both engines again with every event recorded (rtl/engine_compare.hpp).
    std::fprintf(stderr, "the timing recurrences differ from the clocked unit: %llu against %llu cycles; %s\n",
                 static_cast<unsigned long long>(rec.cycles), static_cast<unsigned long long>(got.cycles),
                 tfu::rtl::compare_engines(frame, trace, unit).c_str());
    std::abort();
  }
  return 0;
}
