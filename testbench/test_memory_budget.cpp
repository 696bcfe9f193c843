// The run's memory budget (cmodel/memory_budget.hpp; TFU-S E11): sizes parsed, the MIP chain's bytes
// by hand, charges refused before the allocation with one line naming the input and the figures,
// and given back when what they pay for goes; a file texture, a procedural texture and a trace
// each charged before they are decoded or read.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "cmodel/bindings.hpp"
#include "cmodel/error.hpp"
#include "cmodel/memory_budget.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"

namespace tfu {
namespace {

// Each test sets the budget it needs and puts the default back.
class Budget {
 public:
  explicit Budget(uint64_t bytes) { set_memory_budget(bytes); }
  ~Budget() { set_memory_budget(default_memory_budget()); }
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MemoryBudget, SizesAndTheMipChainByHand) {
  EXPECT_EQ(parse_memory_size("8G", "--memory-budget"), uint64_t{8} << 30);
  EXPECT_EQ(parse_memory_size("512M", "--memory-budget"), uint64_t{512} << 20);
  EXPECT_EQ(parse_memory_size("64KiB", "--memory-budget"), uint64_t{64} << 10);
  EXPECT_EQ(parse_memory_size("1T", "--memory-budget"), uint64_t{1} << 40);
  EXPECT_EQ(parse_memory_size("1000", "--memory-budget"), 1000u);
  for (const char* bad : {"", "8x", "G", "-1", "1.5G", "8 G", "99999999999999999999", "16777216T"})
    EXPECT_EQ(error_of([&] { (void)parse_memory_size(bad, "--memory-budget"); }).find("--memory-budget: '"), 0u) << bad;
  EXPECT_EQ(error_of([] { (void)parse_memory_size("0", "--memory-budget"); }), "--memory-budget: the memory budget must be more than 0 bytes");
  // 4 bytes per texel of every level down to 1x1
  EXPECT_EQ(mip_chain_bytes(1, 1), 4u);
  EXPECT_EQ(mip_chain_bytes(2, 2), 4u * (4 + 1));
  EXPECT_EQ(mip_chain_bytes(4, 1), 4u * (4 + 2 + 1));
  EXPECT_EQ(mip_chain_bytes(256, 256), 349524u);  // 4 (4^9 - 1) / 3
  EXPECT_EQ(mip_chain_bytes(16384, 16384), uint64_t{1431655764});
  EXPECT_EQ(memory_size_text(1536), "1.5 KiB");
  EXPECT_EQ(memory_size_text(uint64_t{3} << 29), "1.5 GiB");
  EXPECT_GT(default_memory_budget(), 0u);
}

TEST(MemoryBudget, AChargeBeyondTheBudgetIsRefusedAndChargesAreGivenBack) {
  const uint64_t base = memory_in_use();
  const Budget budget(base + 1000);
  {
    MemoryCharge a(600, "'a.png'", "decoded texels");
    EXPECT_EQ(memory_in_use(), base + 600);
    const std::string e = error_of([] { MemoryCharge b(500, "'b.png'", "decoded texels"); });
    EXPECT_EQ(e.find("'b.png': decoded texels of about 500 bytes would pass the memory budget of"), 0u) << e;
    EXPECT_EQ(memory_in_use(), base + 600);  // the refused charge holds nothing
    a.add(400);                              // exactly the budget
    EXPECT_THROW(a.add(1), InputError);
    EXPECT_EQ(a.bytes(), 1000u);
  }
  EXPECT_EQ(memory_in_use(), base);
}

TEST(MemoryBudget, TexturesAreChargedBeforeTheyAreDecoded) {
  const TempDir tmp("tfu-test-budget");
  const std::string png = (tmp.path() / "wide.png").string();
  write_image_file(Image(512, 512, {10, 20, 30, 255}), png, png);
  const uint64_t base = memory_in_use();
  {
    const Budget budget(base + mip_chain_bytes(512, 512));
    const LoadedTexture t = load_texture_spec({png, {}}, "s.json: meshes[0].texture.file");
    EXPECT_EQ(memory_in_use(), base + mip_chain_bytes(512, 512));  // level 0 read, the chain generated: one charge
    const Texture copy = *t.texture;                                // a copy shares the charge
    EXPECT_EQ(copy.memory, t.texture->memory);
    const std::string e = error_of([&] { (void)load_texture_spec({png, {{"format", "l8"}}}, "s.json: meshes[1].texture.file"); });
    EXPECT_EQ(e.find("s.json: meshes[1].texture.file: " + png + ": decoded texels of about 1.3 MiB would pass the memory budget"), 0u)
        << e;
    const std::string p = error_of([] { (void)load_texture_spec({"proc:noise:64", {}}, "--texture"); });
    EXPECT_EQ(p.find("--texture: texture 'proc:noise:64': decoded texels of about 21.3 KiB"), 0u) << p;
  }
  EXPECT_EQ(memory_in_use(), base);
}

TEST(MemoryBudget, TracesAreChargedAsTheirRequestsAreRead) {
  std::string text = "# tfu-trace mode=lod fields=s,t,lod\n";
  for (int i = 0; i < 5000; ++i) text += "0.5,0.5,0\n";
  const uint64_t base = memory_in_use();
  {
    const Budget budget(base + 4096 * sizeof(TraceRequest));  // the first block, not the second
    std::istringstream in(text);
    const std::string e = error_of([&] { (void)parse_trace(in, "t.txt"); });
    EXPECT_EQ(e.find("trace t.txt: requests of about"), 0u) << e;
  }
  {
    const Budget budget(base + 8192 * sizeof(TraceRequest));
    std::istringstream in(text);
    const Trace tr = parse_trace(in, "t.txt");
    EXPECT_EQ(tr.requests.size(), 5000u);
    EXPECT_EQ(memory_in_use(), base + 8192 * sizeof(TraceRequest));
    EXPECT_EQ(tr.memory->bytes(), tr.requests.capacity() * sizeof(TraceRequest));
  }
  EXPECT_EQ(memory_in_use(), base);
}

}  // namespace
}  // namespace tfu
