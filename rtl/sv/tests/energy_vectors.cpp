// tfu_energy_vectors: the input vectors of the filter datapath blocks for a real request stream,
// for scripts/energy (docs/silicon.md, "Energy per filtered pixel"). Renders a scene with its
// request trace, samples runs of consecutive requests from it, and writes for each request what the
// SystemVerilog block receives (texels, fractions, shape, level weight) and the result the C++
// model gives (the golden Sampler, sample_channels), which the gate-level simulation must reproduce.
//
//   tfu_energy_vectors --scene NAME --filter bilinear|trilinear|cubic|edge|aniso --out FILE
//                      [--size WxH] [--pixels N] [--run R]
//
// Sampling: R consecutive requests (default 64: 16 quads, in the renderer's quad order) at N / R
// evenly spaced starts over the trace, so that neighbouring requests stay neighbours as in the
// unit's input stream. Requests of textures without 8-bit channels (vs16x2) are skipped.
//
// Output (text): per stream one header "stream NAME BLOCK", lines "in PORT BITS" / "out PORT BITS"
// in port order, "data", then one line per request of hexadecimal fields (inputs, then outputs),
// then "end". Streams: bilinear -> bilinear_top (the level of the LOD); trilinear -> bilinear_top
// twice (level0, level1) and level_blend; cubic -> cubic_filter; edge -> edge_interp_top.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "cmodel/aniso.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/edge_filter.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_frame.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/trace.hpp"

namespace {

using tfu::Texel4;

constexpr int kMaxAniso = 16;  // the anisotropic streams' maxAniso (the largest the LOD unit takes)

// One 8-bit RGBA texel as the SV ports carry it: channel k in bits [8k+7:8k].
uint32_t pack(const Texel4& c) {
  return static_cast<uint32_t>(c[0]) | static_cast<uint32_t>(c[1]) << 8 | static_cast<uint32_t>(c[2]) << 16 |
         static_cast<uint32_t>(c[3]) << 24;
}

// A wide port value as hexadecimal: 32-bit words, word 0 the least significant.
std::string hex_words(const std::vector<uint32_t>& words) {
  std::string s;
  for (size_t k = words.size(); k-- > 0;) s += fmt::format("{:08x}", words[k]);
  return s;
}

struct Stream {
  std::string name, block;
  std::vector<std::pair<std::string, int>> ins, outs;
  std::vector<std::string> lines;
  void write(std::ofstream& f) const {
    f << "stream " << name << ' ' << block << '\n';
    for (const auto& [p, b] : ins) f << "in " << p << ' ' << b << '\n';
    for (const auto& [p, b] : outs) f << "out " << p << ' ' << b << '\n';
    f << "data\n";
    for (const std::string& l : lines) f << l << '\n';
    f << "end\n";
  }
};

Stream bilinear_stream(const std::string& name) {
  return {name,
          "bilinear_top",
          {{"c00", 32}, {"c10", 32}, {"c01", 32}, {"c11", 32}, {"fu", 8}, {"fv", 8}},
          {{"q", 64}, {"c", 32}},
          {}};
}

// Q.8 channels as one 64-bit port (channel k in bits [16k+15:16k]; tfu_bilinear_top's q).
uint64_t pack_q8(const Texel4& q) {
  uint64_t w = 0;
  for (size_t ch = 0; ch < 4; ++ch) w |= uint64_t{static_cast<uint16_t>(q[ch])} << (16 * ch);
  return w;
}

// The bilinear lerp's inputs on one level (taps as dp::bilinear_lerp orders them) and its results, at
// (s, t) plus a probe offset (Q.16 level-0 texels, dp::probe_texel_coord; 0 for the centre): the
// code (first) and the Q.8 result for the blend unit (second).
std::pair<Texel4, Texel4> bilinear_on_level(const tfu::Sampler& smp, int level, float s, float t, Stream& out,
                         const tfu::ProbeOffset& off = {}) {
  const tfu::Image& img = smp.texture().levels[static_cast<size_t>(level)];
  const tfu::dp::LevelCoord u =
      tfu::dp::probe_texel_coord(tfu::dp::texel_coord(s, img.width), tfu::dp::probe_offset_on_level(off.du_q16, level));
  const tfu::dp::LevelCoord v = tfu::dp::probe_texel_coord(tfu::dp::texel_coord(t, img.height),
                                                           tfu::dp::probe_offset_on_level(off.dv_q16, level));
  const int x = static_cast<int>(u.i0), y = static_cast<int>(v.i0);
  const std::array<Texel4, 4> c{smp.fetch(level, x, y), smp.fetch(level, x + 1, y), smp.fetch(level, x, y + 1),
                                smp.fetch(level, x + 1, y + 1)};
  const Texel4 r = tfu::dp::bilinear_lerp(c, u.f, v.f, tfu::TexelFormat::RGBA8);
  const Texel4 q = tfu::dp::bilinear_lerp_q8(c, u.f, v.f);
  out.lines.push_back(fmt::format("{:08x} {:08x} {:08x} {:08x} {:02x} {:02x} {:016x} {:08x}", pack(c[0]), pack(c[1]),
                                  pack(c[2]), pack(c[3]), u.f, v.f, pack_q8(q), pack(r)));
  return {r, q};
}

[[noreturn]] void usage(const std::string& what) {
  throw tfu::InputError("tfu_energy_vectors: " + what +
                        " (usage: --scene NAME --filter bilinear|trilinear|cubic|edge|aniso --out FILE [--size WxH] "
                        "[--pixels N] [--run R])");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string scene_name, filter, out_path;
    int width = 0, height = 0;
    long pixels = 4096, run = 64;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (i + 1 >= argc) usage("missing value after " + a);
      const std::string v = argv[++i];
      if (a == "--scene")
        scene_name = v;
      else if (a == "--filter")
        filter = v;
      else if (a == "--out")
        out_path = v;
      else if (a == "--size") {
        if (std::sscanf(v.c_str(), "%dx%d", &width, &height) != 2 || width < 8 || height < 8 || width > 4096 ||
            height > 4096)
          usage("--size " + v + ": expected WxH in 8..4096");
      } else if (a == "--pixels") {
        pixels = std::strtol(v.c_str(), nullptr, 10);
        if (pixels < 1 || pixels > 1'000'000) usage("--pixels " + v + ": expected 1..1000000");
      } else if (a == "--run") {
        run = std::strtol(v.c_str(), nullptr, 10);
        if (run < 4 || run > 65536 || run % 4 != 0) usage("--run " + v + ": expected a multiple of 4 in 4..65536");
      } else {
        usage("unknown option " + a);
      }
    }
    if (scene_name.empty() || out_path.empty()) usage("--scene and --out are required");
    const char* mode_name = filter == "bilinear"    ? "linear_mipmap_nearest"
                            : filter == "trilinear" ? "linear_mipmap_linear"
                            : filter == "cubic"     ? "cubic_mipmap_nearest"
                            : filter == "edge"      ? "edge_preserving_mipmap_nearest"
                            : filter == "aniso"     ? "linear_mipmap_linear"
                                                    : nullptr;
    if (!mode_name) usage("--filter " + filter + ": expected bilinear, trilinear, cubic, edge or aniso");

