// The programming interface: descriptor register encodings, the texel memory and its layouts,
// level selection, request traces with descriptor indices and bindings, the driver's frame, the
// texture environment, and materials of several stages through both models.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "cmodel/bindings.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/texenv.hpp"
#include "cmodel/texture_memory.hpp"
#include "cmodel/trace.hpp"
#include "rtl/scene_sim.hpp"
#include "testbench/docs_text.hpp"

namespace tfu {
namespace {

SamplerDescriptor random_sampler(std::mt19937& rng) {
  SamplerDescriptor s;
  s.mode = all_filter_modes()[rng() % all_filter_modes().size()];
  s.wrap_s = static_cast<WrapMode>(rng() % 4);
  s.wrap_t = static_cast<WrapMode>(rng() % 4);
  s.border = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
  s.lod.bias_q8 = static_cast<int32_t>(rng() % 512001) - 256000;
  s.lod.min_lod_q8 = -static_cast<int32_t>(rng() % 256001);
  s.lod.max_lod_q8 = static_cast<int32_t>(rng() % 256001);
  s.kernel = cubic_kernel_names()[rng() % cubic_kernel_names().size()];
  s.cubic_rom.samples = 16 + static_cast<int>(rng() % 497);
  s.cubic_rom.bits = static_cast<unsigned>(4 + rng() % 13);
  s.cubic_rom.pos = static_cast<SamplePos>(rng() % 2);
  s.cubic_rom.rounding = static_cast<RomRounding>(rng() % 2);
  s.cubic_recon = static_cast<RomRecon>(rng() % 2);
  s.cubic_level_adapt = rng() % 2;
  s.edge_shape = static_cast<EdgeShape>(rng() % 3);
  s.max_aniso = 1 + static_cast<int>(rng() % 16);
  s.aniso_rounding = static_cast<AnisoRounding>(rng() % 2);
  s.aniso_threshold = static_cast<int>(rng() % 8);
  s.aniso_axes = static_cast<AnisoAxes>(rng() % 2);
  return s;
}

Texture random_texture(std::mt19937& rng, int w, int h, TexelFormat f, MemoryLayout layout, int tile_bytes) {
  Texture t;
  t.format = f;
  t.layout = layout;
  t.tile_bytes = tile_bytes;
  Image img(w, h);
  for (Rgba8& x : img.texels) {
    x = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
    if (f == TexelFormat::L8) x = {x.r, x.r, x.r, 255};
  }
  t.levels.push_back(std::move(img));
  generate_mipmaps(t, MipMethod::Box);
  return t;
}

TEST(Descriptors, FieldsTileTheirWordsWithoutOverlap) {
  for (const auto& [fields, words] : {std::pair{texture_descriptor_fields(), kTextureDescriptorWords},
                                      std::pair{sampler_descriptor_fields(), kSamplerDescriptorWords}}) {
    std::vector<uint32_t> used(static_cast<size_t>(words), 0);
    for (const RegisterField& f : fields)
      for (int i = 0; i < f.count; ++i) {
        const int w = f.word + i * f.stride;
        ASSERT_LT(w, words) << f.name;
        ASSERT_LE(f.lsb + f.width, 32) << f.name;
        const uint32_t mask = (f.width == 32 ? ~0u : ((1u << f.width) - 1u)) << f.lsb;
        EXPECT_EQ(used[static_cast<size_t>(w)] & mask, 0u) << f.name << " overlaps";
        used[static_cast<size_t>(w)] |= mask;
      }
  }
}

TEST(Descriptors, SamplerEncodingRoundTripsAndResetIsTheDefault) {
  std::mt19937 rng(1);
  for (int i = 0; i < 5000; ++i) {
    const SamplerDescriptor s = random_sampler(rng);
    const auto w = encode(s);
    EXPECT_EQ(decode_sampler_descriptor(w), s) << i;
  }
  EXPECT_EQ(decode_sampler_descriptor(encode(SamplerDescriptor{})), SamplerDescriptor{});
  // Hand-checked word 0 of the default: LINEAR (1), no MIP, repeat, static shapes (1 << 8),
  // catmull-rom (3 << 10), R = 64 (63 << 14), b = 8 (8 << 23), centre, sum-preserving (1 << 29),
  // nearest reconstruction, level adaptation on (1 << 31).
  EXPECT_EQ(encode(SamplerDescriptor{})[0], 1u | 1u << 8 | 3u << 10 | 63u << 14 | 8u << 23 | 1u << 29 | 1u << 31);
  SamplerDescriptor bad;
  bad.max_aniso = 17;
  EXPECT_THROW(encode(bad), InputError);  // 16 does not fit max_aniso_m1[3:0]
}

TEST(Descriptors, TextureEncodingRoundTrips) {
  std::mt19937 rng(2);
  for (int i = 0; i < 300; ++i) {
    TextureMemory mem;
    const auto f = static_cast<TexelFormat>(rng() % 3);
    const Texture t = random_texture(rng, 1 + static_cast<int>(rng() % 70), 1 + static_cast<int>(rng() % 70), f,
                                     static_cast<MemoryLayout>(rng() % 2), 64 << (2 * (rng() % 3)));
    TextureDescriptor d = place_texture(mem, t);
    d.coeff_scale_q = static_cast<int32_t>(rng());
    d.coeff_bias_q = static_cast<int32_t>(rng());
    EXPECT_EQ(decode_texture_descriptor(encode(d)), d) << i;
  }
}

TEST(Descriptors, DocsShowTheFieldTables) {
  EXPECT_NE(test::docs_text("descriptors.md").find(descriptor_tables_markdown()), std::string::npos)
      << "docs/descriptors.md is stale: paste `tfu descriptors` between the generated markers";
}

// Every texel of every level of every layout, format and tile size is written and read back at
// its own address; addresses never collide; every level and linear row is aligned.
TEST(TextureMemory, PlaceAndReadBackEveryLayout) {
  std::mt19937 rng(3);
  TextureMemory mem;
  std::set<uint64_t> seen;
  for (const TexelFormat f : {TexelFormat::RGBA8, TexelFormat::L8, TexelFormat::VS16X2})
    for (const MemoryLayout layout : {MemoryLayout::Linear, MemoryLayout::Tiled})
      for (const int tile : {64, 256, 1024})
        for (const auto& [w, h] : {std::pair{1, 1}, {37, 5}, {64, 64}, {100, 3}}) {
          const Texture t = random_texture(rng, w, h, f, layout, tile);
          const uint64_t align = static_cast<uint64_t>(tile);
          const TextureDescriptor d = place_texture(mem, t, align);
          EXPECT_EQ(read_texture(mem, d).levels.size(), t.levels.size());
          const Texture back = read_texture(mem, d);
          for (size_t l = 0; l < t.levels.size(); ++l) {
            EXPECT_EQ(back.levels[l].texels, t.levels[l].texels) << texel_format_name(f) << memory_layout_name(layout) << tile;
            EXPECT_EQ(d.level[l].address % align, 0u);
            if (layout == MemoryLayout::Linear) {
              EXPECT_EQ(d.level[l].row_pitch % align, 0u);
            }
            for (int y = 0; y < back.levels[l].height; ++y)
              for (int x = 0; x < back.levels[l].width; ++x) {
                const uint64_t a = d.texel_address(static_cast<int>(l), x, y);
                EXPECT_LT(a + static_cast<uint64_t>(bytes_per_texel(f)), d.level[l].address + d.level_bytes(static_cast<int>(l)) + 1);
                ASSERT_TRUE(seen.insert(a).second) << "two texels at " << a;
              }
          }
        }
}

TEST(TextureMemory, TiledAddressOfAHandPlacedTexel) {
  TextureMemory mem;
  Texture t;
  t.levels.emplace_back(16, 8);  // RGBA8, tiled 4x4 (64 bytes), 4 tiles per row: pitch 256
  const TextureDescriptor d = place_texture(mem, t);
  EXPECT_EQ(d.level[0].address, 0x1000u);
  EXPECT_EQ(d.level[0].row_pitch, 256u);
  // Texel (6, 5): tile (1, 1) at 0x1000 + 256 + 64, inside it row 1, column 2: + (1 * 4 + 2) * 4.
  EXPECT_EQ(d.texel_address(0, 6, 5), 0x1000u + 256 + 64 + 24);
}

TEST(LevelSelection, GlRulesAtHandPickedLambdas) {
  // MIPMAP_NEAREST: d = lambda <= 1/2 ? 0 : ceil(lambda + 1/2) - 1 (GL 4.6 Eq. 8.6).
  EXPECT_EQ(select_levels(128, MipMode::Nearest, 5).level0, 0);
  EXPECT_EQ(select_levels(129, MipMode::Nearest, 5).level0, 1);
  EXPECT_EQ(select_levels(384, MipMode::Nearest, 5).level0, 1);
  EXPECT_EQ(select_levels(385, MipMode::Nearest, 5).level0, 2);
  EXPECT_EQ(select_levels(99 * 256, MipMode::Nearest, 5).level0, 5);
  // MIPMAP_LINEAR: floor, floor + 1, fraction.
  const LevelPick p = select_levels(2 * 256 + 64, MipMode::Linear, 5);
  EXPECT_EQ(p.level0, 2);
  EXPECT_EQ(p.level1, 3);
  EXPECT_EQ(p.blend, 64);
  EXPECT_EQ(select_levels(5 * 256, MipMode::Linear, 5).blend, 0);
  EXPECT_EQ(select_levels(-5, MipMode::Linear, 5).level0, 0);  // magnification
  EXPECT_EQ(select_levels(7 * 256, MipMode::None, 5).level0, 0);
  SamplerDescriptor s;
  s.mode.mip = MipMode::Linear;
  s.lod.bias_q8 = 256;
  s.lod.max_lod_q8 = 512;
  EXPECT_EQ(select_levels(3 * 256, s, 5).level0, 2);  // 3 + 1 clamped to 2
}

TEST(Traces, IndexedTraceWithBindingsRoundTrips) {
  std::istringstream in(
      "# tfu-trace mode=lod fields=sampler,s,t,lod,texture\n"
      "# tfu-texture 0 proc:checkerboard:32 layout=linear\n"
      "# tfu-texture 1 proc:text:16 mipmaps=box\n"
      "# tfu-sampler 0 filter=cubic kernel=bspline\n"
      "1,0.25,0.5,1.5,0\n"
      "0,0.75,0.125,-1,1\n");
  const Trace t = parse_trace(in, "t.txt");
  ASSERT_EQ(t.requests.size(), 2u);
  EXPECT_EQ(t.requests[0].sampler, 1);
  EXPECT_EQ(t.requests[0].texture, 0);
  EXPECT_EQ(t.requests[1].texture, 1);
  EXPECT_EQ(t.requests[1].lod, -1.0f);
  ASSERT_EQ(t.textures.size(), 2u);
  EXPECT_EQ(t.textures[1].spec, "proc:text:16");
  EXPECT_EQ(t.textures[0].params.at("layout"), "linear");
  EXPECT_EQ(t.samplers[0].params.at("kernel"), "bspline");
  std::ostringstream out;
  write_trace(out, t);
  std::istringstream again(out.str());
  const Trace u = parse_trace(again, "u.txt");
  ASSERT_EQ(u.requests.size(), 2u);
  EXPECT_EQ(u.requests[0].sampler, 1);
  EXPECT_EQ(u.requests[1].texture, 1);
  EXPECT_EQ(u.textures[0].params, t.textures[0].params);
  EXPECT_EQ(u.samplers[0].params, t.samplers[0].params);
}

TEST(Traces, OldTracesReadAsDescriptorZeroAndErrorsNameTheLine) {
  std::istringstream old("0.5,0.5\n0.6,0.5\n0.5,0.6\n0.6,0.6\n");
  const Trace t = parse_trace(old, "old.txt");
  for (const TraceRequest& r : t.requests) {
    EXPECT_EQ(r.texture, 0);
    EXPECT_EQ(r.sampler, 0);
  }
  const auto error = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parse_trace(in, "e.txt");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("# tfu-trace mode=quad fields=texture,s,t\n0,0,0\n1,0,0\n0,0,0\n0,0,0\n").find("e.txt:3: the four pixels of a quad"),
            std::string::npos);
  EXPECT_NE(error("# tfu-trace mode=quad fields=texture,s,q\n").find("e.txt:1: unknown field 'q'"), std::string::npos);
  EXPECT_NE(error("# tfu-trace mode=lod fields=s,t\n").find("needs the field 'lod'"), std::string::npos);
  EXPECT_NE(error("# tfu-trace mode=quad fields=texture,s,t\n5000,0,0\n").find("e.txt:2: field 1 '5000' is not an integer 0..4095"),
            std::string::npos);
  EXPECT_NE(error("# tfu-texture x proc:text\n").find("e.txt:1: index 'x'"), std::string::npos);
  EXPECT_NE(error("# tfu-sampler 0 filter\n").find("'filter' is not key=value"), std::string::npos);
}

TEST(Frame, FromTraceBindingsAndBsplineCoefficients) {
  std::istringstream in(
      "# tfu-trace mode=lod fields=texture,sampler,s,t,lod\n"
      "# tfu-texture 0 proc:noise:32\n"
      "# tfu-texture 1 proc:checkerboard:16 format=l8 layout=linear\n"
      "# tfu-sampler 0 filter=cubic_mipmap_linear kernel=bspline-interp wrap_s=clamp-to-edge\n"
      "# tfu-sampler 1 filter=linear\n"
      "0,0,0.3,0.4,0.5\n"
      "1,1,0.3,0.4,0.5\n"
      "0,1,0.7,0.4,0.5\n");
  Trace t = parse_trace(in, "f.txt");
  const Frame f = frame_from_trace(t, {});
  ASSERT_EQ(f.textures.size(), 3u);  // two bound, one coefficient texture
  EXPECT_EQ(f.regs.textures[1].format, TexelFormat::L8);
  EXPECT_EQ(f.regs.textures[1].layout, MemoryLayout::Linear);
  EXPECT_EQ(f.regs.textures[2].content, TextureContent::BsplineCoefficients);
  EXPECT_EQ(f.textures[2].coefficients_of, 0);
  EXPECT_EQ(t.requests[0].texture, 2);  // rebound to the coefficients
  EXPECT_EQ(t.requests[1].texture, 1);
  EXPECT_EQ(t.requests[2].texture, 0);  // texture 0 through a LINEAR sampler reads its texels
  const GoldenUnit g(f);
  for (size_t i = 0; i < t.requests.size(); ++i) (void)g.sample(t.requests[i], g.lambda(t, i));
  // The coefficient codes in memory are what the golden sampler computed.
  const Texture codes = read_texture(f.memory, f.regs.textures[2]);
  EXPECT_EQ(codes.levels[0].texels, g.sampler(2, 0).filtered_level(0).texels);
  // Errors name the binding.
  std::istringstream gap("# tfu-texture 1 proc:text\n0.5,0.5,0\n");
  Trace tg = parse_trace(gap, "g.txt");
  EXPECT_THROW(frame_from_trace(tg, {}), InputError);
  std::istringstream bad("# tfu-texture 0 proc:text:16 layot=tiled\n0.5,0.5,0\n");
  Trace tb = parse_trace(bad, "b.txt");
  try {
    frame_from_trace(tb, {});
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("b.txt:1: unknown texture key 'layot'"), std::string::npos) << e.what();
  }
}

