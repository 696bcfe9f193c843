// tfu_systemc_example: a virtual platform around TfuTlm (docs/systemc.md) under the SystemC kernel.
//
//   TrafficGenerator --(bus)--> TfuTlm.target          programs the descriptors, streams the
//                                                      requests, starts the batch, reads the results
//   TfuTlm.texel_port --(bus)--> MemoryTarget               the texel image at kTexelWindow
//
// The frame and requests are those `tfu sim --requests TRACE` builds from a trace file (or from a
// built-in scene's trace, as `tfu render --trace-out` writes it). --check compares the platform's
// pixels, response cycles and cycle count with the cycle model run in-process as `tfu sim` runs it,
// and its pixels with the golden model (exit 1 on a difference); --bench times both side by side.
#include <chrono>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/error_report.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_frame.hpp"
#include "cmodel/scene_source.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "sim/systemc/memory_target.hpp"
#include "sim/systemc/tfu_tlm.hpp"

namespace tfu::sc {
namespace {

constexpr uint64_t kTexelWindow = 0x8000'0000;  // where the unit sees texel memory address 0

// The driver and the request source. Its socket is bound to the unit's target directly (a
// platform's router would subtract the unit's window base): addresses are the unit's offsets.
struct TrafficGenerator : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<TrafficGenerator> socket;
  const Frame& frame;
  const Trace& trace;
  // What the generator read back from the unit.
  std::vector<Rgba8> pixels;
  std::vector<uint32_t> response_cycle_lo;
  uint64_t cycles = 0;
  uint32_t status = 0;
  sc_core::sc_time batch_time;  // the START write's annotated delay

  SC_HAS_PROCESS(TrafficGenerator);
  TrafficGenerator(const sc_core::sc_module_name& n, const Frame& f, const Trace& t)
      : sc_core::sc_module(n), socket("socket"), frame(f), trace(t) {
    SC_THREAD(run);
  }

  void access(tlm::tlm_command cmd, uint64_t offset, uint32_t* words, size_t count, sc_core::sc_time& delay) {
    tlm::tlm_generic_payload tx;
    tx.set_command(cmd);
    tx.set_address(offset);
    tx.set_data_ptr(reinterpret_cast<unsigned char*>(words));
    tx.set_data_length(static_cast<unsigned>(count * 4));
    tx.set_streaming_width(static_cast<unsigned>(count * 4));
    tx.set_byte_enable_ptr(nullptr);
    tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    socket->b_transport(tx, delay);
    if (tx.is_response_error())
      SC_REPORT_FATAL("tfu_systemc_example",
                      fmt::format("bus access at 0x{:x}: {}", offset, tx.get_response_string()).c_str());
  }
  void write(BusRegion r, uint32_t value, sc_core::sc_time& delay) {
    access(tlm::TLM_WRITE_COMMAND, bus_registers()[static_cast<size_t>(r)].offset, &value, 1, delay);
  }
  uint32_t read(BusRegion r, sc_core::sc_time& delay) {
    uint32_t v = 0;
    access(tlm::TLM_READ_COMMAND, bus_registers()[static_cast<size_t>(r)].offset, &v, 1, delay);
    return v;
  }

