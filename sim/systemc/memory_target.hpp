// MemoryTarget: a TLM-2.0 memory for example platforms and tests (docs/systemc.md): the bytes
// [base, base + size) behind a target socket, with a fixed latency annotated per access. No DMI,
// no byte enables (an access with them, or outside the bytes, answers TLM_ADDRESS_ERROR_RESPONSE).
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

namespace tfu::sc {

struct MemoryTarget : sc_core::sc_module {
  tlm_utils::simple_target_socket<MemoryTarget> socket;
  uint64_t base = 0;
  std::vector<unsigned char> bytes;
  sc_core::sc_time latency;

  MemoryTarget(const sc_core::sc_module_name& n, uint64_t base_address, std::vector<unsigned char> contents,
               sc_core::sc_time access)
      : sc_core::sc_module(n), socket("socket"), base(base_address), bytes(std::move(contents)), latency(access) {
    socket.register_b_transport(this, &MemoryTarget::b_transport);
  }
  void b_transport(tlm::tlm_generic_payload& tx, sc_core::sc_time& delay) {
    const uint64_t a = tx.get_address();
    const unsigned n = tx.get_data_length();
    if (a < base || a - base > bytes.size() || n > bytes.size() - (a - base) || tx.get_byte_enable_ptr() != nullptr)
      return tx.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    unsigned char* p = bytes.data() + (a - base);
    if (tx.is_read()) std::memcpy(tx.get_data_ptr(), p, n);
    if (tx.is_write()) std::memcpy(p, tx.get_data_ptr(), n);
    delay += latency;
    tx.set_response_status(tlm::TLM_OK_RESPONSE);
  }
};

}  // namespace tfu::sc
