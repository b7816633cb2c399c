#include "glint/core/error.h"
#include "glint/core/cache.h"
#include "glint/core/file.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace glint;

namespace {
fs::path freshDir(const char* name) {
  fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "core" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}
}  // namespace

TEST(Error, ExitCodesAreDistinctPerKind) {
  EXPECT_EQ(exitCode(ErrorKind::Usage), 2);
  EXPECT_EQ(exitCode(ErrorKind::Input), 3);
  EXPECT_EQ(exitCode(ErrorKind::Output), 4);
  EXPECT_EQ(exitCode(ErrorKind::NoGpu), 5);
  try {
    fail(ErrorKind::Input, "cannot read '{}'", "x.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_STREQ(e.what(), "cannot read 'x.png'");
  }
}

TEST(AtomicWrite, WritesAndReplacesWholeFiles) {
  const auto dir = freshDir("replace");
  const auto file = dir / "a.txt";
  writeTextAtomically(file, "first");
  EXPECT_EQ(readTextFile(file), "first");
  writeTextAtomically(file, "second");
  EXPECT_EQ(readTextFile(file), "second");
  // Only the destination remains: no temporaries left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicWrite, FailingWriterLeavesNothingAndKeepsTheOldFile) {
  const auto dir = freshDir("failing");
  const auto file = dir / "keep.txt";
  writeTextAtomically(file, "precious");
  EXPECT_THROW(writeAtomically(file,
                               [](const fs::path& tmp) {
                                 std::ofstream(tmp) << "half";
                                 throw Error(ErrorKind::Internal, "boom");
                               }),
               Error);
  EXPECT_EQ(readTextFile(file), "precious");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicWrite, TemporaryKeepsTheExtensionForFormatDetection) {
  const auto dir = freshDir("ext");
  fs::path seen;
  writeAtomically(dir / "x.png", [&](const fs::path& tmp) {
    seen = tmp;
    std::ofstream(tmp) << "data";
  });
  EXPECT_EQ(seen.extension(), ".png");
  EXPECT_EQ(seen.parent_path(), dir);
}

TEST(AtomicWrite, MissingDirectoryIsAnOutputError) {
  try {
    writeTextAtomically("/nonexistent-glint-dir/x.txt", "x");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

TEST(AtomicWrite, UnwritableDirectoryIsAnOutputError) {
  if (geteuid() == 0) GTEST_SKIP() << "root can write into read-only directories";
  const auto dir = freshDir("readonly");
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_THROW(writeTextAtomically(dir / "x.txt", "x"), Error);
  fs::permissions(dir, fs::perms::owner_all);
}

TEST(ReadTextFile, MissingFileIsAnInputError) {
  try {
    readTextFile("/nonexistent-glint-file");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
  }
}

#include "glint/core/text.h"

TEST(Text, EscapesHtml) {
  EXPECT_EQ(escapeHtml("<a href=\"x\">&</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&lt;/a&gt;");
}

TEST(Text, ShardIsTwoPlainIntegersInOrder) {
  const ShardSpec part = parseShard("2/8", "--shard");
  EXPECT_EQ(part.index, 2);
  EXPECT_EQ(part.count, 8);
  EXPECT_EQ(parseShard("1/1", "--shard").count, 1);
  // sscanf("%d/%d") took the first three (leading blanks, a sign); nothing else may pass.
  for (const char* bad : {" 1/2", "+1/2", "1/ 2", "1/2 ", "1/2x", "1 /2", "0/2", "3/2", "-1/2", "1/0", "1/-2", "1",
                          "/2", "1/", "1//2", "1/2/3", "", "1.0/2", "99999999999/2"}) {
    try {
      parseShard(bad, "--shard");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage) << bad;
      EXPECT_NE(std::string(e.what()).find("--shard must be i/n"), std::string::npos) << e.what();
    }
  }
}

TEST(Text, FrameRangeIsFirstColonEndEitherSideOptional) {
  // `glint post --frames` and `glint render --frames` share this parser.
  const FrameRange part = parseFrameRange("150:300", "--frames");
  EXPECT_EQ(part.first, 150);
  EXPECT_EQ(part.end, 300);
  EXPECT_EQ(parseFrameRange("250:", "--frames").end, -1);  // to the end
  EXPECT_EQ(parseFrameRange(":9", "--frames").first, 0);
  EXPECT_EQ(parseFrameRange("9:3", "--frames").end, 3);  // empty ranges are the caller's to refuse
  for (const char* bad : {"", "12", "0-3", "-1:3", "+1:3", "1:2:3", "a:b", " 1:2", "1:2 ", "99999999999:"}) {
    try {
      parseFrameRange(bad, "--frames");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage) << bad;
      EXPECT_NE(std::string(e.what()).find("--frames"), std::string::npos) << e.what();
    }
  }
}

#include "glint/core/locations.h"

#include <cstdlib>
#include <string>

namespace {
// Sets GLINT_DATA_DIR for one scope (each ctest test runs in its own process, but the
// variable is restored anyway).
class DataDirOverride {
public:
  explicit DataDirOverride(const fs::path& dir) { setenv("GLINT_DATA_DIR", dir.c_str(), 1); }
  ~DataDirOverride() { unsetenv("GLINT_DATA_DIR"); }
};
}  // namespace

TEST(Locations, GlintDataDirIsTheOnlyPlaceWhenSet) {
  const fs::path dir = freshDir("data-override");
  fs::create_directories(dir / "env");
  writeTextAtomically(dir / "env" / "x.exr", "not really an EXR");
  DataDirOverride override(dir);
  ASSERT_EQ(dataDirectories(), std::vector<fs::path>{dir});
  EXPECT_EQ(findDataFile("env/x.exr", "environment 'x'"), dir / "env" / "x.exr");
  try {
    findDataFile("bunny/bunny.ply", "the Stanford bunny");  // exists in glint's data, not here
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("the Stanford bunny not found: no bunny/bunny.ply in GLINT_DATA_DIR=" + dir.string()),
              std::string::npos) << e.what();
  }
}

TEST(Locations, AnInstalledLayoutBesideTheExecutableComesFirstAndErrorsListEveryPlace) {
  unsetenv("GLINT_DATA_DIR");
  const std::vector<fs::path> dirs = dataDirectories();
  ASSERT_GE(dirs.size(), 2u);
  // The tests run from build/tests/core: <exe>/../share/glint is where an installed
  // glint command keeps its data (GNUInstallDirs' default layout).
  EXPECT_EQ(dirs[0], (executablePath().parent_path() / ".." / "share" / "glint").lexically_normal());
  try {
    findDataFile("env/no-such-file.exr", "environment 'no-such-file'");
    FAIL();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    for (const fs::path& dir : dirs) EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
    EXPECT_NE(message.find("scripts/setup"), std::string::npos) << message;
  }
}

// Every test process runs cold, as on a fresh machine (tests/support/cold_environment.cpp):
// no Mesa shader cache, and cache directories of the build tree's, not the user's.
TEST(ColdRun, TestsRunWithoutAShaderCacheAndWithTheBuildTreesCacheDirectories) {
  const char* mesa = std::getenv("MESA_SHADER_CACHE_DISABLE");
  ASSERT_NE(mesa, nullptr);
  EXPECT_STREQ(mesa, "true");
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* glintCache = std::getenv("GLINT_CACHE_DIR");
  ASSERT_NE(xdg, nullptr);
  ASSERT_NE(glintCache, nullptr);
  const std::string outputDir = GLINT_TEST_OUTPUT_DIR;
  const std::string buildTree = outputDir.substr(0, outputDir.rfind('/'));  // <build>/test-output → <build>
  EXPECT_EQ(std::string(xdg), buildTree + "/test-home/cache");
  EXPECT_EQ(std::string(glintCache), buildTree + "/cache");
  EXPECT_EQ(glint::cacheDirectory(), std::filesystem::path(buildTree + "/cache"));
}

// ------------------------------------------------------------------ the promise's check
// An output is never an input, nor another output: by file identity, so a hard link, a
// symbolic link or another spelling of the same file counts. Stdout ("-") can be used once.
namespace {
std::string refusalOf(const std::vector<glint::FileUse>& inputs, const std::vector<glint::FileUse>& outputs) {
  try {
    glint::checkDistinctFiles(inputs, outputs);
  } catch (const glint::Error& e) {
    EXPECT_EQ(e.kind(), glint::ErrorKind::Usage);
    return e.what();
  }
  return {};
}
}  // namespace

TEST(DistinctFiles, AnOutputThatIsAnInputByAnyNameIsRefused) {
  const std::filesystem::path d = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "core" / "distinct";
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d / "sub");
  std::ofstream(d / "in.png") << "input";
  std::filesystem::create_hard_link(d / "in.png", d / "hard.png");
  std::filesystem::create_symlink(d / "in.png", d / "soft.png");
  const std::vector<glint::FileUse> inputs{{d / "in.png", "the input"}};
  for (const std::filesystem::path& same : {d / "in.png", d / "hard.png", d / "soft.png", d / "sub" / ".." / "in.png",
                                            d / "." / "in.png"}) {
    const std::string message = refusalOf(inputs, {{same, "-o"}});
    EXPECT_NE(message.find("-o '" + same.string() + "' is the input '" + (d / "in.png").string() +
                           "': writing it would destroy the input"), std::string::npos) << same << ": " << message;
  }
  EXPECT_EQ(refusalOf(inputs, {{d / "out.png", "-o"}, {d / "report.json", "--json"}, {"-", "--json"}}), "");
  EXPECT_EQ(refusalOf({{"-", "the input"}}, {{"-", "-o"}}), "") << "stdin in, stdout out";
  // Two outputs, one file: existing or not yet.
  EXPECT_NE(refusalOf(inputs, {{d / "m.png", "-o"}, {d / "sub" / ".." / "m.png", "--ao"}}).find(
                "-o '" + (d / "m.png").string() + "' and --ao '"), std::string::npos);
  std::ofstream(d / "old.png") << "old";
  std::filesystem::create_hard_link(d / "old.png", d / "old-link.png");
  EXPECT_NE(refusalOf(inputs, {{d / "old.png", "-o"}, {d / "old-link.png", "--height"}}).find("are the same file"),
            std::string::npos);
  EXPECT_NE(refusalOf(inputs, {{"-", "-o"}, {"-", "--json"}}).find("both write to stdout"), std::string::npos);
  EXPECT_EQ(refusalOf(inputs, {{"", "--ao"}, {"", "--height"}}), "") << "options not given";
}

#include "glint/core/progress.h"

TEST(Progress, TheEtaIsTheLinearEstimateOfWhatIsLeft) {
  EXPECT_EQ(glint::etaText(0, 100, 3.0), "");   // nothing done yet: no estimate
  EXPECT_EQ(glint::etaText(10, 0, 3.0), "");    // unknown total (a live source)
  EXPECT_EQ(glint::etaText(100, 100, 3.0), ""); // done
  EXPECT_EQ(glint::etaText(25, 100, 10.0), "ETA 30 s");
  EXPECT_EQ(glint::etaText(1, 100, 2.0), "ETA 3:18");
  EXPECT_EQ(glint::etaText(1, 1000, 10.0), "ETA 2:46:30");
}
