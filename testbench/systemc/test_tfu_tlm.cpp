// TfuTlm (sim/systemc/tfu_tlm.hpp) on its sockets: the register map's decode and bus errors, the
// request record's encoding, a batch against the cycle model run directly, and every refusal
// (STATUS.error with the unit's message). Built only with SystemC (sim/systemc/CMakeLists.txt).
//
// The SystemC kernel elaborates once per process, so one platform serves every test: a driver
// socket bound to the unit's target, the unit's texel port bound to a memory target; the tests
// call b_transport from sc_main after elaboration (the unit never waits, so no process is needed).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <sstream>

#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "rtl/tfu_unit.hpp"
#include "sim/systemc/memory_target.hpp"
#include "sim/systemc/tfu_tlm.hpp"
#include "testbench/iterations.hpp"

namespace tfu::test {
namespace {

using sc::BusRegion;
constexpr uint64_t kTexelWindow = 0x8000'0000;
const sc_core::sc_time kPeriod(2500, sc_core::SC_PS);  // 400 MHz

struct Platform : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Platform> bus;
  sc::TfuTlm unit;
  sc::MemoryTarget memory;
  explicit Platform(const sc_core::sc_module_name& n)
      : sc_core::sc_module(n),
        bus("bus"),
        unit("unit", rtl::UnitConfig{}, kPeriod),
        memory("memory", kTexelWindow, {}, sc_core::sc_time(7, sc_core::SC_NS)) {
    bus.bind(unit.target);
    unit.texel_port.bind(memory.socket);
  }
};
Platform* platform = nullptr;

uint64_t offset(BusRegion r, uint32_t k = 0) {
  const sc::BusRegister& g = sc::bus_registers()[static_cast<size_t>(r)];
  return g.offset + uint64_t{k} * g.stride;
}

// One bus access; returns the response status and adds the annotated delay to `delay`.
tlm::tlm_response_status access(tlm::tlm_command cmd, uint64_t address, uint32_t* words, size_t n,
                                sc_core::sc_time& delay, unsigned char* byte_enables = nullptr,
                                unsigned length_bytes = 0) {
  tlm::tlm_generic_payload tx;
  tx.set_command(cmd);
  tx.set_address(address);
  tx.set_data_ptr(reinterpret_cast<unsigned char*>(words));
  const unsigned len = length_bytes ? length_bytes : static_cast<unsigned>(4 * n);
  tx.set_data_length(len);
  tx.set_streaming_width(len);
  tx.set_byte_enable_ptr(byte_enables);
  tx.set_byte_enable_length(byte_enables ? len : 0);
  tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  platform->bus->b_transport(tx, delay);
  return tx.get_response_status();
}
void write(uint64_t address, uint32_t v, sc_core::sc_time& delay) {
  ASSERT_EQ(access(tlm::TLM_WRITE_COMMAND, address, &v, 1, delay), tlm::TLM_OK_RESPONSE) << std::hex << address;
}
uint32_t read(uint64_t address) {
  sc_core::sc_time d = sc_core::SC_ZERO_TIME;
  uint32_t v = 0xdeadbeef;
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, address, &v, 1, d), tlm::TLM_OK_RESPONSE) << std::hex << address;
  return v;
}

// The frame of a small quad trace: two textures (one mip-mapped), two samplers (trilinear, edge-preserving).
Frame test_frame(Trace& trace, const std::string& text) {
  std::istringstream in(text);
  trace = parse_trace(in, "test");
  return frame_from_trace(trace, FrameDefaults{}, 64);
}
constexpr const char* kTrace =
    "# tfu-trace mode=quad fields=texture,sampler,s,t\n"
    "# tfu-texture 0 proc:checkerboard:32\n"
    "# tfu-texture 1 proc:lightmap:16 mipmaps=none\n"
    "# tfu-sampler 0 filter=linear_mipmap_linear\n"
    "# tfu-sampler 1 filter=edge_preserving\n"
    "0,0,0.1,0.2\n0,0,0.15,0.2\n0,0,0.1,0.27\n0,0,0.15,0.27\n"
    "1,1,0.6,0.3\n1,1,0.62,0.3\n1,1,0.6,0.31\n1,1,0.62,0.31\n"
    "0,1,0.9,0.9\n0,1,0.93,0.9\n0,1,0.9,0.93\n0,1,0.93,0.93\n";

