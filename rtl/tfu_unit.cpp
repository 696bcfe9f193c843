#include "rtl/tfu_unit.hpp"

#include <algorithm>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/json_input.hpp"
#include "rtl/address_gen.hpp"
#include "rtl/cache_stage.hpp"
#include "rtl/edge_datapath.hpp"
#include "rtl/filter_unit.hpp"
#include "rtl/lod_unit.hpp"
#include "rtl/request_fifo.hpp"
#include "rtl/response.hpp"
#include "rtl/unit_watchdog.hpp"

namespace tfu::rtl {

const char* shape_policy_name(ShapePolicy p) {
  switch (p) {
    case ShapePolicy::Static: return "static";
    case ShapePolicy::CacheAware: return "cache-aware";
    case ShapePolicy::FullCross: return "full-cross";
  }
  return "?";
}

ShapePolicy shape_policy_from_name(const std::string& name) {
  for (ShapePolicy p : {ShapePolicy::Static, ShapePolicy::CacheAware, ShapePolicy::FullCross})
    if (name == shape_policy_name(p)) return p;
  throw InputError(fmt::format("unknown kernel-shape policy '{}' (expected static, cache-aware or full-cross)", quote_input(name)));
}

void UnitConfig::validate() const {
  cache.validate();
  memory.validate();
  if (channel_depth < 1 || channel_depth > 64)
    throw InputError(fmt::format("channel_depth {} must be in 1..64", channel_depth));
  if (miss_fifo_depth < 1 || miss_fifo_depth > 1024)
    throw InputError(fmt::format("miss_fifo_depth {} must be in 1..1024", miss_fifo_depth));
  if (filter_lanes != 1 && filter_lanes != 2 && filter_lanes != 4)
    throw InputError(fmt::format("filter_lanes {} must be 1, 2 or 4", filter_lanes));
}

namespace {

using nlohmann::json;

int get_int(const json& j, const char* key, const std::string& where) {
  const json& v = j.at(key);
  if (!v.is_number_integer()) throw InputError(fmt::format("{}: '{}' must be an integer", where, key));
  // An unsigned value above INT64_MAX would read as negative: check it as unsigned first.
  if (v.is_number_unsigned() ? v.get<uint64_t>() > uint64_t{INT32_MAX} : (v.get<int64_t>() < INT32_MIN || v.get<int64_t>() > INT32_MAX))
    throw InputError(fmt::format("{}: '{}' value {} is out of range", where, key, json_number_text(v)));
  return static_cast<int>(v.get<int64_t>());
}

void check_keys(const json& j, std::initializer_list<const char*> keys, const std::string& where) {
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object", where));
  for (const auto& [k, v] : j.items())
    if (std::find_if(keys.begin(), keys.end(), [&k = k](const char* x) { return k == x; }) == keys.end())
      throw InputError(fmt::format("{}: unknown key '{}'", where, quote_input(k)));
}

}  // namespace

UnitConfig unit_config_from_json(const std::string& text, const std::string& name) {
  const json j = parse_json_input(text, name);  // InputError "NAME: line L, column C: malformed JSON: ..."
  UnitConfig c;
  check_keys(j, {"cache", "memory", "channel_depth", "miss_fifo_depth", "filter_lanes", "shape_policy"}, name);
  if (j.contains("cache")) {
    const json& k = j["cache"];
    const std::string w = name + ": cache";
    check_keys(k, {"block", "capacity_bytes", "ways", "banks", "bank_mapping"}, w);
    if (k.contains("block")) c.cache.block = get_int(k, "block", w);
    if (k.contains("capacity_bytes")) c.cache.capacity_bytes = get_int(k, "capacity_bytes", w);
    if (k.contains("ways")) c.cache.ways = get_int(k, "ways", w);
    if (k.contains("banks")) c.cache.banks = get_int(k, "banks", w);
    if (k.contains("bank_mapping")) {
      const json& b = k["bank_mapping"];
      if (b == "texel-parity") {
        c.cache.bank_mapping = BankMapping::TexelParity;
      } else if (b == "block-parity") {
        c.cache.bank_mapping = BankMapping::BlockParity;
      } else {
        throw InputError(fmt::format("{}: bank_mapping must be \"texel-parity\" or \"block-parity\"", w));
      }
    }
  }
  if (j.contains("memory")) {
    const json& m = j["memory"];
    const std::string w = name + ": memory";
    check_keys(m, {"latency", "bytes_per_cycle"}, w);
    if (m.contains("latency")) c.memory.latency = get_int(m, "latency", w);
    if (m.contains("bytes_per_cycle")) c.memory.bytes_per_cycle = get_int(m, "bytes_per_cycle", w);
  }
  if (j.contains("channel_depth")) c.channel_depth = get_int(j, "channel_depth", name);
  if (j.contains("miss_fifo_depth")) c.miss_fifo_depth = get_int(j, "miss_fifo_depth", name);
  if (j.contains("filter_lanes")) c.filter_lanes = get_int(j, "filter_lanes", name);
  if (j.contains("shape_policy")) {
    if (!j["shape_policy"].is_string()) throw InputError(fmt::format("{}: 'shape_policy' must be a string", name));
    try {
      c.shape_policy = shape_policy_from_name(j["shape_policy"].get<std::string>());
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: shape_policy: {}", name, e.what()));
    }
  }
  try {
    c.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", name, e.what()));
  }
  return c;
}

std::string unit_config_to_json(const UnitConfig& c) {
  json j;
  j["cache"] = {{"block", c.cache.block},
                {"capacity_bytes", c.cache.capacity_bytes},
                {"ways", c.cache.ways},
                {"banks", c.cache.banks},
                {"bank_mapping", c.cache.bank_mapping == BankMapping::TexelParity ? "texel-parity" : "block-parity"}};
  j["memory"] = {{"latency", c.memory.latency}, {"bytes_per_cycle", c.memory.bytes_per_cycle}};
  j["channel_depth"] = c.channel_depth;
  j["miss_fifo_depth"] = c.miss_fifo_depth;
  j["filter_lanes"] = c.filter_lanes;
  j["shape_policy"] = shape_policy_name(c.shape_policy);
  return j.dump(2);
}

SamplerConfig golden_sampler_config(const SamplerConfig& cfg, const UnitConfig& u) {
  SamplerConfig g = cfg;
  if (u.shape_policy == ShapePolicy::FullCross) {
    g.edge_shape = EdgeShapePolicy::Cross;
  } else {
    g.edge_shape = EdgeShapePolicy::CacheBlock;
    g.edge_cache_block = u.cache.block;
  }
  return g;
}

Rgba8 golden_pixel(const Sampler& golden, const UnitConfig& u, const UnitOutput& out, const TraceRequest& r,
                   int32_t lambda, size_t i) {
  if (golden.config().mode.base == BaseFilter::EdgePreserving && u.shape_policy == ShapePolicy::CacheAware)
    return golden.sample_edge_masks(r.s, r.t, lambda, out.edge_shapes.at(i));
  return golden.sample(r.s, r.t, lambda);
}

UnitOutput run_unit(const Texture& tex, const SamplerConfig& cfg_in, const Trace& trace, const UnitConfig& ucfg,
                    std::ostream* vcd_stream) {
  ucfg.validate();
  if (trace.mode == TraceMode::Quad && trace.requests.size() % 4 != 0)
    throw InputError("a quad trace needs a multiple of 4 requests");
  const SamplerConfig cfg = golden_sampler_config(cfg_in, ucfg);
  const Sampler smp(tex, cfg);
  const bool edge = cfg.mode.base == BaseFilter::EdgePreserving;
  TexelCacheConfig cc = ucfg.cache;
  cc.bytes_per_texel = bytes_per_texel(tex.format);
  std::vector<int> ws, hs;
  std::vector<const Image*> levels;
  for (size_t l = 0; l < tex.levels.size(); ++l) {
    ws.push_back(tex.levels[l].width);
    hs.push_back(tex.levels[l].height);
    levels.push_back(cfg.mode.base == BaseFilter::Cubic ? &smp.filtered_level(static_cast<int>(l)) : &tex.levels[l]);
  }
  TexelCache cache(cc, ws, hs);
  MemoryModel mem(ucfg.memory);
  // bspline-interp coefficients outside a clamp-to-border texture are zero (Sampler: the coefficient
  // reader's border); every other filter reads the border word.
  const bool coeffs = cfg.mode.base == BaseFilter::Cubic && smp.cubic_normalize().prefiltered;
  const Rgba8 border = coeffs ? Rgba8{0, 0, 0, 0} : cfg.border;

  const size_t n = trace.requests.size();
  UnitOutput out;
  out.pixels.resize(n);
  out.response_cycle.resize(n);
  std::vector<uint64_t> accept(n, 0);
  sim::Simulator sim(no_progress_limit(ucfg));  // the watchdog; no total-cycle cap (unit_watchdog.hpp)
  const auto depth = static_cast<size_t>(ucfg.channel_depth);
  sim::Channel<QuadReq> c_quad("quad", depth);
  sim::Channel<PixelReq> c_pixel("pixel", depth);
  sim::Channel<FootprintReq> c_addr("footprint", depth);
  sim::Channel<FootprintReq> c_shape("shaped_footprint", depth);
  sim::Channel<FilterReq> c_texels("texels", depth);
  sim::Channel<EdgeS1> c_s1("edge_s1", depth);
  sim::Channel<EdgeS2> c_s2("edge_s2", depth);
  sim::Channel<Response> c_resp("response", depth);
  for (sim::ChannelBase* c : std::initializer_list<sim::ChannelBase*>{&c_quad, &c_pixel, &c_addr, &c_shape, &c_texels, &c_resp})
    sim.add_clocked(c);
  if (edge) {
    sim.add_clocked(&c_s1);
    sim.add_clocked(&c_s2);
  }
  RequestFifo src(sim, trace, c_quad, accept);
  LodUnit lod(sim, c_quad, c_pixel, trace.mode, tex.width(), tex.height(), cfg.mode.mip != MipMode::None);
  AddressGen addr(sim, c_pixel, c_addr, smp);
  KernelSelect shape(sim, c_addr, c_shape, edge, ucfg.shape_policy, ucfg.cache.block);
  CacheStage cst(sim, c_shape, c_texels, levels, border, edge, cache, mem, ucfg.miss_fifo_depth);
  std::unique_ptr<FilterUnit> filter;
  std::unique_ptr<EdgeMedian> e1;
  std::unique_ptr<EdgeDirection> e2;
  std::unique_ptr<EdgeMerge> e3;
  if (edge) {
    e1 = std::make_unique<EdgeMedian>(sim, c_texels, c_s1, tex.format);
    e2 = std::make_unique<EdgeDirection>(sim, c_s1, c_s2, tex.format);
    e3 = std::make_unique<EdgeMerge>(sim, c_s2, c_resp, tex.format);
  } else {
    filter = std::make_unique<FilterUnit>(sim, c_texels, c_resp, smp, ucfg.filter_lanes);
  }
  ResponseSink sink(sim, c_resp, out.pixels, out.response_cycle, accept);

  std::unique_ptr<sim::VcdWriter> vcd;
  if (vcd_stream) {
    vcd = std::make_unique<sim::VcdWriter>(*vcd_stream);
    const auto channel = [&](const auto& ch) {
      vcd->add(fmt::format("tfu.{}.valid", ch.name()), 1, [&ch] { return uint64_t{ch.can_pop()}; });
      vcd->add(fmt::format("tfu.{}.ready", ch.name()), 1, [&ch] { return uint64_t{ch.can_push()}; });
      vcd->add(fmt::format("tfu.{}.count", ch.name()), 8, [&ch] { return uint64_t{ch.size()}; });
    };
    channel(c_quad);
    channel(c_pixel);
    channel(c_addr);
    channel(c_shape);
    channel(c_texels);
    if (edge) {
      channel(c_s1);
      channel(c_s2);
    }
    channel(c_resp);
    vcd->add("tfu.lod_unit.busy", 1, [&lod] { return uint64_t{lod.busy()}; });
    vcd->add("tfu.address_gen.busy", 1, [&addr] { return uint64_t{addr.busy()}; });
    vcd->add("tfu.texel_cache.busy", 1, [&cst] { return uint64_t{cst.busy()}; });
    vcd->add("tfu.texel_cache.id", 32, [&cst] { return uint64_t{cst.current_id()}; });
    vcd->add("tfu.response.count", 32, [&sink] { return uint64_t{sink.retired()}; });
    sim.set_vcd(vcd.get());
  }

  sim.set_idle_skip(ucfg.idle_skip);
  sim.run([&] { return sink.retired() == n; }, sim::Simulator::kNoCycleLimit,
          [&] { return static_cast<uint64_t>(sink.retired()); }, n);
  out.cycles = sim.cycle();
  out.edge_shapes = std::move(cst.shapes);
  cst.publish(sim.stats());
  out.stats = sim.stats();
  out.stats.add("cycles", out.cycles);
  out.stats.add("pixels", n);
  out.stats.add("memory_bytes", mem.bytes_read());
  out.stats.add("memory_requests", mem.requests());
  if (filter) out.stats.add("filter_lane_busy_cycles", filter->busy_cycles());
  if (e2) out.stats.set_histogram("edge_direction", std::vector<uint64_t>(e2->chosen.begin(), e2->chosen.end()));
  out.stats.set_histogram("latency", sink.latency);
  const auto dn = static_cast<double>(n);
  out.stats.set("pixels_per_clock", out.cycles ? dn / static_cast<double>(out.cycles) : 0.0);
  out.stats.set("memory_bytes_per_pixel", n ? static_cast<double>(mem.bytes_read()) / dn : 0.0);
  const uint64_t h = out.stats.counter("cache_line_hits"), m = out.stats.counter("cache_line_misses");
  out.stats.set("cache_hit_rate", h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0);
  uint64_t lat_sum = 0, lat_min = UINT64_MAX, lat_max = 0;
  for (size_t c = 0; c < sink.latency.size(); ++c)
    if (sink.latency[c]) {
      lat_sum += c * sink.latency[c];
      lat_min = std::min<uint64_t>(lat_min, c);
      lat_max = c;
    }
  out.stats.set("latency_mean", n ? static_cast<double>(lat_sum) / dn : 0.0);
  out.stats.set("latency_min", n ? static_cast<double>(lat_min) : 0.0);
  out.stats.set("latency_max", static_cast<double>(lat_max));
  return out;
}

}  // namespace tfu::rtl