    tfu::SceneRequest req;
    req.name = scene_name;
    req.width = width;
    req.height = height;
    const tfu::Scene scene = tfu::open_scene(req);
    tfu::RenderOptions o;
    o.trace = true;
    const tfu::RenderResult rr = tfu::render_scene(scene, o);
    const tfu::Trace& trace = rr.trace;
    const tfu::Frame& frame = rr.frame->frame;
    if (trace.requests.size() < 4)
      throw tfu::InputError("tfu_energy_vectors: scene " + scene_name + " issues no requests");
    const std::vector<int32_t> lambdas = tfu::trace_lambdas(trace, [&](int tex) {
      const tfu::Texture& t = *frame.textures.at(static_cast<size_t>(tex)).texels;
      return std::pair<int, int>{t.width(), t.height()};
    });

    // One Sampler per (texture, sampler) pair met: the measured filter mode with the stage's wraps.
    std::map<std::pair<int, int>, std::unique_ptr<tfu::Sampler>> samplers;
    const auto sampler_for = [&](const tfu::TraceRequest& q) -> const tfu::Sampler* {
      const tfu::FrameTexture& ft = frame.textures.at(q.texture);
      if (ft.texels->format == tfu::TexelFormat::VS16X2) return nullptr;
      auto& slot = samplers[{q.texture, q.sampler}];
      if (!slot) {
        const tfu::SamplerDescriptor& stage = frame.regs.samplers.at(q.sampler);
        tfu::SamplerDescriptor cfg;
        cfg.mode = tfu::filter_mode_from_name(mode_name);
        cfg.wrap_s = stage.wrap_s;
        cfg.wrap_t = stage.wrap_t;
        cfg.border = stage.border;
        if (filter == "aniso") cfg.max_aniso = kMaxAniso;
        slot = std::make_unique<tfu::Sampler>(*ft.texels, cfg);
      }
      return slot.get();
    };

