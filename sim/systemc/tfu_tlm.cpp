// TfuTlm: the unit's registers on a TLM-2.0 target socket, its texel memory port on an initiator
// socket, the cycle model behind them (sim/systemc/tfu_tlm.hpp, docs/systemc.md).
#include "sim/systemc/tfu_tlm.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>
#include <iterator>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/texture_memory.hpp"

namespace tfu::sc {

// ---------------------------------------------------------------- the register map
namespace {

using BA = BusAccess;
using BR = BusRegion;
constexpr BusRegister kBusRegisters[] = {
    {BR::Id, "ID", 0x000, 1, 1, 4, BA::ReadOnly, "0x54465531 (\"TFU1\")"},
    {BR::Control, "CONTROL", 0x004, 1, 1, 4, BA::WriteOnly,
     "bit 0 start: run the FIFO's requests as one batch (the FIFO is then empty); bit 1 clear: empty the FIFO and the "
     "results"},
    {BR::Status, "STATUS", 0x008, 1, 1, 4, BA::ReadOnly,
     "bit 0 done: the last batch finished; bit 1 error: it was refused (the unit's one-line message: TfuTlm::error())"},
    {BR::TraceMode, "TRACE_MODE", 0x00c, 1, 1, 4, BA::ReadWrite,
     "how requests give their LOD: 0 lod, 1 grad, 2 quad (4 records a 2x2 quad; reset 2)"},
    {BR::TextureCount, "TEXTURE_COUNT", 0x010, 1, 1, 4, BA::ReadWrite,
     "texture descriptors bound: 0..4096 (descriptors 0..n-1)"},
    {BR::SamplerCount, "SAMPLER_COUNT", 0x014, 1, 1, 4, BA::ReadWrite, "sampler descriptors bound: 0..256"},
    {BR::TexelBaseLo, "TEXEL_BASE_LO", 0x018, 1, 1, 4, BA::ReadWrite,
     "bus address of texel memory address 0, bits [31:0]"},
    {BR::TexelBaseHi, "TEXEL_BASE_HI", 0x01c, 1, 1, 4, BA::ReadWrite, "bits [63:32] of the same"},
    {BR::RequestCount, "REQUEST_COUNT", 0x020, 1, 1, 4, BA::ReadOnly, "whole request records in the FIFO"},
    {BR::ResultCount, "RESULT_COUNT", 0x024, 1, 1, 4, BA::ReadOnly, "results of the last batch (one per request)"},
    {BR::CyclesLo, "CYCLES_LO", 0x028, 1, 1, 4, BA::ReadOnly,
     "cycles of the last batch (the cycle model's count), bits [31:0]"},
    {BR::CyclesHi, "CYCLES_HI", 0x02c, 1, 1, 4, BA::ReadOnly, "bits [63:32] of the same"},
    {BR::TextureDescriptors, "TEXTURE_DESCRIPTOR[k]", 0x10'0000, kTextureDescriptorWords, 4096, 0x100, BA::ReadWrite,
     "texture descriptor k: its 34 words (docs/descriptors.md), word w at + 4 w"},
    {BR::SamplerDescriptors, "SAMPLER_DESCRIPTOR[k]", 0x20'0000, kSamplerDescriptorWords, 256, 0x20, BA::ReadWrite,
     "sampler descriptor k: its 6 words (docs/descriptors.md), word w at + 4 w"},
    {BR::RequestFifo, "REQUEST_FIFO", 0x30'0000, 0x400, 1, 0x1000, BA::WriteOnly,
     "request records of 8 words (below) in order, any address of the window; a burst carries several"},
    {BR::Results, "RESULT[i]", 0x100'0000, kResultWords, kMaxBatchRequests, 8, BA::ReadOnly,
     "result of request i of the last batch: word 0 the texel word (R [7:0] .. A [31:24]), word 1 its response cycle "
     "[31:0]"},
};

// The table is indexed by BusRegion.
static_assert([] {
  for (size_t i = 0; i < std::size(kBusRegisters); ++i)
    if (kBusRegisters[i].region != static_cast<BusRegion>(i)) return false;
  return std::size(kBusRegisters) == static_cast<size_t>(BusRegion::Results) + 1;
}());

// One field of the request record: its place in the words and how a TraceRequest holds it.
struct RequestCodec {
  RegisterField field;
  uint32_t (*get)(const TraceRequest&);
  void (*set)(TraceRequest&, uint32_t bits);
};
#define TFU_FLOAT_FIELD(member, word, meaning)                                                                      \
  RequestCodec {                                                                                                    \
    {#member, word, 0, 32, 1, 0, meaning}, [](const TraceRequest& r) { return std::bit_cast<uint32_t>(r.member); }, \
        [](TraceRequest& r, uint32_t b) { r.member = std::bit_cast<float>(b); }                                     \
  }
const RequestCodec kRequestCodecs[] = {
    {{"texture", 0, 0, 12, 1, 0, "texture descriptor index"},
     [](const TraceRequest& r) { return uint32_t{r.texture}; },
     [](TraceRequest& r, uint32_t b) { r.texture = static_cast<uint16_t>(b); }},
    {{"sampler", 0, 12, 8, 1, 0, "sampler descriptor index"},
     [](const TraceRequest& r) { return uint32_t{r.sampler}; },
     [](TraceRequest& r, uint32_t b) { r.sampler = static_cast<uint8_t>(b); }},
    {{"stage", 0, 20, 2, 1, 0, "material stage that issued it (statistics only)"},
     [](const TraceRequest& r) { return uint32_t{r.stage}; },
     [](TraceRequest& r, uint32_t b) { r.stage = static_cast<uint8_t>(b); }},
    TFU_FLOAT_FIELD(s, 1, "texture coordinate s, IEEE binary32"),
    TFU_FLOAT_FIELD(t, 2, "texture coordinate t, IEEE binary32"),
    TFU_FLOAT_FIELD(lod, 3, "explicit LOD (TRACE_MODE lod), binary32"),
    TFU_FLOAT_FIELD(dsdx, 4, "ds/dx (TRACE_MODE grad), binary32"),
    TFU_FLOAT_FIELD(dtdx, 5, "dt/dx (grad), binary32"),
    TFU_FLOAT_FIELD(dsdy, 6, "ds/dy (grad), binary32"),
    TFU_FLOAT_FIELD(dtdy, 7, "dt/dy (grad), binary32"),
};
#undef TFU_FLOAT_FIELD

constexpr uint32_t field_mask(int width) { return width == 32 ? ~0u : (1u << width) - 1u; }

const BusRegister& reg(BusRegion r) { return kBusRegisters[static_cast<size_t>(r)]; }

// The register an address falls in: the element index and the word inside the element.
struct Decoded {
  const BusRegister* reg = nullptr;
  uint32_t index = 0, word = 0;
};
// The regions are in address order without overlap: the only candidate is the last one that starts
// at or below the address.
static_assert([] {
  for (size_t i = 0; i + 1 < std::size(kBusRegisters); ++i)
    if (kBusRegisters[i].offset + uint64_t{kBusRegisters[i].count} * kBusRegisters[i].stride >
        kBusRegisters[i + 1].offset)
      return false;
  return true;
}());
Decoded decode_address(uint64_t address) {
  for (size_t i = std::size(kBusRegisters); i-- > 0;) {
    const BusRegister& r = kBusRegisters[i];
    if (address < r.offset) continue;
    const uint64_t d = address - r.offset, k = d / r.stride, w = d % r.stride / 4;
    if (k < r.count && w < static_cast<uint64_t>(r.words))
      return {&r, static_cast<uint32_t>(k), static_cast<uint32_t>(w)};
    return {};
  }
  return {};
}

}  // namespace

std::span<const BusRegister> bus_registers() { return kBusRegisters; }

std::span<const RegisterField> request_record_fields() {
  static const std::vector<RegisterField> fields = [] {
    std::vector<RegisterField> f;
    for (const RequestCodec& c : kRequestCodecs) f.push_back(c.field);
    return f;
  }();
  return fields;
}

std::array<uint32_t, kRequestRecordWords> encode_request(const TraceRequest& r) {
  std::array<uint32_t, kRequestRecordWords> w{};
  for (const RequestCodec& c : kRequestCodecs)
    w[static_cast<size_t>(c.field.word)] |= (c.get(r) & field_mask(c.field.width)) << c.field.lsb;
  return w;
}

TraceRequest decode_request(std::span<const uint32_t, kRequestRecordWords> w) {
  TraceRequest r;
  for (const RequestCodec& c : kRequestCodecs)
    c.set(r, (w[static_cast<size_t>(c.field.word)] >> c.field.lsb) & field_mask(c.field.width));
  return r;
}

std::string bus_register_markdown() {
  std::string md = "| register | offset | words | elements (stride) | access | meaning |\n|---|---|---:|---|---|---|\n";
  for (const BusRegister& r : kBusRegisters) {
    const char* access = r.access == BA::ReadOnly ? "RO" : r.access == BA::WriteOnly ? "WO" : "RW";
    const std::string elements = r.count == 1 ? std::string("1") : fmt::format("{} (0x{:x})", r.count, r.stride);
    md += fmt::format("| `{}` | 0x{:07x} | {} | {} | {} | {} |\n", r.name, r.offset, r.words, elements, access,
                      r.meaning);
  }
  md += "\nRequest record (8 words):\n\n| field | word | bits | meaning |\n|---|---:|---|---|\n";
  for (const RegisterField& f : request_record_fields())
    md += fmt::format("| `{}` | {} | [{}:{}] | {} |\n", f.name, f.word, f.lsb + f.width - 1, f.lsb, f.meaning);
  return md;
}

// ---------------------------------------------------------------- the module
TfuTlm::TfuTlm(const sc_core::sc_module_name& name, const rtl::UnitConfig& unit, const sc_core::sc_time& clock_period,
               rtl::UnitEngine engine)
    : sc_core::sc_module(name),
      target("target"),
      texel_port("texel_port"),
      unit_(unit),
      period_(clock_period),
      engine_(engine),
      texture_words_(size_t{reg(BR::TextureDescriptors).count} * kTextureDescriptorWords, 0),
      sampler_words_(size_t{reg(BR::SamplerDescriptors).count} * kSamplerDescriptorWords, 0) {
  unit_.validate();
  if (period_ <= sc_core::SC_ZERO_TIME) throw InputError("the unit's clock period must be positive");
  target.register_b_transport(this, &TfuTlm::b_transport);
  target.register_transport_dbg(this, &TfuTlm::transport_dbg);
}

void TfuTlm::b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay) {
  const unsigned len = tx.get_data_length();
  if (tx.get_byte_enable_ptr() != nullptr) return tx.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
  if (tx.get_streaming_width() < len) return tx.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
  if (tx.get_address() % 4 != 0 || len % 4 != 0 || len == 0)
    return tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
  tx.set_response_status(tlm::TLM_OK_RESPONSE);
  if (tx.is_read() || tx.is_write()) {
    unsigned char* data = tx.get_data_ptr();
    // A burst inside the request FIFO's window (the bulk of the traffic): records without a decode per word.
    const BusRegister& fifo = reg(BR::RequestFifo);
    if (tx.is_write() && tx.get_address() >= fifo.offset &&
        tx.get_address() + len <= fifo.offset + 4u * static_cast<uint64_t>(fifo.words)) {
      for (unsigned k = 0; k < len; k += 4) {
        if (partial_words_ == 0 && requests_.size() >= kMaxBatchRequests)
          return tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
        std::memcpy(&partial_[static_cast<size_t>(partial_words_++)], data + k, 4);
        if (partial_words_ == kRequestRecordWords) {
          requests_.push_back(decode_request(partial_));
          partial_words_ = 0;
        }
      }
      return;
    }
    for (unsigned k = 0; k < len; k += 4) {
      uint32_t v = 0;
      bool ok;
      if (tx.is_write()) {
        std::memcpy(&v, data + k, 4);
        ok = write_word(tx.get_address() + k, v, delay);
      } else {
        ok = read_word(tx.get_address() + k, v);
        std::memcpy(data + k, &v, 4);
      }
      if (!ok) return tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    }
  }
}

unsigned int TfuTlm::transport_dbg(tlm::tlm_generic_payload& tx) {
  // Debug reads only (a debugger's view of the registers); writes have side effects and are refused.
  if (!tx.is_read() || tx.get_address() % 4 != 0) return 0;
  unsigned n = 0;
  for (; n + 4 <= tx.get_data_length(); n += 4) {
    uint32_t v = 0;
    if (!read_word(tx.get_address() + n, v)) break;
    std::memcpy(tx.get_data_ptr() + n, &v, 4);
  }
  return n;
}

bool TfuTlm::write_word(uint64_t address, uint32_t v, sc_core::sc_time& delay) {
  const Decoded d = decode_address(address);
  if (d.reg == nullptr || d.reg->access == BA::ReadOnly) return false;
  switch (d.reg->region) {
    case BR::Control:
      if (v & kControlClear) clear();
      if (v & kControlStart) start(delay);
      return true;
    case BR::TraceMode: trace_mode_ = v; return true;
    case BR::TextureCount: texture_count_ = v; return true;
    case BR::SamplerCount: sampler_count_ = v; return true;
    case BR::TexelBaseLo: texel_base_ = (texel_base_ & ~uint64_t{0xffffffff}) | v; return true;
    case BR::TexelBaseHi: texel_base_ = (texel_base_ & 0xffffffff) | uint64_t{v} << 32; return true;
    case BR::TextureDescriptors: texture_words_[size_t{d.index} * kTextureDescriptorWords + d.word] = v; return true;
    case BR::SamplerDescriptors: sampler_words_[size_t{d.index} * kSamplerDescriptorWords + d.word] = v; return true;
    case BR::RequestFifo:
      if (partial_words_ == 0 && requests_.size() >= kMaxBatchRequests) return false;  // full: the write is refused
      partial_[static_cast<size_t>(partial_words_++)] = v;
      if (partial_words_ == kRequestRecordWords) {
        requests_.push_back(decode_request(partial_));
        partial_words_ = 0;
      }
      return true;
    default: return false;
  }
}

bool TfuTlm::read_word(uint64_t address, uint32_t& v) const {
  const Decoded d = decode_address(address);
  if (d.reg == nullptr || d.reg->access == BA::WriteOnly) return false;
  switch (d.reg->region) {
    case BR::Id: v = kUnitId; return true;
    case BR::Status: v = status_; return true;
    case BR::TraceMode: v = trace_mode_; return true;
    case BR::TextureCount: v = texture_count_; return true;
    case BR::SamplerCount: v = sampler_count_; return true;
    case BR::TexelBaseLo: v = static_cast<uint32_t>(texel_base_); return true;
    case BR::TexelBaseHi: v = static_cast<uint32_t>(texel_base_ >> 32); return true;
    case BR::RequestCount: v = static_cast<uint32_t>(requests_.size()); return true;
    case BR::ResultCount: v = static_cast<uint32_t>(out_.pixels.size()); return true;
    case BR::CyclesLo: v = static_cast<uint32_t>(out_.cycles); return true;
    case BR::CyclesHi: v = static_cast<uint32_t>(out_.cycles >> 32); return true;
    case BR::TextureDescriptors: v = texture_words_[size_t{d.index} * kTextureDescriptorWords + d.word]; return true;
    case BR::SamplerDescriptors: v = sampler_words_[size_t{d.index} * kSamplerDescriptorWords + d.word]; return true;
    case BR::Results:
      if (d.index >= out_.pixels.size()) return false;  // beyond the last batch's results
      v = d.word == 0 ? std::bit_cast<uint32_t>(out_.pixels[d.index])
                      : static_cast<uint32_t>(out_.response_cycle[d.index]);
      return true;
    default: return false;
  }
}

void TfuTlm::clear() {
  requests_.clear();
  partial_words_ = 0;
  out_ = {};
  status_ = 0;
  error_.clear();
}

// The registers' frame: the bound descriptors decoded from their words, and a texel memory holding
// the bytes [lowest level address, end of the highest level) read from the platform at
// TEXEL_BASE + address, one cache line per transaction (the last one shorter).
Frame TfuTlm::fetch_frame() {
  if (texture_count_ > reg(BR::TextureDescriptors).count || sampler_count_ > reg(BR::SamplerDescriptors).count)
    throw InputError(fmt::format("TEXTURE_COUNT {} / SAMPLER_COUNT {} exceed the tables' 4096 / 256 descriptors",
                                 texture_count_, sampler_count_));
  Frame f;
  f.line_bytes = unit_.cache.line_bytes;
  for (uint32_t k = 0; k < texture_count_; ++k) {
    f.regs.textures.push_back(decode_texture_descriptor(std::span<const uint32_t, kTextureDescriptorWords>(
        texture_words_.data() + size_t{k} * kTextureDescriptorWords, kTextureDescriptorWords)));
    f.textures.push_back(FrameTexture{fmt::format("descriptor {}", k), {}, nullptr, -1});
  }
  for (uint32_t k = 0; k < sampler_count_; ++k)
    f.regs.samplers.push_back(decode_sampler_descriptor(std::span<const uint32_t, kSamplerDescriptorWords>(
        sampler_words_.data() + size_t{k} * kSamplerDescriptorWords, kSamplerDescriptorWords)));
  f.regs.validate();
  uint64_t lo = UINT64_MAX, hi = 0;
  for (size_t k = 0; k < f.regs.textures.size(); ++k) {
    const TextureDescriptor& t = f.regs.textures[k];
    for (int l = 0; l < t.levels; ++l) {
      const uint64_t a = t.level[static_cast<size_t>(l)].address;
      if (a < TextureMemory::kFirstAddress)
        throw InputError(fmt::format(
            "texture descriptor {} level {}: address 0x{:x} is below the texel memory's first address 0x{:x}", k, l, a,
            TextureMemory::kFirstAddress));
      lo = std::min(lo, a);
      hi = std::max(hi, a + t.level_bytes(l));
    }
  }
  if (hi == 0) return f;  // no texture bound: the unit refuses the requests (they name unbound descriptors)
  if (hi - TextureMemory::kFirstAddress > TextureMemory::kMaxBytes)
    throw InputError(fmt::format("texture descriptors reach 0x{:x}, beyond the texel memory's {} bytes", hi,
                                 TextureMemory::kMaxBytes));
  if (f.memory.allocate(hi - TextureMemory::kFirstAddress) != TextureMemory::kFirstAddress)
    throw CheckFailed("texel memory: the first allocation is not at its first address");
  std::vector<unsigned char> line(static_cast<size_t>(unit_.cache.line_bytes));
  for (uint64_t a = lo; a < hi; a += line.size()) {
    const auto n = static_cast<unsigned>(std::min<uint64_t>(line.size(), hi - a));
    tlm::tlm_generic_payload tx;
    tx.set_read();
    tx.set_address(texel_base_ + a);
    tx.set_data_ptr(line.data());
    tx.set_data_length(n);
    tx.set_streaming_width(n);
    tx.set_byte_enable_ptr(nullptr);
    tx.set_dmi_allowed(false);
    tx.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_core::sc_time d = sc_core::SC_ZERO_TIME;
    texel_port->b_transport(tx, d);
    ++texel_reads_;
    texel_read_delay_ += d;
    if (tx.is_response_error())
      throw InputError(fmt::format("texel memory read of {} bytes at bus address 0x{:x} (texel address 0x{:x}): {}", n,
                                   texel_base_ + a, a, tx.get_response_string()));
    // Whole texel words through the memory's word writer (RGBA8: 4 bytes), the tail byte by byte.
    unsigned i = 0;
    for (; i + 4 <= n; i += 4)
      f.memory.write_word(a + i, TexelFormat::RGBA8, Rgba8{line[i], line[i + 1], line[i + 2], line[i + 3]});
    for (; i < n; ++i) f.memory.write_word(a + i, TexelFormat::L8, Rgba8{line[i], 0, 0, 0});
  }
  return f;
}

void TfuTlm::start(sc_core::sc_time& delay) {
  out_ = {};
  error_.clear();
  status_ = 0;
  try {
    if (partial_words_ != 0)
      throw InputError(fmt::format("the request FIFO holds {} words of an unfinished record (a record is {} words)",
                                   partial_words_, kRequestRecordWords));
    if (trace_mode_ > static_cast<uint32_t>(TraceMode::Quad))
      throw InputError(fmt::format("TRACE_MODE {} is not 0 lod, 1 grad or 2 quad", trace_mode_));
    Trace trace;
    trace.mode = static_cast<TraceMode>(trace_mode_);
    trace.requests = std::move(requests_);
    requests_.clear();
    const Frame frame = fetch_frame();
    const auto t0 = std::chrono::steady_clock::now();
    out_ = rtl::run_unit(frame, trace, unit_, engine_, rtl::VcdOptions{});
    model_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The batch's time at the unit's clock, exactly: cycles x period in the kernel's resolution.
    delay += sc_core::sc_time::from_value(period_.value() * out_.cycles);
    status_ = kStatusDone;
  } catch (const InputError& e) {
    out_ = {};
    error_ = e.what();
    status_ = kStatusDone | kStatusError;
  }
}

}  // namespace tfu::sc
