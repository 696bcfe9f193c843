// Input and output files: every input must be a regular file of bounded size (a
// directory, FIFO or device is refused without hanging), and every output goes through
// OutputFiles: distinct files by canonical path and identity, nothing overwritten without force,
// streams checked after writing and closing, temporaries renamed on commit and removed on failure.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "testbench/input_error.hpp"
#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/run_files.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

// A fresh, empty scratch directory per test.
fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d = fs::temp_directory_path() / fmt::format("tfu_io_files_{}_{}_{}", ::getpid(), info->test_suite_name(), info->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// Names of the entries of a directory (recursive), sorted.
std::vector<std::string> entries(const fs::path& d) {
  std::vector<std::string> v;
  for (const auto& e : fs::recursive_directory_iterator(d)) v.push_back(fs::relative(e.path(), d).string());
  std::sort(v.begin(), v.end());
  return v;
}

// ---- Inputs ----

TEST(InputFiles, DirectoriesDevicesAndFifosAreRefusedWithoutReading) {
  const fs::path d = scratch_dir();
  const fs::path fifo = d / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Nobody writes to the FIFO: an open() without O_NONBLOCK or a read would hang this test.
  EXPECT_NE(input_error([&] { load_trace(fifo.string()); }).find("is a named pipe (FIFO), not a regular file"),
            std::string::npos);
  EXPECT_NE(input_error([&] { load_texture(fifo.string()); }).find("named pipe"), std::string::npos);
  EXPECT_NE(input_error([&] { load_scene(fifo.string()); }).find("named pipe"), std::string::npos);
  EXPECT_NE(input_error([&] { read_input_file(fifo.string(), "x", 100); }).find("x: is a named pipe"), std::string::npos);
  EXPECT_NE(input_error([&] { load_trace(d.string()); }).find("is a directory, not a file"), std::string::npos);
  EXPECT_NE(input_error([&] { load_trace("/dev/zero"); }).find("is a character device"), std::string::npos);
  EXPECT_NE(input_error([&] { load_image("/dev/null"); }).find("is a character device"), std::string::npos);
  EXPECT_NE(input_error([&] { load_trace((d / "missing.txt").string()); }).find("no such file"), std::string::npos);
  EXPECT_NE(input_error([&] { load_trace((d / std::string(300, 'a')).string()); }).find("file name too long"),
            std::string::npos);
}

TEST(InputFiles, SizeIsBoundedBeforeAndWhileReading) {
  const fs::path d = scratch_dir();
  write_text(d / "ten.txt", "0123456789");
  EXPECT_EQ(read_input_file((d / "ten.txt").string(), "ten", 10), "0123456789");
  EXPECT_NE(input_error([&] { read_input_file((d / "ten.txt").string(), "ten", 9); }).find("ten: larger than the limit of 9 bytes"),
            std::string::npos);
  // /proc files report size 0 but have content: the bound holds while reading.
  const std::string maps = read_input_file("/proc/self/maps", "maps", kMaxTextInputBytes);
  EXPECT_GT(maps.size(), 0u);
  EXPECT_NE(input_error([&] { read_input_file("/proc/self/maps", "maps", 16); }).find("larger than the limit of 16 bytes"),
            std::string::npos);
  // Through a stream (the trace reader): the error comes out of the read, not as a short file.
  InputFile f("/proc/self/maps", "maps", 16);
  std::string line;
  EXPECT_THROW(
      while (std::getline(f.stream(), line)) {}, InputError);
}

// The Python scripts' input checks (scripts/tfu_inputs.py) use the same bound for text inputs.
TEST(InputFiles, ThePythonScriptsShareTheTextInputBound) {
  std::ifstream f(std::string(TFU_DOCS_DIR) + "/../scripts/tfu_inputs.py");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const std::string line = "\nMAX_TEXT_INPUT_BYTES = 64 << 20\n";
  EXPECT_NE(text.find(line), std::string::npos) << "scripts/tfu_inputs.py lost its MAX_TEXT_INPUT_BYTES line";
  EXPECT_EQ(kMaxTextInputBytes, uint64_t{64} << 20) << "change scripts/tfu_inputs.py's MAX_TEXT_INPUT_BYTES with it";
}

// ---- Outputs ----

TEST(OutputFiles, CommitRenamesCompleteFilesAndLeavesNoTemporaries) {
  const fs::path d = scratch_dir();
  {
    OutputFiles out(false);
    out.add("--a", (d / "a.txt").string()).stream() << "alpha\n";
    out.add("--b", (d / "sub" / "deeper" / "b.txt").string()).stream() << "beta\n";
    out.add_image("--c", (d / "c.png").string()).write_image(Image(3, 2, Rgba8{1, 2, 3, 4}));
    out.add("--unused", (d / "unused.txt").string());  // reserved but never written: not created
    // Before the commit: four temporaries (one per output) and the two new directories.
    EXPECT_EQ(entries(d).size(), 6u);
    for (const std::string& e : entries(d))
      EXPECT_TRUE(e == "sub" || e == "sub/deeper" || e.find(".tfu-") != std::string::npos) << e;
    out.commit();
  }
  EXPECT_EQ(entries(d), (std::vector<std::string>{"a.txt", "c.png", "sub", "sub/deeper", "sub/deeper/b.txt"}));
  EXPECT_EQ(read_text(d / "a.txt"), "alpha\n");
  EXPECT_EQ(read_text(d / "sub" / "deeper" / "b.txt"), "beta\n");
  EXPECT_EQ(load_image((d / "c.png").string()).texels, Image(3, 2, Rgba8{1, 2, 3, 4}).texels);
}

TEST(OutputFiles, AFailedRunLeavesNothingBehind) {
  const fs::path d = scratch_dir();
  try {
    OutputFiles out(false);
    out.add("--vcd", (d / "t.vcd").string()).stream() << "$timescale 1ns $end\n";
    out.add("--out", (d / "new" / "dir" / "x.png").string());
    throw InputError("the texture is truncated");
  } catch (const InputError&) {
  }
  EXPECT_TRUE(entries(d).empty()) << fmt::format("{}", fmt::join(entries(d), " "));
  // So the rerun is not refused.
  OutputFiles again(false);
  EXPECT_NO_THROW(again.add("--vcd", (d / "t.vcd").string()));
}

TEST(OutputFiles, ExistingFilesNeedForceAndOnlyRegularFilesAreReplaced) {
  const fs::path d = scratch_dir();
  write_text(d / "old.txt", "old");
  {
    OutputFiles out(false);
    EXPECT_NE(input_error([&] { out.add("--out", (d / "old.txt").string()); }).find("already exists (pass --force"),
              std::string::npos);
  }
  EXPECT_EQ(read_text(d / "old.txt"), "old");
  {
    OutputFiles out(true);
    out.add("--out", (d / "old.txt").string()).stream() << "new";
    out.commit();
  }
  EXPECT_EQ(read_text(d / "old.txt"), "new");
  OutputFiles out(true);
  EXPECT_NE(input_error([&] { out.add("--vcd", "/dev/full"); }).find("exists and is a character device"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--out", d.string()); }).find("exists and is a directory"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--out", (d / "x" / "").string()); }).find("names a directory"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--out", ""); }).find("--out: empty file name"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--out", (d / std::string(256, 'n')).string()); }).find("longer than 255 bytes"),
            std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--out", "/proc/no-such-dir/x.txt"); }).find("cannot create directory '/proc/no-such-dir'"),
            std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--json", "/proc/x.json"); }).find("cannot create a file in '/proc'"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add_image("--out", (d / "x.nosuchformat").string()); }).find("no image writer"),
            std::string::npos);
}