    std::vector<Stream> streams;
    if (filter == "bilinear") {
      streams.push_back(bilinear_stream("bilinear"));
    } else if (filter == "trilinear") {
      streams.push_back(bilinear_stream("level0"));
      streams.push_back(bilinear_stream("level1"));
      streams.push_back({"blend", "level_blend", {{"c0", 64}, {"c1", 64}, {"f", 8}}, {{"c", 32}}, {}});
    } else if (filter == "cubic") {
      streams.push_back({"cubic", "cubic_filter", {{"texels", 512}, {"fu", 8}, {"fv", 8}}, {{"c", 32}}, {}});
    } else if (filter == "aniso") {
      streams.push_back({"lod",
                         "aniso_lod",
                         {{"dudx", 49},
                          {"dvdx", 49},
                          {"dudy", 49},
                          {"dvdy", 49},
                          {"max_aniso", 5},
                          {"aniso_rounding", 1},
                          {"aniso_threshold", 3}},
                         {{"px2", 63},
                          {"py2", 63},
                          {"major_x", 1},
                          {"major_du", 32},
                          {"major_dv", 32},
                          {"probes", 5},
                          {"lambda_q8", 16}},
                         {}});
      streams.push_back({"probe",
                         "aniso_probe",
                         {{"major_du", 32}, {"major_dv", 32}, {"probes", 5}, {"index", 5}, {"level", 4}},
                         {{"off_du_q16", 31}, {"off_dv_q16", 31}, {"off_du_q8", 23}, {"off_dv_q8", 23}, {"weight", 9}},
                         {}});
      streams.push_back(bilinear_stream("level0"));
      streams.push_back(bilinear_stream("level1"));
      streams.push_back({"blend", "level_blend", {{"c0", 64}, {"c1", 64}, {"f", 8}}, {{"c", 32}}, {}});
    } else {
      streams.push_back(
          {"edge", "edge_interp_top", {{"texels", 384}, {"shape", 12}, {"fu", 8}, {"fv", 8}}, {{"c", 32}}, {}});
    }

