// Fuzz target, spec bounds (docs/fuzzing.md): a texture, a sampler and up to 64 requests drawn from
// the input (testbench/spec_bounds_case.hpp: NEAREST / LINEAR, plain and MIP-mapped, every wrap,
// bias within maxSamplerLodBias, LOD clamps, explicit / gradient / quad LOD, coordinates from the
// ordinary to 2^29 texels and any bit pattern), each golden-model result checked against the
// Vulkan spec's interval (testbench/spec_bounds.hpp). A result outside it aborts with the request.
// Requests outside the verifier's domain (non-finite values) still run through the golden model.
#include <cstdio>
#include <cstdlib>

#include "cmodel/error.hpp"
#include "testbench/fuzz/fuzz_input.hpp"
#include "testbench/spec_bounds_case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 2048) return 0;
  tfu::fuzz::ByteReader in(data, size);
  tfu::spec::CaseResult r;
  try {
    r = tfu::spec::run_case(in);
  } catch (const tfu::InputError&) {
    return 0;  // a configuration the model refuses
  }
  if (r.outside != 0) {
    std::fprintf(stderr, "outside the Vulkan spec's bounds: %s\n", r.first.c_str());
    std::abort();
  }
  return 0;
}