// FrameBuilder places each texture object once; a texture the caller frees after adding it must
// never be taken for a later one allocated at the same address (it once was, when the builder
// keyed its placements by the caller's pointer and kept only a re-tiled copy).
TEST(Frame, TexturesFreedBetweenAddsAreNotTakenForEachOther) {
  for (int line : {64, 256, 1024}) {
    FrameBuilder b(line);
    for (int k = 0; k < 8; ++k) {
      // Same-sized objects, freed after each add (the builder keeps only its re-tiled copy when the
      // texture is tiled for another line size): an allocator reuses their addresses.
      auto t = std::make_shared<Texture>(make_procedural(k % 2 == 0 ? "checkerboard" : "lightmap", 64).texture);
      EXPECT_EQ(b.add_texture(t, {"test", {}}), k) << line;
      EXPECT_EQ(b.add_texture(t, {"test", {}}), k) << line;  // the same object again: the same index
    }
    const Frame f = b.frame();
    EXPECT_EQ(f.textures.size(), 8u);
  }
  // The trace that showed it: two procedural textures bound by a trace, at 256-byte lines.
  std::istringstream in(
      "# tfu-trace mode=lod fields=texture,sampler,s,t,lod\n"
      "# tfu-texture 0 proc:checkerboard:64\n"
      "# tfu-texture 1 proc:lightmap:64 mipmaps=none\n"
      "# tfu-sampler 0 filter=linear\n"
      "# tfu-sampler 1 filter=nearest\n"
      "0,0,0.3,0.4,0\n"
      "1,1,0.3,0.4,0\n");
  Trace t = parse_trace(in, "two.txt");
  const Frame f = frame_from_trace(t, {}, 256);
  EXPECT_EQ(f.textures.size(), 2u);
  EXPECT_EQ(t.requests[1].texture, 1);
}

