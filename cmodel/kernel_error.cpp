#include "cmodel/kernel_error.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "cmodel/error.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/unorm.hpp"

namespace tfu {

void KernelErrorSpec::validate() const {
  FilterKernel::by_name(kernel);  // throws on unknown names
  TileRomSpec{samples, bits, sample_pos, RomRounding::Nearest}.validate();
  if (dims < 1 || dims > 3) throw InputError("--dims must be 1, 2 or 3, got " + std::to_string(dims));
  if (locations < 0 || locations > 4096)
    throw InputError("--locations must be in [1, 4096] (0 = default), got " + std::to_string(locations));
  checked_thread_count("--threads", threads, true);
}

namespace {

// Per-axis lookup: for location index i along one axis, the entries of every tile that the
// reconstruction reads and their blend factors, plus the exact 1D kernel value per tap.
struct AxisTap {
  int k0, k1;       // ROM entries (global index over the packed tiles: tile * n + k)
  double a;         // blend factor towards k1 (0 for nearest)
};

struct Axis {
  int taps = 0;
  int n = 0;                           // entries per tile
  std::vector<double> sample;          // taps * n : h at every ROM sample position (signed)
  std::vector<double> exact;           // locations * taps
  std::vector<AxisTap> lookup;         // locations * taps
};

Axis build_axis(const FilterKernel& h, const KernelErrorSpec& s) {
  Axis ax;
  ax.taps = 2 * ((h.width() + 1) / 2);
  const TileRomSpec rs{s.samples, s.bits, s.sample_pos, RomRounding::Nearest};
  ax.n = rs.entries();
  const int T = ax.taps, n = ax.n, R = s.samples;
  // Tile index j = T/2 - m holds tap m; store by tap t (m = 1 - T/2 + t), tile j = T - 1 - t.
  ax.sample.resize(static_cast<size_t>(T) * n);
  for (int t = 0; t < T; ++t) {
    const int m = 1 - T / 2 + t;
    for (int k = 0; k < n; ++k) ax.sample[static_cast<size_t>(t) * n + k] = h(rs.position(k) - m);
  }
  const int N = s.effective_locations();
  ax.exact.resize(static_cast<size_t>(N) * T);
  ax.lookup.resize(static_cast<size_t>(N) * T);
  for (int i = 0; i < N; ++i) {
    const double f = s.grid == LocationGrid::Corner ? static_cast<double>(i) / N : (i + 0.5) / N;
    for (int t = 0; t < T; ++t) {
      const int m = 1 - T / 2 + t;
      ax.exact[static_cast<size_t>(i) * T + t] = h(f - m);
      AxisTap tap{};
      const int base = t * n;
      if (s.recon == RomRecon::Nearest) {
        int k = s.sample_pos == SamplePos::Centre ? static_cast<int>(std::floor(f * R))
                                                  : static_cast<int>(std::floor(f * R + 0.5));
        k = std::clamp(k, 0, n - 1);
        tap = {base + k, base + k, 0.0};
      } else {
        const double u = s.sample_pos == SamplePos::Centre ? f * R - 0.5 : f * R;
        int k0 = static_cast<int>(std::floor(u));
        double a = u - k0;
        if (s.edge == TileEdge::Clamp || s.sample_pos == SamplePos::Corner) {
          if (k0 < 0) { k0 = 0; a = 0.0; }
          if (k0 >= n - 1) { k0 = n - 1; a = 0.0; }
          tap = {base + k0, base + std::min(k0 + 1, n - 1), a};
        } else {
          // Continuous: the neighbour tile in kernel space. Tap t's tile covers x in [m' .. m'+1]
          // with x = f - m; the entry before entry 0 is the last entry of tap t+1 (x smaller by
          // one tile), the entry after the last is entry 0 of tap t-1. Outside the support: 0.
          if (k0 < 0) {
            tap = {t + 1 < T ? (t + 1) * n + (n - 1) : -1, base, a};
          } else if (k0 >= n - 1) {
            tap = {base + n - 1, t - 1 >= 0 ? (t - 1) * n : -1, a};
          } else {
            tap = {base + k0, base + k0 + 1, a};
          }
        }
      }
      ax.lookup[static_cast<size_t>(i) * T + t] = tap;
    }
  }
  return ax;
}

}  // namespace

double kernel_error_scaled(const KernelErrorSpec& spec) {
  spec.validate();
  const FilterKernel h = FilterKernel::by_name(spec.kernel);
  const Axis ax = build_axis(h, spec);
  const double scale = static_cast<double>(unorm::max_code(spec.bits));
  // The ROM's own quantization rule (weight_rom.hpp: Eq. 3.4 on sign + magnitude), in [0,1] units.
  const auto quantized = [&](double w) { return quantize_weight(w, spec.bits).value() / scale; };
  const int T = ax.taps, N = spec.effective_locations(), d = spec.dims;
  const auto sample = [&](int idx) { return idx < 0 ? 0.0 : ax.sample[static_cast<size_t>(idx)]; };

  // Rows of locations (y, and z inside) are handed out to threads through an atomic counter;
  // each thread keeps its own maximum. Tiles composition quantizes the d-D sample h(x)h(y)[h(z)]
  // on the fly (no R^d table), reading 2^d entries per weight for linear reconstruction.
  const auto nthreads = static_cast<unsigned>(spec.threads > 0 ? spec.threads : hardware_threads());
  std::atomic<int> next_row{0};
  std::vector<double> worst(nthreads, 0.0);

  // Per-axis reconstructed 1D weights (separable compositions), in the [0,1] domain.
  auto recon1d = [&](const AxisTap& l) {
    const double q0 = quantized(sample(l.k0));
    if (spec.recon == RomRecon::Nearest || l.a == 0.0) return q0;
    const double lin = q0 * (1 - l.a) + quantized(sample(l.k1)) * l.a;
    return spec.requantize_linear ? quantized(lin) : lin;
  };
  auto fixed_mul = [&](double a, double b) {  // b-bit tile-weight multiplier on codes
    const auto ca = static_cast<int32_t>(std::lround(a * scale)), cb = static_cast<int32_t>(std::lround(b * scale));
    return tile_weight_multiply(ca, cb, spec.bits) / scale;
  };
  // Tiles composition: the quantized d-D sample, reconstructed over 2^d neighbours.
  auto recon_tiles = [&](const AxisTap& lx, const AxisTap& ly, const AxisTap* lz) {
    double rom = 0.0;
    const int corners = (spec.recon == RomRecon::Nearest) ? 1 : (lz ? 8 : 4);
    for (int c = 0; c < corners; ++c) {
      const int kx = (c & 1) ? lx.k1 : lx.k0, ky = (c & 2) ? ly.k1 : ly.k0;
      double w = ((c & 1) ? lx.a : 1 - lx.a) * ((c & 2) ? ly.a : 1 - ly.a);
      double prod = sample(kx) * sample(ky);
      if (lz) {
        const int kz = (c & 4) ? lz->k1 : lz->k0;
        w *= (c & 4) ? lz->a : 1 - lz->a;
        prod *= sample(kz);
      }
      if (spec.recon == RomRecon::Nearest) w = 1.0;
      if (w != 0.0) rom += w * quantized(prod);
    }
    return spec.requantize_linear && spec.recon == RomRecon::Linear ? quantized(rom) : rom;
  };

  auto work = [&](unsigned tid) {
    double local = 0.0;
    std::vector<double> rx(static_cast<size_t>(T)), ry(rx), rz(rx), ex(rx), ey(rx), ez(rx);
    const int y_count = d >= 2 ? N : 1, tyn = d >= 2 ? T : 1;
    for (int iy = next_row++; iy < y_count; iy = next_row++) {
      const int z_count = d == 3 ? N : 1;
      for (int t = 0; t < tyn; ++t) {
        ry[static_cast<size_t>(t)] = d >= 2 ? recon1d(ax.lookup[static_cast<size_t>(iy) * T + t]) : 1.0;
        ey[static_cast<size_t>(t)] = d >= 2 ? ax.exact[static_cast<size_t>(iy) * T + t] : 1.0;
      }
      for (int iz = 0; iz < z_count; ++iz) {
        const int tzn = d == 3 ? T : 1;
        for (int t = 0; t < tzn; ++t) {
          rz[static_cast<size_t>(t)] = d == 3 ? recon1d(ax.lookup[static_cast<size_t>(iz) * T + t]) : 1.0;
          ez[static_cast<size_t>(t)] = d == 3 ? ax.exact[static_cast<size_t>(iz) * T + t] : 1.0;
        }
        for (int ix = 0; ix < N; ++ix) {
          for (int t = 0; t < T; ++t) {
            rx[static_cast<size_t>(t)] = recon1d(ax.lookup[static_cast<size_t>(ix) * T + t]);
            ex[static_cast<size_t>(t)] = ax.exact[static_cast<size_t>(ix) * T + t];
          }
          double sum = 0.0;
          for (int tz = 0; tz < tzn; ++tz)
            for (int ty = 0; ty < tyn; ++ty)
              for (int tx = 0; tx < T; ++tx) {
                const size_t x = static_cast<size_t>(tx), y = static_cast<size_t>(ty), z = static_cast<size_t>(tz);
                const double exact = ex[x] * ey[y] * ez[z];
                double rom;
                switch (d == 1 ? Composition::Separable : spec.composition) {
                  case Composition::Separable: rom = rx[x] * ry[y] * rz[z]; break;
                  case Composition::SeparableFixed:
                    rom = fixed_mul(rx[x], ry[y]);
                    if (d == 3) rom = fixed_mul(rom, rz[z]);
                    break;
                  default:
                    rom = recon_tiles(ax.lookup[static_cast<size_t>(ix) * T + tx], ax.lookup[static_cast<size_t>(iy) * T + ty],
                                      d == 3 ? &ax.lookup[static_cast<size_t>(iz) * T + tz] : nullptr);
                }
                sum += std::abs(rom - exact);
              }
          local = std::max(local, sum);
        }
      }
    }
    worst[tid] = local;
  };
  run_workers(static_cast<int>(nthreads), [&](int w) { work(static_cast<unsigned>(w)); });
  return *std::max_element(worst.begin(), worst.end()) * scale;
}

KernelErrorFloor kernel_error_floor(const KernelErrorSpec& spec, double max_error_lsb) {
  spec.validate();
  if (spec.dims > 2 || spec.composition == Composition::SeparableFixed || spec.requantize_linear)
    throw InputError("the kernel-error floor needs --dims 1 or 2, --composition separable or tiles, and no --requantize");
  if (!(max_error_lsb >= 0.0)) throw InputError("the kernel-error floor needs a quantizer error >= 0 LSB");
  const FilterKernel h = FilterKernel::by_name(spec.kernel);
  const Axis ax = build_axis(h, spec);
  const double scale = static_cast<double>(unorm::max_code(spec.bits));
  const double e = max_error_lsb / scale;
  const int T = ax.taps, N = spec.effective_locations();
  const auto sample = [&](int idx) { return idx < 0 ? 0.0 : ax.sample[static_cast<size_t>(idx)]; };
  // Unquantized reconstructed 1D weights u (nearest or linear between exact ROM samples) and the
  // exact weights, per location and tap.
  std::vector<double> u(static_cast<size_t>(N) * T), abs_sum(static_cast<size_t>(N), 0.0);
  for (int i = 0; i < N; ++i)
    for (int t = 0; t < T; ++t) {
      const AxisTap& l = ax.lookup[static_cast<size_t>(i) * T + t];
      const double v = spec.recon == RomRecon::Nearest ? sample(l.k0) : sample(l.k0) * (1 - l.a) + sample(l.k1) * l.a;
      u[static_cast<size_t>(i) * T + t] = v;
      abs_sum[static_cast<size_t>(i)] += std::abs(v);
    }
  KernelErrorFloor out;
  const auto at = [&](const std::vector<double>& v, int i, int t) { return v[static_cast<size_t>(i) * T + t]; };
  if (spec.dims == 1) {
    for (int i = 0; i < N; ++i) {
      double d = 0;
      for (int t = 0; t < T; ++t) d += std::abs(at(u, i, t) - at(ax.exact, i, t));
      out.discretization = std::max(out.discretization, d);
      out.floor = std::max(out.floor, d - T * e);
    }
  } else {
    for (int iy = 0; iy < N; ++iy)
      for (int ix = 0; ix < N; ++ix) {
        double d = 0;
        for (int ty = 0; ty < T; ++ty)
          for (int tx = 0; tx < T; ++tx)
            d += std::abs(at(u, ix, tx) * at(u, iy, ty) - at(ax.exact, ix, tx) * at(ax.exact, iy, ty));
        // Separable: |q_x q_y - u_x u_y| <= E |u_y| + E |u_x| + E^2 for |q - u| <= E on each axis.
        // Tiles: every 2D weight is quantized on its own, |q - u_x u_y| <= E.
        const double q = spec.composition == Composition::Tiles
                             ? T * T * e
                             : T * e * (abs_sum[static_cast<size_t>(ix)] + abs_sum[static_cast<size_t>(iy)]) + T * T * e * e;
        out.discretization = std::max(out.discretization, d);
        out.floor = std::max(out.floor, d - q);
      }
  }
  out.discretization *= scale;
  out.floor *= scale;
  return out;
}

const std::vector<PublishedKernelError>& published_table_3_5() {
  // Hadwiger 2004, Table 3.5 (values are 255 * eps_h). Transcribed from the dissertation text in
  // ../shared/seeds; these are the published targets, not our results.
  using R = RomRecon;
  static const std::vector<PublishedKernelError> kTable = {
      {"bspline", 16, 2, R::Nearest, 11.2351},     {"bspline", 16, 2, R::Linear, 5.5803},
      {"bspline", 16, 3, R::Nearest, 12.3400},     {"bspline", 16, 3, R::Linear, 7.2346},
      {"bspline", 32, 2, R::Nearest, 6.1619},      {"bspline", 32, 2, R::Linear, 3.9219},
      {"bspline", 32, 3, R::Nearest, 7.1811},      {"bspline", 32, 3, R::Linear, 5.4758},
      {"bspline", 64, 2, R::Nearest, 3.8838},      {"bspline", 64, 2, R::Linear, 3.3165},
      {"bspline", 64, 3, R::Nearest, 5.0478},      {"bspline", 64, 3, R::Linear, 7.0751},
      {"bspline", 128, 2, R::Nearest, 2.8293},     {"bspline", 128, 2, R::Linear, 2.5841},
      {"bspline", 128, 3, R::Nearest, 4.4375},     {"bspline", 128, 3, R::Linear, 4.1687},
      {"bspline", 256, 2, R::Nearest, 2.3145},     {"bspline", 256, 2, R::Linear, 2.2676},
      {"bspline", 512, 2, R::Nearest, 2.0867},     {"bspline", 512, 2, R::Linear, 2.0867},
      {"catmull-rom", 16, 2, R::Nearest, 25.3076}, {"catmull-rom", 16, 2, R::Linear, 15.0835},
      {"catmull-rom", 16, 3, R::Nearest, 32.6554}, {"catmull-rom", 16, 3, R::Linear, 19.1470},
      {"catmull-rom", 32, 2, R::Nearest, 14.4100}, {"catmull-rom", 32, 2, R::Linear, 10.8905},
      {"catmull-rom", 32, 3, R::Nearest, 17.8089}, {"catmull-rom", 32, 3, R::Linear, 14.3186},
      {"catmull-rom", 64, 2, R::Nearest, 8.7091},  {"catmull-rom", 64, 2, R::Linear, 8.3325},
      {"catmull-rom", 64, 3, R::Nearest, 11.2476}, {"catmull-rom", 64, 3, R::Linear, 11.9767},
      {"catmull-rom", 128, 2, R::Nearest, 6.0308}, {"catmull-rom", 128, 2, R::Linear, 7.1140},
      {"catmull-rom", 128, 3, R::Nearest, 8.1039}, {"catmull-rom", 128, 3, R::Linear, 10.5024},
      {"catmull-rom", 256, 2, R::Nearest, 4.9057}, {"catmull-rom", 256, 2, R::Linear, 6.7169},
      {"catmull-rom", 512, 2, R::Nearest, 4.3535}, {"catmull-rom", 512, 2, R::Linear, 6.3613},
      {"blackman", 16, 2, R::Nearest, 26.3035},    {"blackman", 16, 2, R::Linear, 15.4278},
      {"blackman", 16, 3, R::Nearest, 34.0124},    {"blackman", 16, 3, R::Linear, 20.0338},
      {"blackman", 32, 2, R::Nearest, 14.3229},    {"blackman", 32, 2, R::Linear, 10.7960},
      {"blackman", 32, 3, R::Nearest, 17.9082},    {"blackman", 32, 3, R::Linear, 14.7748},
      {"blackman", 64, 2, R::Nearest, 8.8159},     {"blackman", 64, 2, R::Linear, 8.3062},
      {"blackman", 64, 3, R::Nearest, 11.4056},    {"blackman", 64, 3, R::Linear, 12.0028},
      {"blackman", 128, 2, R::Nearest, 6.0954},    {"blackman", 128, 2, R::Linear, 7.2064},
      {"blackman", 128, 3, R::Nearest, 8.1723},    {"blackman", 128, 3, R::Linear, 10.6158},
      {"blackman", 256, 2, R::Nearest, 4.9426},    {"blackman", 256, 2, R::Linear, 6.6606},
      {"blackman", 512, 2, R::Nearest, 4.3151},    {"blackman", 512, 2, R::Linear, 6.3229},
  };
  return kTable;
}

}  // namespace tfu