// Programs the frame and the trace's requests (the memory target gets the texel image).
void program(const Frame& frame, const Trace& trace, uint64_t texel_base = kTexelWindow) {
  sc_core::sc_time d = sc_core::SC_ZERO_TIME;
  platform->memory.bytes.assign(frame.memory.end(), 0);
  std::memcpy(platform->memory.bytes.data() + TextureMemory::kFirstAddress,
              frame.memory.bytes_at(TextureMemory::kFirstAddress), frame.memory.bytes_used());
  write(offset(BusRegion::Control), sc::kControlClear, d);
  for (uint32_t k = 0; k < frame.regs.textures.size(); ++k) {
    auto w = encode(frame.regs.textures[k]);
    ASSERT_EQ(access(tlm::TLM_WRITE_COMMAND, offset(BusRegion::TextureDescriptors, k), w.data(), w.size(), d),
              tlm::TLM_OK_RESPONSE);
  }
  for (uint32_t k = 0; k < frame.regs.samplers.size(); ++k) {
    auto w = encode(frame.regs.samplers[k]);
    ASSERT_EQ(access(tlm::TLM_WRITE_COMMAND, offset(BusRegion::SamplerDescriptors, k), w.data(), w.size(), d),
              tlm::TLM_OK_RESPONSE);
  }
  write(offset(BusRegion::TextureCount), static_cast<uint32_t>(frame.regs.textures.size()), d);
  write(offset(BusRegion::SamplerCount), static_cast<uint32_t>(frame.regs.samplers.size()), d);
  write(offset(BusRegion::TexelBaseLo), static_cast<uint32_t>(texel_base), d);
  write(offset(BusRegion::TexelBaseHi), static_cast<uint32_t>(texel_base >> 32), d);
  write(offset(BusRegion::TraceMode), static_cast<uint32_t>(trace.mode), d);
  std::vector<uint32_t> words;
  for (const TraceRequest& r : trace.requests) {
    const auto rec = sc::encode_request(r);
    words.insert(words.end(), rec.begin(), rec.end());
  }
  if (!words.empty()) {
    ASSERT_EQ(access(tlm::TLM_WRITE_COMMAND, offset(BusRegion::RequestFifo), words.data(), words.size(), d),
              tlm::TLM_OK_RESPONSE);
  }
  EXPECT_EQ(d, sc_core::SC_ZERO_TIME);  // register accesses take no time of their own
}
sc_core::sc_time start() {
  sc_core::sc_time d = sc_core::SC_ZERO_TIME;
  write(offset(BusRegion::Control), sc::kControlStart, d);
  return d;
}

TEST(TfuTlm, RequestRecordRoundTripsEveryFieldBitForBit) {
  std::mt19937 rng(35);
  for (int it = 0; it < iterations(20000); ++it) {
    TraceRequest r;
    r.texture = static_cast<uint16_t>(rng() & 0xfff);
    r.sampler = static_cast<uint8_t>(rng() & 0xff);
    r.stage = static_cast<uint8_t>(rng() & 3);
    for (float* f : {&r.s, &r.t, &r.lod, &r.dsdx, &r.dtdx, &r.dsdy, &r.dtdy})
      *f = std::bit_cast<float>(static_cast<uint32_t>(rng()));
    const TraceRequest back = sc::decode_request(sc::encode_request(r));
    ASSERT_EQ(back.texture, r.texture);
    ASSERT_EQ(back.sampler, r.sampler);
    ASSERT_EQ(back.stage, r.stage);
    for (auto [a, b] : {std::pair{back.s, r.s},
                        {back.t, r.t},
                        {back.lod, r.lod},
                        {back.dsdx, r.dsdx},
                        {back.dtdx, r.dtdx},
                        {back.dsdy, r.dsdy},
                        {back.dtdy, r.dtdy}})
      ASSERT_EQ(std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b));  // NaN payloads included
  }
  // Hand-derived: texture 0xabc, sampler 0x5d, stage 2 -> word 0 = 0x2 << 20 | 0x5d << 12 | 0xabc.
  TraceRequest r;
  r.texture = 0xabc;
  r.sampler = 0x5d;
  r.stage = 2;
  r.s = 1.0f;
  EXPECT_EQ(sc::encode_request(r)[0], 0x0025dabcu);
  EXPECT_EQ(sc::encode_request(r)[1], 0x3f800000u);
}

