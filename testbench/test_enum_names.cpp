// The enum name tables (cmodel/enum_names.hpp): every table names each value of its enum exactly
// once (aliases aside), every name reads back as its value, and the error line of an unknown name
// is the one the CLI has always printed (the expected lines are typed here from the messages the
// hand-written functions gave before the tables replaced them).
#include <set>
#include <string>
#include <type_traits>

#include <gtest/gtest.h>

#include "cmodel/descriptors.hpp"
#include "cmodel/enum_names.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/q3_textures.hpp"
#include "cmodel/raster_order.hpp"
#include "cmodel/texenv.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_stats.hpp"

namespace tfu {
namespace {

// Every value 0..count-1 named by its first entry, no other value named, names unique, every
// entry's name reading back as its value.
template <typename E, size_t N>
void expect_table_complete(const EnumNames<E, N>& t, int count) {
  using U = std::underlying_type_t<E>;
  std::set<std::string> seen;
  std::set<U> values;
  for (const EnumName<E>& e : t.entries) {
    EXPECT_TRUE(seen.insert(e.name).second) << t.what << ": name '" << e.name << "' twice";
    values.insert(static_cast<U>(e.value));
    E back{};
    ASSERT_TRUE(t.find(e.name, back)) << e.name;
    EXPECT_EQ(back, e.value) << e.name;
    EXPECT_EQ(t.from_name(e.name), e.value) << e.name;
  }
  EXPECT_EQ(values.size(), static_cast<size_t>(count)) << t.what;
  for (int v = 0; v < count; ++v) EXPECT_STRNE(t.name(static_cast<E>(v)), "?") << t.what << " value " << v;
  EXPECT_STREQ(t.name(static_cast<E>(count)), "?") << t.what << ": a value beyond the enum is named";
}

template <typename E, size_t N>
std::string error_of(const EnumNames<E, N>& t, const std::string& input) {
  try {
    t.from_name(input);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(EnumNames, EveryTableNamesEveryValueOnce) {
  expect_table_complete(kTexelFormatNames, 4);
  expect_table_complete(kMemoryLayoutNames, 2);
  expect_table_complete(kWrapModeNames, 4);
  expect_table_complete(kMipMethodNames, 3);
  expect_table_complete(kTexEnvNames, 4);
  expect_table_complete(kEdgeShapeNames, 3);
  expect_table_complete(kTraceModeNames, 3);
  expect_table_complete(kRasterTraversalNames, 3);
  expect_table_complete(kUnitDistributionNames, 2);
  expect_table_complete(q3::kSurfaceClassNames, 3);
  expect_table_complete(rtl::kUnitEngineNames, 2);
  expect_table_complete(rtl::kStatKindNames, 4);
}

TEST(EnumNames, NameFunctionsReadTheTables) {
  EXPECT_STREQ(texel_format_name(TexelFormat::VS16X2), "vs16x2");
  EXPECT_EQ(memory_layout_from_name("tiled"), MemoryLayout::Tiled);
  EXPECT_STREQ(wrap_mode_name(WrapMode::MirroredRepeat), "mirrored-repeat");
  EXPECT_EQ(wrap_mode_names(),
            (std::vector<std::string>{"repeat", "mirrored-repeat", "clamp-to-edge", "clamp-to-border"}));
  EXPECT_EQ(mip_method_from_name("gaussian"), MipMethod::Gaussian);
  EXPECT_STREQ(tex_env_name(TexEnv::Decal), "decal");
  // "full-cross" is an alias: accepted, not offered, and never the name of the value.
  EXPECT_EQ(edge_shape_from_name("full-cross"), EdgeShape::Cross);
  EXPECT_STREQ(edge_shape_name(EdgeShape::Cross), "cross");
  EXPECT_STREQ(trace_mode_name(TraceMode::Grad), "grad");
  EXPECT_STREQ(q3::surface_class_name(q3::SurfaceClass::Sky), "sky");
}

TEST(EnumNames, UnknownNameErrorLines) {
  EXPECT_EQ(error_of(kTexelFormatNames, "rgb8"),
            "unknown texel format 'rgb8' (did you mean 'rgba8'? expected rgba8, l8, vs16x2 or srgba8)");
  EXPECT_EQ(error_of(kMemoryLayoutNames, "morton"), "unknown memory layout 'morton' (expected linear or tiled)");
  EXPECT_EQ(error_of(kWrapModeNames, "clamp"),
            "unknown wrap mode 'clamp' (did you mean 'clamp-to-edge'? expected repeat, mirrored-repeat, clamp-to-edge or clamp-to-border)");
  EXPECT_EQ(error_of(kMipMethodNames, "lanczos"), "unknown MIP method 'lanczos' (expected box, gaussian or edge)");
  EXPECT_EQ(error_of(kTexEnvNames, "blend"),
            "unknown texture environment 'blend' (expected replace, modulate, add or decal)");
  EXPECT_EQ(error_of(kEdgeShapeNames, "t"), "unknown kernel-shape policy 't' (expected static, cache-aware or cross)");
  // The input is quoted as every input is (cmodel/error.hpp quote_input): control characters as
  // '?', cut at 60 characters.
  EXPECT_EQ(error_of(kMemoryLayoutNames, "a\nb"), "unknown memory layout 'a?b' (expected linear or tiled)");
  const std::string long_name(200, 'x');
  EXPECT_EQ(error_of(kTexEnvNames, long_name),
            "unknown texture environment '" + quote_input(long_name) + "' (expected replace, modulate, add or decal)");
  EXPECT_LT(error_of(kTexEnvNames, long_name).size(), 140u);
  EXPECT_EQ(kTraceModeNames.expected(), "lod, grad or quad");
  EXPECT_EQ(error_of(rtl::kUnitEngineNames, "fast"), "unknown engine 'fast' (expected recurrence or clocked)");
}

}  // namespace
}  // namespace tfu
