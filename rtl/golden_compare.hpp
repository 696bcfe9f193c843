// The cycle model against the golden model, request by request: the one place both `tfu sim` and
// the scene simulation compare (and the tests). Includes the golden model (cmodel/golden_unit.hpp),
// which no block of the unit does.
#pragma once

#include <string>
#include <vector>

#include "cmodel/golden_unit.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu::rtl {

// The golden model's value of every request of a run: its LOD unit (GoldenUnit::lod: lambda, and
// for anisotropic samplers N and the major axis) and sampler on the same requests (cache-aware
// edge-preserving requests with the shapes the run chose for every probe and level). Follows the
// fast-path switch at the call (cmodel/fast_paths.hpp): on, Sampler::sample (the fast paths); off
// (TFU_PLAIN=1, --plain), the plain datapath (Sampler::sample_channels, encoded) even of a sampler
// built while the switch was on.
std::vector<Rgba8> golden_outputs(const GoldenUnit& golden, const Trace& trace, const UnitOutput& out);
// Empty when every output equals the golden model's, else one line naming the first request that
// differs, both values and the cycle (`where` prefixes it, e.g. "unit 2"). `first`: the index of
// the trace's first request in the unit's requests (a chunk of a stream: rtl/tfu_unit.hpp).
std::string first_mismatch(const Trace& trace, const std::vector<Rgba8>& want, const UnitOutput& out, const std::string& where = {},
                           size_t first = 0);

}  // namespace tfu::rtl