TEST(TfuTlm, FieldTablesDoNotOverlap) {
  std::array<uint32_t, sc::kRequestRecordWords> used{};
  for (const RegisterField& f : sc::request_record_fields()) {
    const uint32_t m = (f.width == 32 ? ~0u : (1u << f.width) - 1u) << f.lsb;
    EXPECT_EQ(used[static_cast<size_t>(f.word)] & m, 0u) << f.name;
    used[static_cast<size_t>(f.word)] |= m;
  }
  const auto regs = sc::bus_registers();
  for (size_t i = 0; i < regs.size(); ++i) {
    EXPECT_GE(regs[i].stride, 4u * static_cast<uint32_t>(regs[i].words)) << regs[i].name;
    if (i + 1 < regs.size()) {
      EXPECT_LE(regs[i].offset + uint64_t{regs[i].count} * regs[i].stride, regs[i + 1].offset) << regs[i].name;
    }
  }
}

TEST(TfuTlm, BusErrorsAndRegisterReadBack) {
  EXPECT_EQ(read(offset(BusRegion::Id)), sc::kUnitId);
  sc_core::sc_time d = sc_core::SC_ZERO_TIME;
  uint32_t v = 1;
  EXPECT_EQ(access(tlm::TLM_WRITE_COMMAND, offset(BusRegion::Id), &v, 1, d),
            tlm::TLM_ADDRESS_ERROR_RESPONSE);  // read-only
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset(BusRegion::Control), &v, 1, d),
            tlm::TLM_ADDRESS_ERROR_RESPONSE);                                                 // write-only
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, 0x30, &v, 1, d), tlm::TLM_ADDRESS_ERROR_RESPONSE);  // no register
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset(BusRegion::TextureDescriptors) + 4 * 34, &v, 1, d),
            tlm::TLM_ADDRESS_ERROR_RESPONSE);  // past descriptor 0's 34 words
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset(BusRegion::Id) + 2, &v, 1, d),
            tlm::TLM_ADDRESS_ERROR_RESPONSE);  // unaligned
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset(BusRegion::Id), &v, 1, d, nullptr, 2),
            tlm::TLM_ADDRESS_ERROR_RESPONSE);  // 2 bytes
  unsigned char be[4] = {0xff, 0xff, 0xff, 0xff};
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset(BusRegion::Id), &v, 1, d, be), tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
  // Descriptor words read back as written; a burst spans the registers it covers.
  write(offset(BusRegion::SamplerDescriptors, 255) + 20, 0x1234abcd, d);
  EXPECT_EQ(read(offset(BusRegion::SamplerDescriptors, 255) + 20), 0x1234abcdu);
  uint32_t base[2] = {0x89abcdef, 0x01234567};
  EXPECT_EQ(access(tlm::TLM_WRITE_COMMAND, offset(BusRegion::TexelBaseLo), base, 2, d), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(read(offset(BusRegion::TexelBaseHi)), 0x01234567u);
  EXPECT_EQ(read(offset(BusRegion::TexelBaseLo)), 0x89abcdefu);
}