TEST(TexEnv, DivisionFreeRoundingIsExact) {
  for (uint32_t x = 0; x <= 255u * 255u; ++x)
    ASSERT_EQ(div255_round(x), static_cast<uint32_t>(std::floor(x / 255.0 + 0.5))) << x;
}

TEST(TexEnv, IntegerCombineWithinHalfAnLsbOfTheRealOne) {
  std::mt19937 rng(4);
  for (int i = 0; i < 200000; ++i) {
    const Rgba8 p{static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
    const Rgba8 s{static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
    const StageCombine c{static_cast<TexEnv>(rng() % 4), 1 << (rng() % 3)};
    const Rgba8 got = combine_stage(p, s, c);
    const auto real = combine_stage(std::array<double, 4>{p.r / 255.0, p.g / 255.0, p.b / 255.0, p.a / 255.0},
                                    std::array<double, 4>{s.r / 255.0, s.g / 255.0, s.b / 255.0, s.a / 255.0}, c);
    const std::array<uint8_t, 4> g{got.r, got.g, got.b, got.a};
    for (size_t k = 0; k < 4; ++k) {
      // The product is rounded once; rgb_scale multiplies that rounded value (error x scale).
      const double tol = k < 3 ? 0.5 * c.rgb_scale + 1e-9 : 0.5 + 1e-9;
      ASSERT_LE(std::abs(g[k] - 255.0 * real[k]), tol) << tex_env_name(c.env) << " scale " << c.rgb_scale << " ch " << k;
    }
  }
  EXPECT_EQ(combine_stage(Rgba8{255, 255, 255, 255}, Rgba8{10, 20, 30, 40}, {TexEnv::Modulate, 1}), (Rgba8{10, 20, 30, 40}));
  EXPECT_EQ(combine_stage(Rgba8{200, 100, 50, 255}, Rgba8{128, 128, 128, 255}, {TexEnv::Modulate, 2}), (Rgba8{200, 100, 50, 255}));  // round(200 x 128 / 255) = 100, x 2
  EXPECT_EQ(combine_stage(Rgba8{200, 100, 0, 77}, Rgba8{100, 200, 255, 0}, {TexEnv::Decal, 1}), (Rgba8{200, 100, 0, 77}));
  EXPECT_EQ(combine_stage(Rgba8{200, 100, 0, 255}, Rgba8{100, 200, 255, 255}, {TexEnv::Add, 1}), (Rgba8{255, 255, 255, 255}));
}

TEST(Materials, SceneStagesAndSecondUvSet) {
  const Scene s = load_scene("lightmapped");
  ASSERT_EQ(s.meshes.size(), 3u);
  const Mesh& floor = s.meshes[0];
  ASSERT_EQ(floor.stages.size(), 2u);
  EXPECT_EQ(floor.stages[0].combine.env, TexEnv::Replace);
  EXPECT_EQ(floor.stages[1].combine.env, TexEnv::Modulate);
  EXPECT_EQ(floor.stages[1].combine.rgb_scale, 2);
  EXPECT_EQ(floor.stages[1].uv_set, 1);
  // The plane's base UVs repeat 8 x 16 times, its light-map UVs span it once.
  double umax = 0, u1max = 0;
  for (const Vertex& v : floor.vertices) {
    umax = std::max(umax, v.uv.x);
    u1max = std::max(u1max, v.uv1.x);
  }
  EXPECT_EQ(umax, 8.0);
  EXPECT_EQ(u1max, 1.0);
  const auto error = [](const std::string& mesh) {
    const std::string scene = R"({"meshes": [)" + mesh + "]}";
    try {
      parse_scene(scene, "m.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string quad = R"("primitive": "quad", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]])";
  EXPECT_NE(error("{" + quad + R"(, "stages": []})").find("m.json: meshes[0].stages: expected an array of 1..4 stages"),
            std::string::npos);
  EXPECT_NE(error("{" + quad + R"(, "stages": [{"texture": {"procedural": "text"}, "env": "blend"}]})")
                .find("meshes[0].stages[0].env: unknown texture environment 'blend'"),
            std::string::npos);
  EXPECT_NE(error("{" + quad + R"(, "texture": {"procedural": "text"}, "stages": [{"texture": {"procedural": "text"}}]})")
                .find("not both"),
            std::string::npos);
  EXPECT_NE(error("{" + quad + R"(, "stages": [{"texture": {"procedural": "text"}, "uv_set": 2}]})").find("uv_set: 2 outside 0..1"),
            std::string::npos);
}

// The image of a multitextured scene, composed from its traced requests, is the rendered image;
// and the cycle model equals the golden model on every request of every stage.
TEST(Materials, MultitexturedSceneThroughBothModels) {
  Scene s = load_scene("lightmapped");
  s.width = 128;
  s.height = 96;
  RenderOptions o;
  o.trace = true;
  o.threads = 1;
  const RenderResult r = render_scene(s, o);
  ASSERT_GT(r.quad_targets.size(), 100u);
  const GoldenUnit golden(r.frame->frame);
  std::vector<Rgba8> outputs(r.trace.requests.size());
  for (size_t i = 0; i < outputs.size(); ++i) outputs[i] = golden.sample(r.trace.requests[i], golden.lambda(r.trace, i));
  Image composed(s.width, s.height, Rgba8{0, 0, 0, 0});
  compose_quad_outputs(s, r.quad_targets, outputs, composed);
  for (size_t i = 0; i < composed.texels.size(); ++i)
    if (composed.texels[i] != Rgba8{0, 0, 0, 0}) {
      ASSERT_EQ(composed.texels[i], r.image.texels[i]) << i;
    }
  std::set<int> stages;
  for (const QuadTarget& t : r.quad_targets) stages.insert(t.stage);
  EXPECT_EQ(stages, (std::set<int>{0, 1}));
  for (const char* filter : {"LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR", "NEAREST"}) {
    o.filter = filter_mode_from_name(filter);
    const RenderResult rf = render_scene(s, o);
    const rtl::SceneSimResult sim = rtl::simulate_scene(s, rf, rtl::UnitConfig{}, {});
    EXPECT_TRUE(sim.mismatch.empty()) << filter << ": " << sim.mismatch;
    EXPECT_EQ(sim.image.texels, rf.image.texels) << filter;
    const sim::Stats::Table* st = sim.stats.table("stages");
    ASSERT_NE(st, nullptr);
    EXPECT_EQ(st->rows.size(), 2u);
    EXPECT_GE(sim.stats.table("textures")->rows.size(), 4u);  // checkerboard, text, two light maps
  }
}

}  // namespace
}  // namespace tfu
