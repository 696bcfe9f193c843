// Continuous filter kernels (cmodel/kernels.hpp): hand-derived values and reported properties.
#include <gtest/gtest.h>

#include <cmath>

#include "cmodel/error.hpp"
#include "cmodel/kernels.hpp"

namespace tfu {
namespace {

TEST(Kernels, BSplineHandDerived) {
  const auto h = FilterKernel::bspline();
  EXPECT_NEAR(h(0.0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(h(1.0), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(h(-1.0), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(h(0.5), 23.0 / 48.0, 1e-15);  // (3/8 - 3/2 + 4) / 6
  EXPECT_NEAR(h(1.5), 1.0 / 48.0, 1e-15);   // (2 - 1.5)^3 / 6
  EXPECT_EQ(h(2.0), 0.0);
  EXPECT_EQ(h.width(), 4);
  EXPECT_FALSE(h.interpolating());
  EXPECT_TRUE(h.sign_changes().empty());
  EXPECT_LT(h.partition_of_unity_deviation(), 1e-14);
}

TEST(Kernels, CatmullRomInterpolatesAtIntegers) {
  const auto h = FilterKernel::catmull_rom();
  EXPECT_NEAR(h(0.0), 1.0, 1e-15);
  EXPECT_NEAR(h(1.0), 0.0, 1e-15);
  EXPECT_NEAR(h(2.0), 0.0, 1e-15);
  EXPECT_NEAR(h(0.5), 0.5625, 1e-15);
  EXPECT_NEAR(h(1.5), -0.0625, 1e-15);
  EXPECT_TRUE(h.interpolating());
  const auto z = h.sign_changes();
  ASSERT_EQ(z.size(), 2u);
  EXPECT_NEAR(z[0], -1.0, 1e-9);
  EXPECT_NEAR(z[1], 1.0, 1e-9);
  EXPECT_LT(h.partition_of_unity_deviation(), 1e-14);
}

TEST(Kernels, MitchellDefaultAndBcFamily) {
  const auto h = FilterKernel::mitchell();
  EXPECT_NEAR(h(0.0), (6.0 - 2.0 / 3.0) / 6.0, 1e-15);  // (6 - 2B)/6 with B = 1/3
  EXPECT_NEAR(h(1.0), 1.0 / 18.0, 1e-15);               // B/6
  EXPECT_FALSE(h.interpolating());
  const auto z = h.sign_changes();
  ASSERT_EQ(z.size(), 2u);  // negative lobes between 1 and 2
  EXPECT_GT(z[1], 1.0);
  EXPECT_LT(z[1], 2.0);
  EXPECT_NEAR(h(z[1]), 0.0, 1e-10);
  // (B, C) = (1, 0) is the B-spline.
  const auto b = FilterKernel::mitchell_netravali(1.0, 0.0);
  for (double x = -2.0; x <= 2.0; x += 0.0625) EXPECT_NEAR(b(x), FilterKernel::bspline()(x), 1e-15);
}

TEST(Kernels, WindowedSincsInterpolateAndChangeSignAtOne) {
  for (const auto& h : {FilterKernel::blackman_sinc(), FilterKernel::kaiser_sinc()}) {
    EXPECT_TRUE(h.interpolating()) << h.name();
    EXPECT_TRUE(h.symmetric()) << h.name();
    const auto z = h.sign_changes();
    ASSERT_EQ(z.size(), 2u) << h.name();
    EXPECT_NEAR(z[1], 1.0, 1e-9);
    EXPECT_EQ(h(2.0), 0.0);
    // Windowed sincs do not sum to one exactly; the deviation is reported, and small.
    EXPECT_GT(h.partition_of_unity_deviation(), 1e-6) << h.name();
    EXPECT_LT(h.partition_of_unity_deviation(), 0.05) << h.name();
  }
  // Blackman window of width 4 at x = 1: 0.42 + 0.5 cos(pi/2) + 0.08 cos(pi) = 0.34; sinc(0.5) = 2/pi.
  EXPECT_NEAR(FilterKernel::blackman_sinc()(0.5), (2.0 / M_PI) * (0.42 + 0.5 * std::cos(M_PI / 4) + 0.08 * std::cos(M_PI / 2)),
              1e-15);
}

TEST(Kernels, BoxAndTent) {
  const auto box = FilterKernel::box(), tent = FilterKernel::tent();
  EXPECT_EQ(box.width(), 1);
  EXPECT_EQ(tent.width(), 2);
  EXPECT_EQ(box(0.49), 1.0);
  EXPECT_EQ(box(0.5), 0.0);
  EXPECT_EQ(box(-0.5), 1.0);
  EXPECT_NEAR(tent(0.25), 0.75, 1e-15);
  EXPECT_TRUE(tent.interpolating());
  EXPECT_LT(box.partition_of_unity_deviation(), 1e-15);
  EXPECT_LT(tent.partition_of_unity_deviation(), 1e-15);
}

TEST(Kernels, EveryNamedKernelIsSymmetricAndSeparable) {
  for (const auto& n : FilterKernel::names()) {
    const auto h = FilterKernel::by_name(n);
    EXPECT_EQ(h.name(), n);
    EXPECT_TRUE(h.separable());
    if (n != "box") {  // box is half-open at +1/2 by design
      EXPECT_TRUE(h.symmetric()) << n;
    }
  }
}

TEST(Kernels, UnknownNameIsAnInputError) {
  EXPECT_THROW(FilterKernel::by_name("lanczos9"), InputError);
  try {
    FilterKernel::by_name("nope");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos);
  }
}

}  // namespace
}  // namespace tfu