TEST(OutputFiles, TheSameFileUnderTwoNamesIsRefused) {
  const fs::path d = scratch_dir();
  const fs::path cwd = fs::current_path();
  fs::current_path(d);
  OutputFiles out(true);
  out.add("--out", "a.png");
  EXPECT_NE(input_error([&] { out.add("--trace-out", "./a.png"); }).find("is the same file as --out 'a.png'"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--x", (d / "a.png").string()); }).find("same file"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--x", "/" + (d / "a.png").string()); }).find("same file"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--x", "sub/../a.png"); }).find("same file"), std::string::npos);
  // An existing file under another name: a hard link and a symbolic link.
  write_text(d / "target.txt", "t");
  fs::create_hard_link(d / "target.txt", d / "hard.txt");
  fs::create_symlink(d / "target.txt", d / "soft.txt");
  out.add("--stats", "target.txt");
  EXPECT_NE(input_error([&] { out.add("--x", "hard.txt"); }).find("same file"), std::string::npos);
  EXPECT_NE(input_error([&] { out.add("--x", "soft.txt"); }).find("same file"), std::string::npos);
  fs::current_path(cwd);
}

// An output never replaces an input of the same run (cmodel/run_files.hpp, on as in tfu's main()):
// an input under any of its names is refused as an output, even with --force, and an input that
// is a pending output is refused as an input; once committed, an output may be read.
TEST(RunFiles, AnOutputNeverReplacesAnInput) {
  const fs::path d = scratch_dir();
  write_text(d / "scene.json", "{}");
  fs::create_hard_link(d / "scene.json", d / "hard.json");
  track_run_files(true);
  (void)read_input_file((d / "scene.json").string(), "scene 'scene.json'", 100);
  {
    OutputFiles out(true);
    for (const fs::path& p : {d / "scene.json", d / "." / "scene.json", d / "hard.json"})
      EXPECT_EQ(input_error([&] { out.add("--stats", p.string()); }),
                fmt::format("--stats '{}' is also an input of this run (scene 'scene.json'); an output never replaces an "
                            "input, even with --force",
                            p.string()));
    out.add("--out", (d / "out.txt").string()).stream() << "x";
    write_text(d / "out.txt", "old");
    EXPECT_EQ(input_error([&] { (void)read_input_file((d / "out.txt").string(), "--config 'out.txt'", 100); }),
              fmt::format("--config 'out.txt' is also an output of this run (--out '{}'); an output never replaces an "
                          "input, even with --force",
                          (d / "out.txt").string()));
    out.commit();
  }
  EXPECT_EQ(read_input_file((d / "out.txt").string(), "out", 100), "x");  // committed: an input like any other
  EXPECT_EQ(read_text(d / "scene.json"), "{}");
  track_run_files(false);
  // Off (a library user's default): nothing is refused.
  OutputFiles out(true);
  out.add("--stats", (d / "scene.json").string());
}