  void run() {
    const auto& map = bus_registers();
    const auto at = [&](BusRegion r) { return map[static_cast<size_t>(r)]; };
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    // The driver's part: descriptor tables, counts, where the texel image is, the trace mode.
    write(BusRegion::Control, kControlClear, delay);
    for (size_t k = 0; k < frame.regs.textures.size(); ++k) {
      auto w = encode(frame.regs.textures[k]);
      access(tlm::TLM_WRITE_COMMAND,
             at(BusRegion::TextureDescriptors).offset + k * at(BusRegion::TextureDescriptors).stride, w.data(),
             w.size(), delay);
    }
    for (size_t k = 0; k < frame.regs.samplers.size(); ++k) {
      auto w = encode(frame.regs.samplers[k]);
      access(tlm::TLM_WRITE_COMMAND,
             at(BusRegion::SamplerDescriptors).offset + k * at(BusRegion::SamplerDescriptors).stride, w.data(),
             w.size(), delay);
    }
    write(BusRegion::TextureCount, static_cast<uint32_t>(frame.regs.textures.size()), delay);
    write(BusRegion::SamplerCount, static_cast<uint32_t>(frame.regs.samplers.size()), delay);
    write(BusRegion::TexelBaseLo, static_cast<uint32_t>(kTexelWindow), delay);
    write(BusRegion::TexelBaseHi, static_cast<uint32_t>(kTexelWindow >> 32), delay);
    write(BusRegion::TraceMode, static_cast<uint32_t>(trace.mode), delay);
    // The request stream: bursts of up to 64 records into the FIFO window.
    constexpr size_t kBurst = 64;
    std::vector<uint32_t> burst;
    for (size_t i = 0; i < trace.requests.size(); i += kBurst) {
      burst.clear();
      for (size_t j = i; j < std::min(trace.requests.size(), i + kBurst); ++j) {
        const auto rec = encode_request(trace.requests[j]);
        burst.insert(burst.end(), rec.begin(), rec.end());
      }
      access(tlm::TLM_WRITE_COMMAND, at(BusRegion::RequestFifo).offset, burst.data(), burst.size(), delay);
    }
    wait(delay);  // synchronise before the batch: the unit's time starts here
    delay = sc_core::SC_ZERO_TIME;
    write(BusRegion::Control, kControlStart, delay);
    batch_time = delay;
    wait(delay);
    delay = sc_core::SC_ZERO_TIME;
    status = read(BusRegion::Status, delay);
    cycles = read(BusRegion::CyclesLo, delay) | uint64_t{read(BusRegion::CyclesHi, delay)} << 32;
    const uint32_t n = read(BusRegion::ResultCount, delay);
    pixels.reserve(n);
    response_cycle_lo.reserve(n);
    std::vector<uint32_t> words(2 * kBurst);
    for (uint32_t i = 0; i < n; i += kBurst) {
      const uint32_t m = std::min<uint32_t>(kBurst, n - i);
      access(tlm::TLM_READ_COMMAND, at(BusRegion::Results).offset + uint64_t{i} * at(BusRegion::Results).stride,
             words.data(), 2 * m, delay);
      for (uint32_t j = 0; j < m; ++j) {
        pixels.push_back(std::bit_cast<Rgba8>(words[2 * j]));
        response_cycle_lo.push_back(words[2 * j + 1]);
      }
    }
    wait(delay);
  }
};

struct Options {
  std::string requests, scene, config;
  int width = 0, height = 0;
  uint64_t clock_ps = 1000;
  std::string engine = "recurrence";
  bool check = false, bench = false;
};

[[noreturn]] void usage() {
  throw InputError(
      "usage: tfu_systemc_example (--requests TRACE | --scene NAME [--width W --height H]) [--config UNIT.json] "
      "[--clock-ps P] [--engine recurrence|clocked] [--check] [--bench] | --register-map");
}

Options parse(int argc, char** argv, bool& register_map) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError(fmt::format("{} needs a value", a));
      return argv[++i];
    };
    const auto number = [&](long long lo, long long hi) {
      const std::string v = value();
      size_t used = 0;
      long long x = 0;
      try {
        x = std::stoll(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != v.size() || v.empty() || x < lo || x > hi)
        throw InputError(fmt::format("{} {:.40}: expected an integer in {}..{}", a, v, lo, hi));
      return x;
    };
    if (a == "--requests")
      o.requests = value();
    else if (a == "--scene")
      o.scene = value();
    else if (a == "--config")
      o.config = value();
    else if (a == "--width")
      o.width = static_cast<int>(number(2, kMaxRenderSize));
    else if (a == "--height")
      o.height = static_cast<int>(number(2, kMaxRenderSize));
    else if (a == "--clock-ps")
      o.clock_ps = static_cast<uint64_t>(number(1, 1'000'000'000));
    else if (a == "--engine")
      o.engine = value();
    else if (a == "--check")
      o.check = true;
    else if (a == "--bench")
      o.bench = true;
    else if (a == "--register-map")
      register_map = true;
    else
      usage();
  }
  if (!register_map && o.requests.empty() == o.scene.empty()) usage();
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(int argc, char** argv) {
  bool register_map = false;
  const Options o = parse(argc, argv, register_map);
  if (register_map) {
    std::cout << bus_register_markdown();
    return 0;
  }
  rtl::UnitConfig unit;
  if (!o.config.empty())
    unit = rtl::unit_config_from_json(read_input_file(o.config, "--config " + o.config, kMaxTextInputBytes), o.config);
  unit.validate();
  const rtl::UnitEngine engine = rtl::unit_engine_from_name(o.engine);
  // The trace as `tfu sim --requests` reads it: from the file, or the scene's trace as a file records it.
  Trace trace;
  if (!o.requests.empty()) {
    trace = load_trace(o.requests);
  } else {
    RenderOptions ro;
    ro.trace = true;
    ro.line_bytes = unit.cache.line_bytes;
    const RenderResult r = render_scene(open_scene({o.scene, o.width, o.height, ""}), ro);
    trace = loadable_trace(r.frame->frame, r.trace);
  }
  const Frame frame = frame_from_trace(trace, FrameDefaults{}, unit.cache.line_bytes);
  const std::string what = o.requests.empty() ? fmt::format("scene {} trace", o.scene) : o.requests;

  // The platform: texel image in the memory target at kTexelWindow (texel addresses 0 .. end).
  std::vector<unsigned char> image(frame.memory.end(), 0);
  if (frame.memory.bytes_used() > 0)
    std::memcpy(image.data() + TextureMemory::kFirstAddress, frame.memory.bytes_at(TextureMemory::kFirstAddress),
                frame.memory.bytes_used());
  const sc_core::sc_time period(static_cast<double>(o.clock_ps), sc_core::SC_PS);
  MemoryTarget memory("memory", kTexelWindow, std::move(image), sc_core::sc_time(10, sc_core::SC_NS));
  TfuTlm tfu("tfu", unit, period, engine);
  TrafficGenerator gen("generator", frame, trace);
  gen.socket.bind(tfu.target);
  tfu.texel_port.bind(memory.socket);
  // --bench: one unit run first, so that neither timed run pays for first use (tables built on
  // first use, page faults of the first allocations).
  if (o.bench) (void)rtl::run_unit(frame, trace, unit, engine, rtl::VcdOptions{});
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double platform_s = seconds_since(t0);

  if (gen.status & kStatusError) throw InputError(fmt::format("{}: the unit refused the batch: {}", what, tfu.error()));
  if (!(gen.status & kStatusDone))
    throw CheckFailed(fmt::format("{}: the batch did not finish (STATUS 0x{:x})", what, gen.status));
  const size_t n = trace.requests.size();
  std::cout << fmt::format("tfu_systemc_example: {} requests ({}) through TfuTlm at {} ps per cycle\n", n, what,
                           o.clock_ps);
  std::cout << fmt::format("  cycles {}  batch time {}  simulated time {}  texel reads {} ({} bytes)\n", gen.cycles,
                           gen.batch_time.to_string(), sc_core::sc_time_stamp().to_string(),
                           tfu.texel_read_transactions(), frame.memory.bytes_used());
  if (gen.batch_time != sc_core::sc_time::from_value(period.value() * gen.cycles))
    throw CheckFailed(fmt::format("the START write's delay {} is not cycles x period", gen.batch_time.to_string()));
  if (gen.pixels.size() != n)
    throw CheckFailed(fmt::format("{} results read back for {} requests", gen.pixels.size(), n));

  if (o.check || o.bench) {
    // The cycle model as `tfu sim --requests` runs it, in-process, on the same frame and trace.
    double ref_s = 1e30;
    rtl::UnitOutput ref;
    for (int k = 0; k < (o.bench ? 3 : 1); ++k) {
      const auto t1 = std::chrono::steady_clock::now();
      ref = rtl::run_unit(frame, trace, unit, engine, rtl::VcdOptions{});
      ref_s = std::min(ref_s, seconds_since(t1));
    }
    if (o.check) {
      if (gen.cycles != ref.cycles)
        throw CheckFailed(fmt::format("cycles: platform {}, tfu sim {}", gen.cycles, ref.cycles));
      for (size_t i = 0; i < n; ++i) {
        if (gen.pixels[i] != ref.pixels[i] || gen.response_cycle_lo[i] != static_cast<uint32_t>(ref.response_cycle[i]))
          throw CheckFailed(
              fmt::format("request {}: platform ({},{},{},{}) at cycle {}, tfu sim ({},{},{},{}) at cycle {}", i,
                          gen.pixels[i].r, gen.pixels[i].g, gen.pixels[i].b, gen.pixels[i].a, gen.response_cycle_lo[i],
                          ref.pixels[i].r, ref.pixels[i].g, ref.pixels[i].b, ref.pixels[i].a, ref.response_cycle[i]));
      }
      const GoldenUnit golden(frame);
      const std::string mismatch =
          rtl::first_mismatch(trace, rtl::golden_outputs(golden, trace, tfu.output()), tfu.output());
      if (!mismatch.empty()) throw CheckFailed(mismatch);
      std::cout << fmt::format(
          "  check: cycles and all {} pixels and response cycles equal to tfu sim's; golden compare: all {} equal\n", n,
          n);
    }
    if (o.bench)
      std::cout << fmt::format(
          "  bench: tfu sim's unit run {:.2f} ms, SystemC platform {:.2f} ms (x{:.2f}; {:.0f} ns per request more; "
          "the unit's run inside it {:.2f} ms)\n",
          ref_s * 1e3, platform_s * 1e3, platform_s / ref_s,
          n ? (platform_s - ref_s) * 1e9 / static_cast<double>(n) : 0.0, tfu.model_seconds() * 1e3);
  }
  return 0;
}

}  // namespace
}  // namespace tfu::sc

int sc_main(int argc, char** argv) {
  try {
    return tfu::sc::run(argc, argv);
  } catch (...) {
    return tfu::report_error(std::current_exception());
  }
}
