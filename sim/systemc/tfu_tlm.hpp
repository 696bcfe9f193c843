// TfuTlm: the texture filter unit as a SystemC TLM-2.0 loosely-timed model for virtual platforms
// (docs/systemc.md). It wraps the cycle model (rtl/tfu_unit.hpp run_unit, the same library
// `tfu sim` calls), never a second implementation:
//
//   target socket     the unit's registers, memory-mapped (kBusRegisters): control and status,
//                     the texture and sampler descriptor tables in their register encoding
//                     (cmodel/descriptors.hpp, docs/descriptors.md), a request FIFO window taking
//                     request records (kRequestRecordFields), and the results window
//   initiator socket  the unit's texel memory port: at START the unit reads every byte its bound
//                     texture descriptors cover from the platform, at TEXEL_BASE + descriptor address
//
// Timing (loosely timed, b_transport): register accesses take no time of their own (the
// interconnect's latency is the platform's); the write that sets CONTROL.start returns with its
// delay increased by the batch's cycles (the cycle model's count, texel memory latency and
// bandwidth included: rtl/memory_model.hpp) times the configured clock period. The texel reads the
// unit issues over its initiator socket are functional (their annotated delay is counted in
// `texel_read_delay()` but not added: the unit's memory timing is the cycle model's MemoryConfig).
//
// Bus words are 32 bits, little endian (the host's byte order in the transaction's data array);
// every access is word aligned, a multiple of 4 bytes long, and has no byte enables.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

#include "cmodel/descriptors.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"

namespace tfu::sc {

// ---- The register map as the bus sees it (byte offsets from the unit's base address) ----
enum class BusAccess { ReadOnly, WriteOnly, ReadWrite };
enum class BusRegion {
  Id,
  Control,
  Status,
  TraceMode,
  TextureCount,
  SamplerCount,
  TexelBaseLo,
  TexelBaseHi,
  RequestCount,
  ResultCount,
  CyclesLo,
  CyclesHi,
  TextureDescriptors,
  SamplerDescriptors,
  RequestFifo,
  Results
};
// One region: `count` elements of `words` 32-bit words, element k at offset + k * stride.
struct BusRegister {
  BusRegion region;
  const char* name;
  uint64_t offset;
  int words;
  uint32_t count, stride;
  BusAccess access;
  const char* meaning;
};
std::span<const BusRegister> bus_registers();
inline constexpr uint32_t kUnitId = 0x54465531;  // "TFU1"
// CONTROL bits (write 1 to act) and STATUS bits.
inline constexpr uint32_t kControlStart = 1u << 0, kControlClear = 1u << 1;
inline constexpr uint32_t kStatusDone = 1u << 0, kStatusError = 1u << 1;
// Request and result capacity of one batch (the request FIFO and the results window).
inline constexpr uint32_t kMaxBatchRequests = 1u << 24;

// ---- A request as written to the request FIFO: one record of 8 words ----
// The fields of QuadReq (rtl/unit_ports.hpp) for one pixel: descriptor indices, FP32 coordinates,
// and the explicit LOD (lod traces) or gradients (grad traces); quad traces write the four pixels
// of a quad as four consecutive records. RegisterField as the descriptor tables use it.
inline constexpr int kRequestRecordWords = 8;
std::span<const RegisterField> request_record_fields();
std::array<uint32_t, kRequestRecordWords> encode_request(const TraceRequest& r);
TraceRequest decode_request(std::span<const uint32_t, kRequestRecordWords> w);
// A result in the results window: word 0 the filtered texel word (R [7:0], G [15:8], B [23:16],
// A [31:24]), word 1 the cycle the pixel left the unit (bits [31:0]).
inline constexpr int kResultWords = 2;

// The register map and the request record as Markdown tables (docs/systemc.md reproduces them).
std::string bus_register_markdown();

// ---- The module ----
class TfuTlm : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<TfuTlm> target;         // registers
  tlm_utils::simple_initiator_socket<TfuTlm> texel_port;  // texel memory reads

  // `unit`: the hardware configuration (rtl/unit_config.hpp; cache line, memory latency and
  // bandwidth, ...); `clock_period`: one cycle of the unit; `engine`: how the cycle model runs
  // (both engines give the same pixels and cycles).
  TfuTlm(const sc_core::sc_module_name& name, const rtl::UnitConfig& unit, const sc_core::sc_time& clock_period,
         rtl::UnitEngine engine = rtl::UnitEngine::Recurrence);

  // The last batch: the cycle model's output (pixels, response cycles, cycles, statistics).
  const rtl::UnitOutput& output() const { return out_; }
  // Why STATUS.error is set: the one-line message of the unit's InputError (empty if none).
  const std::string& error() const { return error_; }
  sc_core::sc_time texel_read_delay() const { return texel_read_delay_; }
  uint64_t texel_read_transactions() const { return texel_reads_; }
  // Host time (seconds, wall clock) of the last batch's cycle model run alone: for the overhead
  // figures of docs/systemc.md, not a simulated quantity.
  double model_seconds() const { return model_seconds_; }

 private:
  void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay);
  unsigned int transport_dbg(tlm::tlm_generic_payload& tx);
  // One word access; false for an address no register decodes or a wrong direction.
  bool write_word(uint64_t address, uint32_t value, sc_core::sc_time& delay);
  bool read_word(uint64_t address, uint32_t& value) const;
  void start(sc_core::sc_time& delay);
  void clear();
  Frame fetch_frame();

  rtl::UnitConfig unit_;
  sc_core::sc_time period_;
  rtl::UnitEngine engine_;
  uint32_t status_ = 0, trace_mode_ = static_cast<uint32_t>(TraceMode::Quad), texture_count_ = 0, sampler_count_ = 0;
  uint64_t texel_base_ = 0;
  std::vector<uint32_t> texture_words_, sampler_words_;  // the descriptor tables
  std::vector<TraceRequest> requests_;
  std::array<uint32_t, kRequestRecordWords> partial_{};  // the record being written
  int partial_words_ = 0;
  rtl::UnitOutput out_;
  std::string error_;
  sc_core::sc_time texel_read_delay_ = sc_core::SC_ZERO_TIME;
  uint64_t texel_reads_ = 0;
  double model_seconds_ = 0;
};

}  // namespace tfu::sc
