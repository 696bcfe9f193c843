// Equivalence of the edge-preserving SystemVerilog (rtl/sv/edge/, Verilated) with the C++ model
// (cmodel/edge_filter, rtl/median_network), bit for bit, and co-simulation of a scene's request
// trace through the pipelined top (docs/sv-edge.md). Exhaustive where the input space allows it,
// otherwise >= 10^6 random vectors plus directed corners. Every mismatch is counted; the first few
// are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/direction_rom.hpp"
#include "cmodel/edge_filter.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"
#include "rtl/median_network.hpp"
#include "testbench/median_inputs.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/sv/tests/sv_texel.hpp"
#include "testbench/iterations.hpp"

#include "Vtfu_edge_dir_roms.h"
#include "Vtfu_edge_dir_select.h"
#include "Vtfu_edge_interp_top.h"
#include "Vtfu_edge_interp_top_l8.h"
#include "Vtfu_edge_lowpass_select.h"
#include "Vtfu_edge_merge.h"
#include "Vtfu_edge_rgb_to_y.h"
#include "Vtfu_median_network.h"
#include "verilated.h"

namespace {

namespace lj = tfu::lee_jen;
using tfu::Texel4;
using Texels = std::array<Texel4, lj::kTexels>;

constexpr uint64_t kSeed = 0xed9eULL;
constexpr int kRandomVectors = tfu::test::iterations(1'000'000);  // testbench/iterations.hpp
constexpr int kMaxReports = 8;
constexpr tfu::TexelFormat kFmt = tfu::TexelFormat::RGBA8;

struct Mismatches {
  int count = 0;
  void add(const std::string& what) {
    if (++count <= kMaxReports) ADD_FAILURE() << what;
  }
};

using tfu::svtest::pack;
using tfu::svtest::str;
using tfu::svtest::unpack;
std::string str(const Texels& c) {
  std::string s;
  for (const Texel4& t : c) s += str(t);
  return s;
}

// Bits [lsb, lsb + width) of a wide Verilator signal (width <= 32).
template <std::size_t N>
uint32_t field(const VlWide<N>& w, int lsb, int width) {
  uint64_t v = w[static_cast<std::size_t>(lsb / 32)];
  if (static_cast<std::size_t>(lsb / 32 + 1) < N) v |= uint64_t{w[static_cast<std::size_t>(lsb / 32 + 1)]} << 32;
  return static_cast<uint32_t>((v >> (lsb % 32)) & ((uint64_t{1} << width) - 1));
}
template <std::size_t N>
void put(VlWide<N>& w, int lsb, int width, uint32_t value) {
  for (int b = 0; b < width; ++b) {
    const auto word = static_cast<std::size_t>((lsb + b) / 32);
    const uint32_t bit = 1u << ((lsb + b) % 32);
    w[word] = ((value >> b) & 1u) ? (w[word] | bit) : (w[word] & ~bit);
  }
}

bool has(lj::TexelMask m, int n) { return ((m >> (n - 1)) & 1u) != 0; }
const Texel4& at(const Texels& c, int n) { return c[static_cast<size_t>(n - 1)]; }

// ------------------------------------------------------------------ stimulus
// Texel patterns: uniform random words, a straight two-colour edge through the 4x4 grid, a random
// two-colour palette, near-constant (small dP: many cost ties), all equal.
Texels random_texels(std::mt19937_64& rng) {
  Texels c{};
  const auto word = [&rng] { return unpack(static_cast<uint32_t>(rng())); };
  switch (rng() % 5) {
    case 0:
      for (Texel4& t : c) t = word();
      break;
    case 1: {
      const Texel4 a = word(), b = word();
      const double ang = static_cast<double>(rng() % 3600) * 3.14159265358979 / 1800.0;
      const double off = static_cast<double>(rng() % 2001) / 1000.0 - 0.5;
      for (int n = 1; n <= lj::kTexels; ++n) {
        const lj::TexelPos p = lj::texel_pos(n);
        c[static_cast<size_t>(n - 1)] = std::cos(ang) * (p.x - 0.5) + std::sin(ang) * (p.y - 0.5) < off - 0.5 ? a : b;
      }
      break;
    }
    case 2: {
      const Texel4 a = word(), b = word();
      for (Texel4& t : c) t = (rng() & 1) ? a : b;
      break;
    }
    case 3: {
      const Texel4 base = word();
      for (Texel4& t : c)
        for (size_t ch = 0; ch < 4; ++ch) t[ch] = std::clamp(base[ch] + static_cast<int32_t>(rng() % 7) - 3, 0, 255);
      break;
    }
    default: {
      const Texel4 a = word();
      c.fill(a);
    }
  }
  return c;
}

uint32_t random_fraction(std::mt19937_64& rng) {
  static constexpr std::array<uint32_t, 8> kCorner{0, 1, 15, 16, 127, 128, 240, 255};
  return (rng() % 8 == 0) ? kCorner[rng() % kCorner.size()] : static_cast<uint32_t>(rng() & 255);
}

const lj::KernelShape& random_shape(std::mt19937_64& rng) {
  const auto& shapes = lj::kernel_shapes();
  return shapes[rng() % shapes.size()];
}

// ------------------------------------------------------------------ direction ROMs (every address)
TEST(SvEdgeRom, EveryAddressOfEveryDirectionRomMatchesTheModel) {
  VerilatedContext ctx;
  Vtfu_edge_dir_roms m{&ctx};
  Mismatches bad;
  for (uint32_t fv = 0; fv < 16; ++fv)
    for (uint32_t fu = 0; fu < 16; ++fu) {
      m.fu = static_cast<uint8_t>(fu);
      m.fv = static_cast<uint8_t>(fv);
      m.eval();
      for (int i = 0; i < lj::kDirections; ++i) {
        const uint32_t want = lj::direction_weight_rom(i)[(fv << 4) | fu];
        const uint32_t got = field(m.w, 8 * i, 8);
        if (got != want) bad.add(fmt::format("direction {} fu4 {} fv4 {}: sv {} c++ {}", i, fu, fv, got, want));
      }
    }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ RGB -> Y (exhaustive)
TEST(SvEdgeLuma, RgbToYEveryRgbTriple) {
  VerilatedContext ctx;
  Vtfu_edge_rgb_to_y m{&ctx};
  Mismatches bad;
  for (uint32_t rgb = 0; rgb < (1u << 24); ++rgb) {
    const Texel4 c{static_cast<int32_t>(rgb & 255), static_cast<int32_t>((rgb >> 8) & 255), static_cast<int32_t>(rgb >> 16), 0};
    m.r = static_cast<uint8_t>(c[0]);
    m.g = static_cast<uint8_t>(c[1]);
    m.b = static_cast<uint8_t>(c[2]);
    m.eval();
    const auto want = static_cast<uint32_t>(lj::edge_luma(c, kFmt));
    if (m.y != want) bad.add(fmt::format("rgb {}: sv {} c++ {}", str(c), m.y, want));
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ median network
using tfu::testing::median_inputs_in_shape;
using tfu::testing::plain_median;

// Runs the SV network on keys (luma_keys layout) and checks every available texel's median against
// the plain median of its inputs (testbench/median_inputs.hpp), the behavioural model
// (lee_jen::median_low_pass) and the C++ netlist (rtl::median_network_eval).
void check_median(Vtfu_median_network& m, const lj::LumaKeys& key, lj::TexelMask shape, Mismatches& bad,
                  const char* what) {
  for (int n = 1; n <= lj::kTexels; ++n) put(m.key, 16 * (n - 1), 16, static_cast<uint32_t>(key[static_cast<size_t>(n)]));
  m.shape = shape;
  m.eval();
  const lj::LowIndex model = lj::median_low_pass(key, shape);
  const lj::LowIndex net = tfu::rtl::median_network_eval(key, shape);
  for (int n = 1; n <= lj::kTexels; ++n) {
    if (!has(shape, n)) continue;
    const auto got = static_cast<int>((m.low >> (4 * (n - 1))) & 15u);
    const int w = plain_median(key, median_inputs_in_shape(n, shape));
    if (got != w || net[static_cast<size_t>(n)] != w || model[static_cast<size_t>(n)] != w) {
      std::string keys;
      for (int k = 1; k <= lj::kTexels; ++k) keys += fmt::format(" {}", key[static_cast<size_t>(k)]);
      bad.add(fmt::format("{} shape {:#05x} C{}: sv {} netlist {} model {} plain median {}; keys{}", what, shape, n, got,
                          net[static_cast<size_t>(n)], model[static_cast<size_t>(n)], w, keys));
    }
  }
}

lj::LumaKeys keys_from_y(const std::array<int32_t, lj::kTexels + 1>& y, lj::TexelMask shape) {
  lj::LumaKeys k{};
  for (int n = 1; n <= lj::kTexels; ++n) k[static_cast<size_t>(n)] = has(shape, n) ? y[static_cast<size_t>(n)] * 16 + n : 0;
  return k;
}

TEST(SvEdgeMedian, EveryInputOrderingOfEveryMedianInEveryShape) {
  ASSERT_EQ(tfu::rtl::median_netlist().cells.size(), 40u);
  VerilatedContext ctx;
  Vtfu_median_network m{&ctx};
  std::mt19937 rng(7);
  Mismatches bad;
  size_t cases = 0;
  for (const lj::KernelShape& shape : lj::kernel_shapes())
    for (int n = 1; n <= lj::kTexels; ++n) {
      if (!has(shape.mask, n)) continue;
      const std::vector<int> in = median_inputs_in_shape(n, shape.mask);
      std::vector<int> rank(in.size());
      std::iota(rank.begin(), rank.end(), 0);
      do {
        for (int rep = 0; rep < 3; ++rep) {
          std::array<int32_t, lj::kTexels + 1> y{};
          for (int k = 1; k <= lj::kTexels; ++k) y[static_cast<size_t>(k)] = static_cast<int32_t>(rng() % 4081);
          // The median's own inputs take the ordering `rank` (rep 2: all equal, the texel number decides).
          for (size_t k = 0; k < in.size(); ++k) y[static_cast<size_t>(in[k])] = rep == 2 ? 1000 : 500 + 700 * rank[k] + rep;
          check_median(m, keys_from_y(y, shape.mask), shape.mask, bad, shape.name().c_str());
          ++cases;
        }
      } while (std::next_permutation(rank.begin(), rank.end()));
    }
  EXPECT_EQ(bad.count, 0);
  EXPECT_EQ(cases, 3u * ((8 * 6 + 4 * 120) + 4 * (6 * 6 + 4 * 120) + 4 * (4 * 6 + 3 * 120 + 6)));  // cross, 4 T, 4 L
}

TEST(SvEdgeMedian, RandomKeyVectors) {
  VerilatedContext ctx;
  Vtfu_median_network m{&ctx};
  std::mt19937_64 rng(kSeed);
  Mismatches bad;
  for (int i = 0; i < kRandomVectors; ++i) {
    const lj::KernelShape& shape = random_shape(rng);
    // Full range, or a narrow one (many equal Y: the texel number decides), or the extremes.
    const uint32_t range = (i % 3 == 0) ? 4081 : (i % 3 == 1 ? 4 : 2);
    std::array<int32_t, lj::kTexels + 1> y{};
    for (int k = 1; k <= lj::kTexels; ++k) {
      const auto v = static_cast<int32_t>(rng() % range);
      y[static_cast<size_t>(k)] = range == 2 ? v * 4080 : v;
    }
    check_median(m, keys_from_y(y, shape.mask), shape.mask, bad, shape.name().c_str());
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ low-pass texel select
TEST(SvEdgeLowpass, SelectsTheMedianTexelOfEveryAvailableTexel) {
  VerilatedContext ctx;
  Vtfu_edge_lowpass_select m{&ctx};
  std::mt19937_64 rng(kSeed + 1);
  Mismatches bad;
  for (int i = 0; i < kRandomVectors / 4; ++i) {
    const lj::KernelShape& shape = random_shape(rng);
    const Texels c = random_texels(rng);
    const lj::LowIndex low = lj::median_low_pass(lj::luma_keys(c, shape.mask, kFmt), shape.mask);
    uint64_t lowbits = 0;
    for (int n = 1; n <= lj::kTexels; ++n) {
      m.texels[static_cast<size_t>(n - 1)] = pack(at(c, n));
      lowbits |= uint64_t{static_cast<uint32_t>(low[static_cast<size_t>(n)]) & 15u} << (4 * (n - 1));
    }
    m.low = lowbits;
    m.eval();
    for (int n = 1; n <= lj::kTexels; ++n) {
      if (!has(shape.mask, n)) continue;
      const uint32_t want = pack(at(c, low[static_cast<size_t>(n)]));
      const uint32_t got = m.lowtex[static_cast<size_t>(n - 1)];
      if (got != want) bad.add(fmt::format("{} C{}_low (= C{}): sv {:#010x} c++ {:#010x}", shape.name(), n, low[static_cast<size_t>(n)], got, want));
    }
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ direction select
// The SV block gets the low-pass texels directly; the model gets them as c with low[n] = n.
struct DirSelectCheck {
  Vtfu_edge_dir_select& m;
  Mismatches& bad;
  void operator()(const Texels& lowtex, lj::TexelMask shape, uint32_t fu, uint32_t fv) {
    for (int n = 1; n <= lj::kTexels; ++n) put(m.lowrgb, 24 * (n - 1), 24, pack(at(lowtex, n)) & 0xFFFFFFu);
    m.shape = shape;
    m.fu4 = static_cast<uint8_t>(fu >> 4);
    m.fv4 = static_cast<uint8_t>(fv >> 4);
    m.eval();
    lj::LowIndex identity{};
    for (int n = 1; n <= lj::kTexels; ++n) identity[static_cast<size_t>(n)] = n;
    const lj::EdgeDecision want = lj::select_direction(lowtex, identity, shape, fu, fv, kFmt);
    if (static_cast<int>(m.dir) != want.direction || m.cost != want.cost)
      bad.add(fmt::format("shape {:#05x} fu {} fv {} texels {}: sv dir {} cost {}, c++ dir {} cost {}", shape, fu, fv,
                          str(lowtex), m.dir, m.cost, want.direction, want.cost));
  }
};

TEST(SvEdgeDirSelect, RandomVectors) {
  VerilatedContext ctx;
  Vtfu_edge_dir_select m{&ctx};
  std::mt19937_64 rng(kSeed + 2);
  Mismatches bad;
  DirSelectCheck check{m, bad};
  for (int i = 0; i < kRandomVectors; ++i) {
    // Mostly the nine kernel shapes; every fourth vector an arbitrary availability mask.
    const auto shape = (i % 4 == 3) ? static_cast<lj::TexelMask>(rng() & lj::kAllTexels) : random_shape(rng).mask;
    check(random_texels(rng), shape, random_fraction(rng), random_fraction(rng));
  }
  EXPECT_EQ(bad.count, 0);
}

TEST(SvEdgeDirSelect, CornersEveryShapeEveryRomAddress) {
  VerilatedContext ctx;
  Vtfu_edge_dir_select m{&ctx};
  std::mt19937_64 rng(kSeed + 3);
  Mismatches bad;
  DirSelectCheck check{m, bad};
  const Texel4 black{0, 0, 0, 0}, white{255, 255, 255, 255};
  for (const lj::KernelShape& shape : lj::kernel_shapes())
    for (uint32_t a = 0; a < 256; ++a) {
      const uint32_t fu = (a & 15) << 4 | (a & 1 ? 15 : 0), fv = (a >> 4) << 4 | (a & 2 ? 15 : 0);
      Texels c{};
      c.fill(black);  // all equal: every cost 0, the lowest usable index wins
      check(c, shape.mask, fu, fv);
      c.fill(white);
      check(c, shape.mask, fu, fv);
      for (int n = 1; n <= lj::kTexels; ++n) c[static_cast<size_t>(n - 1)] = (n & 1) ? black : white;  // maximal dP
      check(c, shape.mask, fu, fv);
      for (int n = 1; n <= lj::kTexels; ++n) c[static_cast<size_t>(n - 1)] = lj::texel_pos(n).x < 1 ? black : white;
      check(c, shape.mask, fu, fv);
      for (int n = 1; n <= lj::kTexels; ++n) c[static_cast<size_t>(n - 1)] = lj::texel_pos(n).y < 1 ? white : black;
      check(c, shape.mask, fu, fv);
      check(random_texels(rng), shape.mask, fu, fv);
    }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ merge (Eq. 3, 5, 6)
struct MergeCheck {
  Vtfu_edge_merge& m;
  Mismatches& bad;
  void operator()(const Texels& c, const lj::LowIndex& low, int dir, uint32_t fu, uint32_t fv) {
    for (int n = 1; n <= lj::kTexels; ++n) m.lowtex[static_cast<size_t>(n - 1)] = pack(at(c, low[static_cast<size_t>(n)]));
    m.centre[0] = pack(at(c, 4));
    m.centre[1] = pack(at(c, 5));
    m.centre[2] = pack(at(c, 8));
    m.centre[3] = pack(at(c, 9));
    m.dir = static_cast<uint8_t>(dir);
    m.fu = static_cast<uint8_t>(fu);
    m.fv = static_cast<uint8_t>(fv);
    m.eval();
    const Texel4 want = lj::edge_merge(c, low, dir, fu, fv, kFmt);
    if (m.c != pack(want)) {
      std::string lows;
      for (int n = 1; n <= lj::kTexels; ++n) lows += fmt::format(" {}", low[static_cast<size_t>(n)]);
      bad.add(fmt::format("dir {} fu {} fv {} texels {} low{}: sv {} c++ {}", dir, fu, fv, str(c), lows,
                          str(unpack(m.c)), str(want)));
    }
  }
};

TEST(SvEdgeMerge, RandomVectors) {
  VerilatedContext ctx;
  Vtfu_edge_merge m{&ctx};
  std::mt19937_64 rng(kSeed + 4);
  Mismatches bad;
  MergeCheck check{m, bad};
  for (int i = 0; i < kRandomVectors; ++i) {
    lj::LowIndex low{};
    for (int n = 1; n <= lj::kTexels; ++n) low[static_cast<size_t>(n)] = 1 + static_cast<int>(rng() % lj::kTexels);
    check(random_texels(rng), low, static_cast<int>(rng() % lj::kDirections), random_fraction(rng), random_fraction(rng));
  }
  EXPECT_EQ(bad.count, 0);
}

TEST(SvEdgeMerge, CornersEveryDirectionExtremeHighFrequency) {
  VerilatedContext ctx;
  Vtfu_edge_merge m{&ctx};
  Mismatches bad;
  MergeCheck check{m, bad};
  const Texel4 black{0, 0, 0, 0}, white{255, 255, 255, 255};
  static constexpr std::array<uint32_t, 7> kF{0, 1, 127, 128, 129, 254, 255};
  for (int dir = 0; dir < lj::kDirections; ++dir)
    for (const uint32_t fu : kF)
      for (const uint32_t fv : kF)
        for (int pattern = 0; pattern < 16; ++pattern) {
          // Centre texels black/white by the pattern bits, every low-pass texel the opposite colour
          // (H_n = +-255: the high-frequency sum at its extremes), plus all-equal texels.
          Texels c{};
          lj::LowIndex low{};
          for (int n = 1; n <= lj::kTexels; ++n) {
            c[static_cast<size_t>(n - 1)] = (n & 1) ? black : white;
            low[static_cast<size_t>(n)] = n;
          }
          for (size_t k = 0; k < 4; ++k) {
            const bool hi = (pattern >> k) & 1;
            const int n = lj::kCentreSquare[k];
            c[static_cast<size_t>(n - 1)] = hi ? white : black;
            low[static_cast<size_t>(n)] = hi ? 1 : 2;  // C1 black, C2 white
          }
          check(c, low, dir, fu, fv);
          c.fill(pattern & 1 ? white : black);
          check(c, low, dir, fu, fv);
        }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ pipelined top
// The top at each offered pipeline depth (parameter CUTS of tfu_edge_interp_top; docs/sv-edge.md):
// latency = clocks from a request at the inputs to its result.

struct Request {
  Texels texels{};  // the model's view: zeros where the shape has no texel
  lj::TexelMask mask = lj::kAllTexels;
  uint32_t fu = 0, fv = 0;
};

// Drives the top one request (or bubble) per clock and checks each result against the model's
// value at the expected clock: out_valid must follow in_valid exactly kLatency clocks later.
template <class Model, int Latency>
class TopBench {
 public:
  static constexpr int kLatency = Latency;
  TopBench() : m_(&ctx_) {
    m_.clk = 0;
    m_.rst_n = 0;
    m_.in_valid = 0;
    m_.eval();
    for (int i = 0; i < 3; ++i) clock();
    m_.rst_n = 1;
    m_.eval();
    if (m_.out_valid) bad.add("out_valid set after reset");
  }
  // `poison`: texels missing from the shape are driven with this word (the SV must not read them).
  void push(const Request* r, uint32_t poison, tfu::Rgba8 want) {
    m_.in_valid = r != nullptr;
    if (r) {
      for (int n = 1; n <= lj::kTexels; ++n)
        m_.texels[static_cast<size_t>(n - 1)] = has(r->mask, n) ? pack(at(r->texels, n)) : poison;
      m_.shape = r->mask;
      m_.fu = static_cast<uint8_t>(r->fu);
      m_.fv = static_cast<uint8_t>(r->fv);
    }
    inflight_.push_back({r != nullptr, want, r ? *r : Request{}});
    clock();
    // After this edge the result of the request pushed kLatency - 1 edges earlier is on the outputs.
    if (inflight_.size() == static_cast<size_t>(kLatency)) {
      const Expect e = inflight_.front();
      inflight_.pop_front();
      if (static_cast<bool>(m_.out_valid) != e.valid) {
        bad.add(fmt::format("clock {}: out_valid {} expected {}", clocks_, m_.out_valid, e.valid));
      } else if (e.valid) {
        ++results;
        const tfu::Rgba8 got{static_cast<uint8_t>(m_.c & 255), static_cast<uint8_t>((m_.c >> 8) & 255),
                             static_cast<uint8_t>((m_.c >> 16) & 255), static_cast<uint8_t>(m_.c >> 24)};
        if (!(got == e.want))
          bad.add(fmt::format("clock {}: shape {:#05x} fu {} fv {} texels {}: sv ({},{},{},{}) c++ ({},{},{},{})",
                              clocks_, e.req.mask, e.req.fu, e.req.fv, str(e.req.texels), got.r, got.g, got.b, got.a,
                              e.want.r, e.want.g, e.want.b, e.want.a));
      }
    }
  }
  void push(const Request& r, uint32_t poison = 0) {
    push(&r, poison, tfu::encode_texel(lj::edge_preserving_interpolate(r.texels, r.mask, r.fu, r.fv, kFmt), kFmt));
  }
  void bubble() { push(nullptr, 0, {}); }
  void drain() {
    for (int i = 0; i < kLatency; ++i) bubble();
  }
  uint64_t clocks() const { return clocks_; }

  Mismatches bad;
  uint64_t results = 0;

 private:
  struct Expect {
    bool valid;
    tfu::Rgba8 want;
    Request req;
  };
  void clock() {
    m_.clk = 1;
    m_.eval();
    m_.clk = 0;
    m_.eval();
    ++clocks_;
  }
  VerilatedContext ctx_;
  Model m_;
  std::deque<Expect> inflight_;
  uint64_t clocks_ = 0;
};

Request make_request(const Texels& c, lj::TexelMask mask, uint32_t fu, uint32_t fv) {
  Request r{c, mask, fu, fv};
  for (int n = 1; n <= lj::kTexels; ++n)
    if (!has(mask, n)) r.texels[static_cast<size_t>(n - 1)] = {0, 0, 0, 0};
  return r;
}

template <class Bench>
void latency_and_one_result_per_clock() {
  Bench tb;
  std::mt19937_64 rng(kSeed + 5);
  // One isolated request: its result appears exactly Latency clocks later (checked by the bench:
  // out_valid is compared with in_valid of kLatency clocks before on every clock).
  tb.push(make_request(random_texels(rng), lj::kAllTexels, 77, 200));
  for (int i = 0; i < Bench::kLatency + 2; ++i) tb.bubble();
  EXPECT_EQ(tb.results, 1u);
  // Back-to-back: N requests on N consecutive clocks give N results on N consecutive clocks.
  const uint64_t before = tb.clocks();
  constexpr int kN = 1000;
  for (int i = 0; i < kN; ++i) tb.push(make_request(random_texels(rng), random_shape(rng).mask, random_fraction(rng), random_fraction(rng)));
  tb.drain();
  EXPECT_EQ(tb.results, 1u + kN);
  EXPECT_EQ(tb.clocks() - before, static_cast<uint64_t>(kN + Bench::kLatency));
  EXPECT_EQ(tb.bad.count, 0);
}

template <class Bench>
void random_vectors_with_bubbles() {
  Bench tb;
  std::mt19937_64 rng(kSeed + 6);
  int pushed = 0;
  while (pushed < kRandomVectors) {
    if (rng() % 16 == 0) {
      tb.bubble();
      continue;
    }
    const lj::KernelShape& shape = random_shape(rng);
    tb.push(make_request(random_texels(rng), shape.mask, random_fraction(rng), random_fraction(rng)), static_cast<uint32_t>(rng()));
    ++pushed;
  }
  tb.drain();
  EXPECT_EQ(tb.results, static_cast<uint64_t>(pushed));
  EXPECT_EQ(tb.bad.count, 0);
}

template <class Bench>
void corners_every_shape() {
  Bench tb;
  std::mt19937_64 rng(kSeed + 7);
  const Texel4 black{0, 0, 0, 0}, white{255, 255, 255, 255};
  static constexpr std::array<uint32_t, 6> kF{0, 1, 127, 128, 254, 255};
  uint64_t n_req = 0;
  for (const lj::KernelShape& shape : lj::kernel_shapes())
    for (const uint32_t fu : kF)
      for (const uint32_t fv : kF) {
        Texels c{};
        for (const Texel4 fill : {black, white, Texel4{255, 0, 0, 255}, Texel4{0, 0, 255, 0}}) {
          c.fill(fill);  // all-equal texels: the result is the texel
          tb.push(make_request(c, shape.mask, fu, fv), 0xFFFFFFFFu);
          ++n_req;
        }
        for (int pat = 0; pat < 8; ++pat) {  // checkerboards, stripes, single outliers at 0 / 255
          for (int n = 1; n <= lj::kTexels; ++n) {
            const lj::TexelPos p = lj::texel_pos(n);
            const bool b = pat == 0   ? ((p.x + p.y) & 1)
                           : pat == 1 ? p.x < 1
                           : pat == 2 ? p.y < 1
                           : pat == 3 ? p.x + p.y < 1
                           : pat == 4 ? p.x - p.y < 0
                           : pat == 5 ? n == 4
                           : pat == 6 ? n == 9
                                      : (rng() & 1);
            c[static_cast<size_t>(n - 1)] = b ? white : black;
          }
          tb.push(make_request(c, shape.mask, fu, fv), 0x12345678u);
          ++n_req;
        }
      }
  tb.drain();
  EXPECT_EQ(tb.results, n_req);
  EXPECT_EQ(tb.bad.count, 0);
}

using Top3 = TopBench<Vtfu_edge_interp_top, 3>;     // default CUTS: Lee & Jen's three stages
using Top8 = TopBench<Vtfu_edge_interp_top_l8, 8>;  // CUTS 8'b1101_1111: 101.2 MHz in OSU 0.35 um

TEST(SvEdgeTop, LatencyIsThreeClocksAndOneResultPerClock) { latency_and_one_result_per_clock<Top3>(); }
TEST(SvEdgeTop, RandomVectorsWithBubbles) { random_vectors_with_bubbles<Top3>(); }
TEST(SvEdgeTop, CornersEveryShape) { corners_every_shape<Top3>(); }
TEST(SvEdgeTopL8, LatencyIsEightClocksAndOneResultPerClock) { latency_and_one_result_per_clock<Top8>(); }
TEST(SvEdgeTopL8, RandomVectorsWithBubbles) { random_vectors_with_bubbles<Top8>(); }
TEST(SvEdgeTopL8, CornersEveryShape) { corners_every_shape<Top8>(); }

// ------------------------------------------------------------------ co-simulation of a scene trace
// The EDGE_PRESERVING (no MIP: level 0) request trace of the scene "text_quad" through the
// pipelined top gives the golden sampler's pixels, for the cross kernel and for the T/L kernels of
// 4x4 and 8x8 cache blocks.
TEST(SvEdgeCosim, TextQuadSceneTraceMatchesTheGoldenSamplerAndTheCycleModel) {
  tfu::Scene scene = tfu::load_scene("text_quad");
  scene.width = 128;
  scene.height = 96;
  tfu::RenderOptions o;
  o.trace = true;
  o.threads = 1;
  const tfu::Trace trace = tfu::render_scene(scene, o).trace;
  ASSERT_GT(trace.requests.size(), 1000u);
  const tfu::Mesh& mesh = scene.meshes.front();
  ASSERT_NE(mesh.stages[0].texture->format, tfu::TexelFormat::VS16X2);  // the SV is RGBA8 only
  const std::vector<int32_t> lambdas =
      tfu::trace_lambdas(trace, mesh.stages[0].texture->width(), mesh.stages[0].texture->height());
  for (const int block : {0, 4, 8}) {  // 0: cross
    tfu::SamplerDescriptor cfg = mesh.stages[0].sampler;
    cfg.mode = {tfu::BaseFilter::EdgePreserving, tfu::MipMode::None};
    cfg.edge_shape = block ? tfu::EdgeShape::Static : tfu::EdgeShape::Cross;
    auto tex = std::make_shared<tfu::Texture>(*mesh.stages[0].texture);
    tex->tile_bytes = block ? block * block * 4 : 64;  // static shapes follow the texture's tiles
    const tfu::Sampler smp(*tex, cfg);
    Top3 tb;
    Top8 tb8;  // the same trace through the latency-8 top
    std::set<lj::TexelMask> shapes;
    for (size_t i = 0; i < trace.requests.size(); ++i) {
      const tfu::TraceRequest& q = trace.requests[i];
      const tfu::EdgeFootprint fp = smp.edge_footprint(0, q.s, q.t);
      shapes.insert(fp.mask);
      const Request r{fp.texels, fp.mask, fp.fu, fp.fv};
      const tfu::Rgba8 want = smp.sample(q.s, q.t, lambdas[i]);
      tb.push(&r, 0xA5A5A5A5u, want);
      tb8.push(&r, 0xA5A5A5A5u, want);
    }
    tb.drain();
    tb8.drain();
    // The C++ cycle model on the same trace and kernel-shape policy: its pixels equal the golden
    // sampler's, which the Verilated top's equal, so the three models agree request by request.
    tfu::rtl::UnitConfig ucfg;
    ucfg.cache.line_bytes = tex->tile_bytes;
    tfu::FrameBuilder fb(ucfg.cache.line_bytes);
    fb.add_texture(tex, {"text_quad", {}});
    fb.add_sampler(cfg);
    tfu::Trace bound = trace;
    for (tfu::TraceRequest& q : bound.requests) q.texture = q.sampler = 0;
    const tfu::Frame frame = fb.finish();
    const tfu::rtl::UnitOutput unit = tfu::rtl::run_unit(frame, bound, ucfg);
    ASSERT_EQ(unit.pixels.size(), trace.requests.size());
    size_t unit_bad = 0;
    for (size_t i = 0; i < trace.requests.size(); ++i)
      unit_bad += unit.pixels[i] != smp.sample(trace.requests[i].s, trace.requests[i].t, lambdas[i]);
    EXPECT_EQ(unit_bad, 0u) << "cycle model vs golden, block " << block;
    fmt::print("text_quad 128x96, {}: {} requests, {} kernel shapes\n", block ? fmt::format("cache block {}", block) : "cross",
               trace.requests.size(), shapes.size());
    EXPECT_EQ(tb.results, trace.requests.size()) << "block " << block;
    EXPECT_EQ(tb.bad.count, 0) << "block " << block;
    EXPECT_EQ(tb8.results, trace.requests.size()) << "latency 8, block " << block;
    EXPECT_EQ(tb8.bad.count, 0) << "latency 8, block " << block;
    if (block) {
      EXPECT_GE(shapes.size(), 5u) << "B = " << block << ": the trace should reach T and L kernels";
    } else {
      EXPECT_EQ(shapes.size(), 1u);
    }
  }
}

}  // namespace
