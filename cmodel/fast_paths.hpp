// The process-wide off switch for the speed-only fast paths (as Mesa's GALLIVM_PERF=no_aos_sampling).
// With fast paths off, a Sampler built afterwards dispatches to the plain datapath of sampler.cpp
// (sample_plain, batch_plain, aniso_plain) instead of sampler_fast.cpp; results are identical
// bit for bit either way (Properties.FastPathsEqualPlainPath, BatchEqualsSample, and the
// PlainPaths tests that render with the switch on and off). The golden compare (rtl::golden_outputs)
// reads the switch at each call: off, it compares against the plain golden datapath.
// The default is read once from the environment: TFU_PLAIN=1 turns the fast paths off. The CLI's
// `--plain` (sample, render, sim, sweep) calls set_fast_paths(false) before any Sampler is built.
#pragma once

namespace tfu {

bool fast_paths_enabled();
void set_fast_paths(bool enabled);

}  // namespace tfu