    const size_t total = trace.requests.size();
    const size_t runs = static_cast<size_t>(std::max(1L, pixels / run));
    long written = 0, skipped = 0, mismatches = 0, probes = 0;
    for (size_t r = 0; r < runs && written < pixels; ++r) {
      const size_t start = (r * total / runs) & ~size_t{3};
      for (size_t i = start; i < std::min(total, start + static_cast<size_t>(run)) && written < pixels; ++i) {
        const tfu::TraceRequest& q = trace.requests[i];
        const tfu::Sampler* smp = sampler_for(q);
        if (!smp) {
          ++skipped;
          continue;
        }
        Texel4 got{}, want{};
        if (filter == "aniso") {
          // The LOD unit on the quad's derivatives, then per probe its offset and a trilinear sample.
          const tfu::Texture& tex = smp->texture();
          const auto d = tfu::request_derivatives(trace, i & ~size_t{3}, tex.width(), tex.height());
          if (!d) {
            ++skipped;
            continue;
          }
          const tfu::AnisoLod a = tfu::aniso_lod(*d, smp->descriptor().aniso());
          const auto w49 = [](int64_t x) { return static_cast<uint64_t>(x) & ((uint64_t{1} << 49) - 1); };
          streams[0].lines.push_back(
              fmt::format("{:013x} {:013x} {:013x} {:013x} {:02x} 0 0 {:016x} {:016x} {:x} {:08x} {:08x} {:02x} {:04x}",
                          w49(d->dudx), w49(d->dvdx), w49(d->dudy), w49(d->dvdy), kMaxAniso, a.px2_q32, a.py2_q32,
                          a.major_x ? 1 : 0, static_cast<uint32_t>(a.major_du_q16),
                          static_cast<uint32_t>(a.major_dv_q16), a.probes, static_cast<uint16_t>(a.lambda_q8)));
          const tfu::LodInfo li = smp->lod_info(a.lambda_q8);
          tfu::dp::AnisoAccumulator acc;
          for (int k = 1; k <= a.probes; ++k) {
            const tfu::ProbeOffset off = tfu::probe_offset(a, k);
            const auto w31 = [](int64_t x) { return static_cast<uint32_t>(x) & 0x7fffffffu; };
            const auto w23 = [](int64_t x) { return static_cast<uint32_t>(x) & 0x7fffffu; };
            streams[1].lines.push_back(fmt::format(
                "{:08x} {:08x} {:02x} {:02x} {:x} {:08x} {:08x} {:06x} {:06x} {:03x}",
                static_cast<uint32_t>(a.major_du_q16), static_cast<uint32_t>(a.major_dv_q16), a.probes, k, li.level0,
                w31(off.du_q16), w31(off.dv_q16), w23(tfu::dp::probe_offset_on_level(off.du_q16, li.level0)),
                w23(tfu::dp::probe_offset_on_level(off.dv_q16, li.level0)),
                tfu::probe_rom()[static_cast<size_t>(tfu::probe_rom_address(a.probes, k))].weight));
            const Texel4 c0 = bilinear_on_level(*smp, li.level0, q.s, q.t, streams[2], off).second;
            const Texel4 c1 = bilinear_on_level(*smp, li.level1, q.s, q.t, streams[3], off).second;
            const Texel4 c = tfu::dp::level_blend(c0, c1, li.blend);
            streams[4].lines.push_back(
                fmt::format("{:016x} {:016x} {:02x} {:08x}", pack_q8(c0), pack_q8(c1), li.blend, pack(c)));
            acc.add(c, a.probes, k);
          }
          got = acc.result();
          want = smp->sample_channels(q.s, q.t, a);
          probes += a.probes;
        } else {
          want = smp->sample_channels(q.s, q.t, lambdas[i]);
        }
        const tfu::LodInfo li = smp->lod_info(lambdas[i]);
        if (filter == "aniso") {
          // written above
        } else if (filter == "bilinear") {
          got = bilinear_on_level(*smp, li.level0, q.s, q.t, streams[0]).first;
        } else if (filter == "trilinear") {
          const Texel4 c0 = bilinear_on_level(*smp, li.level0, q.s, q.t, streams[0]).second;
          const Texel4 c1 = bilinear_on_level(*smp, li.level1, q.s, q.t, streams[1]).second;
          got = tfu::dp::level_blend(c0, c1, li.blend);
          streams[2].lines.push_back(
              fmt::format("{:016x} {:016x} {:02x} {:08x}", pack_q8(c0), pack_q8(c1), li.blend, pack(got)));
        } else if (filter == "cubic") {
          const tfu::Image& img = smp->texture().levels[static_cast<size_t>(li.level0)];
          const tfu::dp::LevelCoord u = tfu::dp::texel_coord(q.s, img.width), v = tfu::dp::texel_coord(q.t, img.height);
          std::vector<uint32_t> words;  // tap k = (column i0 - 1 + k % 4, row j0 - 1 + k / 4)
          for (int k = 0; k < 16; ++k)
            words.push_back(
                pack(smp->fetch(li.level0, static_cast<int>(u.i0) - 1 + k % 4, static_cast<int>(v.i0) - 1 + k / 4)));
          // The taps are checked through the netlists: scripts/energy's simulated cubic parts must give
          // the Sampler's result from them.
          got = want;
          streams[0].lines.push_back(fmt::format("{} {:02x} {:02x} {:08x}", hex_words(words), u.f, v.f, pack(got)));
        } else {
          const tfu::EdgeFootprint fp = smp->edge_footprint(li.level0, q.s, q.t);
          std::vector<uint32_t> words;
          for (const Texel4& c : fp.texels) words.push_back(pack(c));
          got = tfu::lee_jen::edge_preserving_interpolate(fp.texels, fp.mask, fp.fu, fp.fv, tfu::TexelFormat::RGBA8);
          streams[0].lines.push_back(
              fmt::format("{} {:03x} {:02x} {:02x} {:08x}", hex_words(words), fp.mask, fp.fu, fp.fv, pack(got)));
        }
        // The block inputs above must give the golden Sampler's result for the request.
        if (got != want) ++mismatches;
        ++written;
      }
    }
    if (mismatches != 0)
      throw std::runtime_error(
          fmt::format("{} of {} requests: the block inputs do not give the Sampler's result", mismatches, written));
    std::ofstream f(out_path);
    if (!f) throw tfu::InputError("tfu_energy_vectors: cannot write " + out_path);
    f << fmt::format(
        "# tfu-energy-vectors scene={} filter={} requests={} sampled={} runs={} run={} skipped={} probes={}\n",
        scene_name, filter, total, written, runs, run, skipped, probes);
    for (const Stream& s : streams) s.write(f);
    fmt::print("{} {}: {} of {} requests in {} runs of {}\n", scene_name, filter, written, total, runs, run);
    return 0;
  } catch (const tfu::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tfu_energy_vectors: error: %s\n", e.what());
    return 1;
  }
}
