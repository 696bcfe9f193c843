// Continuous 1D reconstruction filter kernels, evaluated in double precision.
// Used ONLY for offline table generation (weight ROMs) and for the "ideal" quality reference;
// no datapath computes with these values directly.
//
// Kernels are even functions centred at 0 with support [-width/2, width/2]:
//   box (width 1), tent (width 2), and width-4 cubics and windowed sincs:
//   cubic B-spline = Mitchell-Netravali (B=1, C=0), Catmull-Rom = (B=0, C=0.5),
//   Mitchell = (B=1/3, C=1/3) by default or any (B, C),
//   Kaiser-windowed sinc (parameter alpha), Blackman-windowed sinc (window width 4).
// 2D and 3D kernels are tensor products h(x)h(y)[h(z)], so every kernel here is separable.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace tfu {

class FilterKernel {
 public:
  using Fn = std::function<double(double)>;

  static FilterKernel box();
  static FilterKernel tent();
  static FilterKernel mitchell_netravali(double B, double C, std::string name = "");
  static FilterKernel bspline() { return mitchell_netravali(1.0, 0.0, "bspline"); }
  static FilterKernel catmull_rom() { return mitchell_netravali(0.0, 0.5, "catmull-rom"); }
  static FilterKernel mitchell() { return mitchell_netravali(1.0 / 3.0, 1.0 / 3.0, "mitchell"); }
  static FilterKernel kaiser_sinc(double alpha = kDefaultKaiserAlpha);
  static FilterKernel blackman_sinc();

  // Kernel by command-line name: box, tent, bspline, catmull-rom, mitchell, kaiser, blackman.
  // Throws InputError naming the unknown kernel and listing the valid names.
  static FilterKernel by_name(std::string_view name);
  static const std::vector<std::string>& names();

  static constexpr double kDefaultKaiserAlpha = 3.0;

  double operator()(double x) const { return fn_(x); }
  const std::string& name() const { return name_; }
  int width() const { return width_; }       // support width in texels: 1, 2 or 4
  int half_width() const { return width_ / 2; }
  bool symmetric() const;                    // h(-x) == h(x), checked numerically
  bool separable() const { return true; }    // tensor-product use in 2D/3D (see header comment)
  bool interpolating() const;                // h(0) == 1 and h(k) == 0 for integers k != 0
  // Positions x (ascending, inside the support) where h changes sign, found by scanning and
  // bisection to 1e-12. Empty for non-negative kernels.
  std::vector<double> sign_changes() const;
  // max over x in [0,1) of |sum_k h(x - k) - 1|: 0 for kernels with the partition-of-unity
  // property (box, tent, all BC cubics); small but non-zero for windowed sincs.
  double partition_of_unity_deviation() const;

 private:
  FilterKernel(std::string name, int width, Fn fn) : name_(std::move(name)), width_(width), fn_(std::move(fn)) {}
  std::string name_;
  int width_;
  Fn fn_;
};

}  // namespace tfu
