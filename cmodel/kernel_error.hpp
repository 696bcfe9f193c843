// Filter-kernel representation error eps_h (Hadwiger 2004, Sec. 3.5, Eq. 3.5, Table 3.5).
//
//   eps_h = max over resampling locations i of  sum_j | w_rom(i, j) - w_exact(i, j) |
//
// where j runs over the T^d weights one output sample needs (16 for bicubic, 64 for tricubic),
// w_exact is the product of the continuous 1D kernel values, and w_rom is what the hardware
// retrieves from the d-dimensional tiles after sampling the kernel at R samples per dimension and
// tile, quantizing every sample to b bits (Eq. 3.4, sign + magnitude), and reconstructing with
// nearest ("box") or linear interpolation between ROM entries (done in double precision, as the
// texture unit of the dissertation's GPU did). Results are reported x (2^b - 1) like Table 3.5.
//
// The sampling conventions are parameters because the dissertation does not state them; see
// docs/kernel-error.md for which convention reproduces the published table and by how much.
#pragma once

#include <string>
#include <vector>

#include "cmodel/kernels.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu {

// Where the resampling locations lie in [0,1)^d: grid i/N, or cell centres (i + 1/2)/N.
enum class LocationGrid { Corner, Centre };
// How linear reconstruction treats the tile edge: clamp inside the tile (each tile its own texture
// with clamp-to-edge), or interpolate across into the neighbouring tile (all tiles packed in one
// texture; the kernel is continuous across tile boundaries).
enum class TileEdge { Clamp, Continuous };

// How the d-dimensional weight is formed from the ROM:
//   Separable : product of the d reconstructed 1D weights (1D tiles, each sample quantized to b
//               bits; the product is formed at full precision, as the pixel shader did);
//   SeparableFixed : the same product through the b-bit normalized tile-weight multiplier
//               (rounded, cmodel/weight_rom.hpp tile_weight_multiply), as our datapath does;
//   Tiles     : d-dimensional tiles whose every sample h(x)h(y)[h(z)] is quantized to b bits.
enum class Composition { Separable, SeparableFixed, Tiles };

struct KernelErrorSpec {
  std::string kernel = "bspline";
  int samples = 64;            // R per dimension and tile
  unsigned bits = 8;           // b
  RomRecon recon = RomRecon::Nearest;
  int dims = 2;                // 1, 2 or 3 (1 = one set of T weights, for analysis)
  int locations = 0;           // per dimension; 0 = the dissertation's choice (1024 in 2D, 256 in 3D)
  SamplePos sample_pos = SamplePos::Centre;
  LocationGrid grid = LocationGrid::Corner;
  TileEdge edge = TileEdge::Clamp;
  Composition composition = Composition::Separable;
  bool requantize_linear = false;  // round each linearly reconstructed weight back to b bits
                                   // (a texture unit that returns b-bit filtered texels)
  int threads = 0;             // 0 = all hardware threads

  void validate() const;  // throws InputError
  int effective_locations() const { return locations > 0 ? locations : (dims == 3 ? 256 : 1024); }
};

// eps_h x (2^b - 1).
double kernel_error_scaled(const KernelErrorSpec& spec);

// What no quantizer can beat (docs/kernel-error.md, "why the published table differs"). For any
// per-weight quantizer whose stored weights are within e LSB of the exact ROM samples (e = 1/2
// for rounding, 1 for truncation), dims 1 or 2, separable or tiles
// composition, no requantization, at every location i:
//   eps_h >= D(i) - Q(i),  D(i) = sum_j |u_j - w_exact_j|  (unquantized ROM, discretization only),
//   Q(i)  = bound of sum_j |q_j - u_j|: T E (d = 1); separable 2D T E sum over both axes of
//           sum_t |u_t| + T^2 E^2; tiles 2D T^2 E; with E = e / (2^b - 1),
// so eps_h >= max_i (D(i) - Q(i)) = floor. Both x (2^b - 1).
struct KernelErrorFloor {
  double discretization = 0;  // max_i D(i)
  double floor = 0;           // max_i (D(i) - Q(i))
};
KernelErrorFloor kernel_error_floor(const KernelErrorSpec& spec, double max_error_lsb);

// One published entry of Table 3.5 (dissertation p. 70): 255 * eps_h.
struct PublishedKernelError {
  const char* kernel;  // bspline, catmull-rom, blackman
  int samples;
  int dims;
  RomRecon recon;
  double value;
};
const std::vector<PublishedKernelError>& published_table_3_5();

}  // namespace tfu