TEST(TfuTlm, BatchEqualsTheCycleModelAndTakesCyclesTimesPeriod) {
  Trace trace;
  const Frame frame = test_frame(trace, kTrace);
  program(frame, trace);
  EXPECT_EQ(read(offset(BusRegion::RequestCount)), 12u);
  const sc_core::sc_time d = start();
  const rtl::UnitOutput want = rtl::run_unit(frame, trace, rtl::UnitConfig{});
  ASSERT_EQ(read(offset(BusRegion::Status)), sc::kStatusDone) << platform->unit.error();
  EXPECT_EQ(read(offset(BusRegion::RequestCount)), 0u);  // start empties the FIFO
  const uint64_t cycles = read(offset(BusRegion::CyclesLo)) | uint64_t{read(offset(BusRegion::CyclesHi))} << 32;
  EXPECT_EQ(cycles, want.cycles);
  EXPECT_GT(cycles, 100u);  // at least one memory latency (100 cycles by default)
  EXPECT_EQ(d, kPeriod * static_cast<double>(want.cycles));
  ASSERT_EQ(read(offset(BusRegion::ResultCount)), 12u);
  for (uint32_t i = 0; i < 12; ++i) {
    EXPECT_EQ(read(offset(BusRegion::Results, i)), std::bit_cast<uint32_t>(want.pixels[i])) << i;
    EXPECT_EQ(read(offset(BusRegion::Results, i) + 4), static_cast<uint32_t>(want.response_cycle[i])) << i;
  }
  // The texels came over the texel port: one 64-byte line per read, the memory's delay not added.
  EXPECT_EQ(platform->unit.texel_read_transactions() * 64, (frame.memory.bytes_used() + 63) / 64 * 64);
  EXPECT_EQ(platform->unit.texel_read_delay(),
            sc_core::sc_time(7, sc_core::SC_NS) * static_cast<double>(platform->unit.texel_read_transactions()));
  uint32_t v = 0;
  sc_core::sc_time dd = sc_core::SC_ZERO_TIME;
  EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset(BusRegion::Results, 12), &v, 1, dd), tlm::TLM_ADDRESS_ERROR_RESPONSE);
}

// A refused batch: STATUS done|error, no results, the message of the refusal.
void expect_refused(const std::string& message_part) {
  EXPECT_EQ(start(), sc_core::SC_ZERO_TIME);
  EXPECT_EQ(read(offset(BusRegion::Status)), sc::kStatusDone | sc::kStatusError);
  EXPECT_EQ(read(offset(BusRegion::ResultCount)), 0u);
  EXPECT_NE(platform->unit.error().find(message_part), std::string::npos) << platform->unit.error();
}

TEST(TfuTlm, RefusesBadBatchesWithTheUnitsMessage) {
  Trace trace;
  const Frame frame = test_frame(trace, kTrace);
  sc_core::sc_time d = sc_core::SC_ZERO_TIME;
  program(frame, trace);
  write(offset(BusRegion::RequestFifo), 0, d);  // the first word of a 13th record
  expect_refused("unfinished record");
  program(frame, trace);
  write(offset(BusRegion::TraceMode), 3, d);
  expect_refused("TRACE_MODE 3");
  program(frame, trace, 0x4000'0000);  // texel memory where the platform has none
  expect_refused("texel memory read of 64 bytes at bus address 0x40001000");
  program(frame, trace);
  write(offset(BusRegion::SamplerCount), 1, d);  // requests name sampler 1
  expect_refused("names texture");
  program(frame, trace);
  write(offset(BusRegion::TextureDescriptors, 1) + 8, 0, d);  // word 2: level 0 of texture 1 at address 0
  expect_refused("below the texel memory's first address");
  program(frame, trace);
  write(offset(BusRegion::TextureCount), 4097, d);
  expect_refused("TEXTURE_COUNT 4097");
  // After a refusal the unit takes the next good batch.
  program(frame, trace);
  (void)start();
  EXPECT_EQ(read(offset(BusRegion::Status)), sc::kStatusDone) << platform->unit.error();
  EXPECT_EQ(read(offset(BusRegion::ResultCount)), 12u);
}

}  // namespace
}  // namespace tfu::test

int sc_main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  tfu::test::Platform p("platform");
  tfu::test::platform = &p;
  sc_core::sc_start(sc_core::SC_ZERO_TIME);  // elaboration: the sockets are bound
  return RUN_ALL_TESTS();
}
