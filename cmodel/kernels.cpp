#include "cmodel/kernels.hpp"

#include <cmath>
#include <numbers>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"

namespace tfu {
namespace {

double sinc(double x) {
  if (std::abs(x) < 1e-12) return 1.0;
  const double px = std::numbers::pi * x;
  return std::sin(px) / px;
}

// Modified Bessel function of the first kind, order 0 (power series; converges for all x).
double bessel_i0(double x) {
  double sum = 1.0, term = 1.0;
  const double q = x * x / 4.0;
  for (int k = 1; k < 200; ++k) {
    term *= q / (static_cast<double>(k) * static_cast<double>(k));
    sum += term;
    if (term < sum * 1e-17) break;
  }
  return sum;
}

}  // namespace

FilterKernel FilterKernel::box() {
  // Half-open on the right so that exactly one texel gets weight 1 at any position.
  return FilterKernel("box", 1, [](double x) { return (x >= -0.5 && x < 0.5) ? 1.0 : 0.0; });
}

FilterKernel FilterKernel::tent() {
  return FilterKernel("tent", 2, [](double x) {
    const double a = std::abs(x);
    return a < 1.0 ? 1.0 - a : 0.0;
  });
}

// Mitchell & Netravali (1988) two-parameter cubic family.
FilterKernel FilterKernel::mitchell_netravali(double B, double C, std::string name) {
  if (name.empty()) name = "bc(" + std::to_string(B) + "," + std::to_string(C) + ")";
  return FilterKernel(std::move(name), 4, [B, C](double x) {
    const double a = std::abs(x);
    const double a2 = a * a, a3 = a2 * a;
    if (a < 1.0)
      return ((12.0 - 9.0 * B - 6.0 * C) * a3 + (-18.0 + 12.0 * B + 6.0 * C) * a2 + (6.0 - 2.0 * B)) / 6.0;
    if (a < 2.0)
      return ((-B - 6.0 * C) * a3 + (6.0 * B + 30.0 * C) * a2 + (-12.0 * B - 48.0 * C) * a + (8.0 * B + 24.0 * C)) /
             6.0;
    return 0.0;
  });
}

FilterKernel FilterKernel::kaiser_sinc(double alpha) {
  const double norm = 1.0 / bessel_i0(alpha);
  return FilterKernel("kaiser", 4, [alpha, norm](double x) {
    const double a = std::abs(x);
    if (a >= 2.0) return 0.0;
    const double r = a / 2.0;
    return sinc(x) * bessel_i0(alpha * std::sqrt(1.0 - r * r)) * norm;
  });
}

FilterKernel FilterKernel::blackman_sinc() {
  // Blackman window of total width 4 centred at 0: 0.42 + 0.5 cos(pi x / 2) + 0.08 cos(pi x).
  return FilterKernel("blackman", 4, [](double x) {
    const double a = std::abs(x);
    if (a >= 2.0) return 0.0;
    const double w = 0.42 + 0.5 * std::cos(std::numbers::pi * x / 2.0) + 0.08 * std::cos(std::numbers::pi * x);
    return sinc(x) * w;
  });
}

const std::vector<std::string>& FilterKernel::names() {
  static const std::vector<std::string> kNames = {"box",      "tent",   "bspline", "catmull-rom",
                                                  "mitchell", "kaiser", "blackman"};
  return kNames;
}

FilterKernel FilterKernel::by_name(std::string_view name) {
  if (name == "box") return box();
  if (name == "tent") return tent();
  if (name == "bspline" || name == "b-spline") return bspline();
  if (name == "catmull-rom" || name == "catmullrom") return catmull_rom();
  if (name == "mitchell") return mitchell();
  if (name == "kaiser") return kaiser_sinc();
  if (name == "blackman") return blackman_sinc();
  std::string valid;
  for (const auto& n : names()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("unknown kernel '" + quote_input(name) + "' (" + did_you_mean(name, names()) + "valid: " + valid + ")");
}

bool FilterKernel::symmetric() const {
  for (int i = 0; i <= 4000; ++i) {
    const double x = 2.0 * i / 4000.0 + 1e-7;
    if (std::abs(fn_(x) - fn_(-x)) > 1e-12) return false;
  }
  return true;
}

bool FilterKernel::interpolating() const {
  if (std::abs(fn_(0.0) - 1.0) > 1e-12) return false;
  for (int k = 1; k <= half_width() + 1; ++k)
    if (std::abs(fn_(k)) > 1e-12 || std::abs(fn_(-k)) > 1e-12) return false;
  return true;
}

std::vector<double> FilterKernel::sign_changes() const {
  // Scan on a fine grid; a sign change between two non-zero samples (zeros are skipped over, so a
  // kernel that touches zero without changing sign reports nothing) is refined by bisection.
  std::vector<double> out;
  const double lo = -width_ / 2.0, hi = width_ / 2.0;
  const int steps = 8192;
  double prev_x = lo;
  double prev_v = 0.0;
  bool have_prev = false;
  for (int i = 1; i < steps; ++i) {
    const double x = lo + (hi - lo) * i / steps;
    const double v = fn_(x);
    if (std::abs(v) < 1e-15) continue;
    if (have_prev && (v > 0) != (prev_v > 0)) {
      double a = prev_x, b = x;
      for (int it = 0; it < 100 && b - a > 1e-13; ++it) {
        const double m = 0.5 * (a + b);
        const double vm = fn_(m);
        if (std::abs(vm) < 1e-15) { a = b = m; break; }
        ((vm > 0) == (prev_v > 0) ? a : b) = m;
      }
      out.push_back(0.5 * (a + b));
    }
    prev_x = x;
    prev_v = v;
    have_prev = true;
  }
  return out;
}

double FilterKernel::partition_of_unity_deviation() const {
  double worst = 0.0;
  for (int i = 0; i < 4096; ++i) {
    const double f = i / 4096.0;
    double s = 0.0;
    for (int k = -width_; k <= width_; ++k) s += fn_(f - k);
    worst = std::max(worst, std::abs(s - 1.0));
  }
  return worst;
}

}  // namespace tfu