TEST(OutputFiles, AFileThatAppearsDuringTheRunIsNotReplacedWithoutForce) {
  const fs::path d = scratch_dir();
  OutputFiles out(false);
  out.add("--out", (d / "late.txt").string()).stream() << "ours";
  write_text(d / "late.txt", "theirs");
  EXPECT_NE(input_error([&] { out.commit(); }).find("appeared while tfu ran"), std::string::npos);
  EXPECT_EQ(read_text(d / "late.txt"), "theirs");
}

// A write error that only shows when the stream is flushed or closed. RLIMIT_FSIZE makes every
// write beyond 1000 bytes fail with EFBIG (SIGXFSZ ignored), as a full disk would.
TEST(OutputFiles, AWriteFailureIsReportedAtCommitAndNothingIsLeft) {
  const fs::path d = scratch_dir();
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = ::signal(SIGXFSZ, SIG_IGN);
  std::string message;
  {
    OutputFiles out(false);
    OutputFile& f = out.add("--vcd", (d / "big.vcd").string());
    struct rlimit small = old;
    small.rlim_cur = 1000;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    f.stream() << std::string(100000, 'x');
    message = input_error([&] { out.commit(); });
    ::setrlimit(RLIMIT_FSIZE, &old);
  }
  ::signal(SIGXFSZ, old_handler);
  EXPECT_NE(message.find("--vcd '"), std::string::npos) << message;
  EXPECT_NE(message.find("write failed: File too large"), std::string::npos) << message;
  EXPECT_TRUE(entries(d).empty());
}

}  // namespace
}  // namespace tfu
