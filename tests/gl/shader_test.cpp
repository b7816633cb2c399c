// GL tier: the shader loader — includes, defines, error messages with file and line.
#include "support/gl_test.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/gl/shader.h"

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;
using glint::testing::GlTest;

namespace {
// Points the loader at a temporary shader tree for one test.
class ShaderDir {
public:
  explicit ShaderDir(const char* name) : m_dir(fs::path(GLINT_TEST_OUTPUT_DIR) / "shaders" / name) {
    fs::remove_all(m_dir);
    fs::create_directories(m_dir / "common");
    gl::ShaderSources::setDirectory(m_dir);
  }
  ~ShaderDir() { gl::ShaderSources::setDirectory({}); }
  void write(const std::string& rel, const std::string& text) const { writeTextAtomically(m_dir / rel, text); }

private:
  fs::path m_dir;
};

const char* kOkFrag = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1); }\n";
}  // namespace

TEST(ShaderLog, MapsMesaAndNvidiaLinesToFiles) {
  const std::vector<std::string> files = {"a/main.frag", "common/lib.glsl"};
  EXPECT_EQ(gl::mapShaderLog("0:100007(12): error: `x' undeclared\n", files),
            "shaders/common/lib.glsl:7: error: `x' undeclared\n");
  EXPECT_EQ(gl::mapShaderLog("0(3) : error C1008: undefined variable \"y\"\n", files),
            "shaders/a/main.frag:3: error C1008: undefined variable \"y\"\n");
}

TEST(ShaderPreprocess, ExpandsIncludesOnceAndKeepsLineNumbers) {
  ShaderDir dir("preprocess");
  dir.write("common/lib.glsl", "float f() { return 1.0; }\n");
  dir.write("x.frag", "#version 450 core\n#include \"common/lib.glsl\"\n#include \"common/lib.glsl\"\nvoid main() {}\n");
  const auto pre = gl::preprocessShader("x.frag", {"FOO 2"});
  EXPECT_EQ(pre.files, (std::vector<std::string>{"x.frag", "common/lib.glsl"}));
  EXPECT_EQ(pre.source.rfind("#version 450 core\n#define FOO 2\n#line 2\n", 0), 0u) << pre.source;
  EXPECT_NE(pre.source.find("#line 100001\nfloat f()"), std::string::npos) << pre.source;
  // Included once (pragma-once semantics), and the line after the include is numbered right.
  EXPECT_EQ(pre.source.find("float f()"), pre.source.rfind("float f()"));
  EXPECT_NE(pre.source.find("#line 4\nvoid main"), std::string::npos) << pre.source;
}

TEST_F(GlTest, CompileErrorNamesFileAndLine) {
  allowGlErrors();  // the driver reports the failed compile through the debug callback too
  ShaderDir dir("errors");
  dir.write("common/lib.glsl", "vec4 helper() {\n  return undefinedThing;\n}\n");
  dir.write("bad.frag", "#version 450 core\n#include \"common/lib.glsl\"\nout vec4 c;\nvoid main() { c = helper(); }\n");
  dir.write("fs.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n");
  try {
    gl::Program::fromFiles({"fs.vert", "bad.frag"});
    FAIL() << "expected a compile error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("shaders/common/lib.glsl:2:", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
}

TEST_F(GlTest, DefinesSelectCodeAndUniformsAreSet) {
  ShaderDir dir("defines");
  dir.write("v.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n");
  dir.write("f.frag", "#version 450 core\nuniform float uValue;\nout vec4 c;\n"
                      "void main() {\n#ifdef RED\n c = vec4(uValue, 0, 0, 1);\n#else\n c = vec4(0);\n#endif\n}\n");
  auto program = gl::Program::fromFiles({"v.vert", "f.frag"}, {"RED"});
  EXPECT_GE(program.uniformLocation("uValue"), 0);
  program.set("uValue", 0.5f);
  float value = 0;
  glGetUniformfv(program.id(), program.uniformLocation("uValue"), &value);
  EXPECT_FLOAT_EQ(value, 0.5f);
  // Without RED the uniform is unused and optimised away.
  auto plain = gl::Program::fromFiles({"v.vert", "f.frag"});
  EXPECT_EQ(plain.uniformLocation("uValue"), -1);
}

TEST_F(GlTest, CachedUniformLocationsAreGlsOwn) {
  ShaderDir dir("locations");
  dir.write("v.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n");
  dir.write("f.frag", "#version 450 core\nstruct Light { vec3 position; float power; };\n"
                      "uniform Light uLights[2];\nuniform float uWeights[3];\nuniform mat4 uMatrix;\nout vec4 c;\n"
                      "void main() { c = vec4(uLights[0].position * uLights[1].power, uWeights[0] + uWeights[2]) "
                      "* uMatrix; }\n");
  const auto program = gl::Program::fromFiles({"v.vert", "f.frag"});
  // The locations read once after linking, and those asked on demand, are GL's own.
  for (const char* name : {"uLights[0].position", "uLights[1].power", "uWeights", "uWeights[0]", "uWeights[2]",
                           "uMatrix", "uMissing"}) {
    EXPECT_EQ(program.uniformLocation(name), glGetUniformLocation(program.id(), name)) << name;
    EXPECT_EQ(program.uniformLocation(name), glGetUniformLocation(program.id(), name)) << name << " (cached)";
  }
  EXPECT_GE(program.uniformLocation("uWeights[2]"), 0);
  EXPECT_EQ(program.uniformLocation("uMissing"), -1);
}

TEST_F(GlTest, MissingShaderAndUnknownStageAreErrors) {
  allowGlErrors();
  EXPECT_THROW(gl::Program::fromFiles({"does/not/exist.vert"}), Error);
  ShaderDir dir("stage");
  dir.write("x.txt", kOkFrag);
  EXPECT_THROW(gl::Program::fromFiles({"x.txt"}), Error);
}

TEST_F(GlTest, EveryEmbeddedShaderHasAVersionLine) {
  for (const auto& path : gl::ShaderSources::list()) {
    if (gl::shaderStageForPath(path) == 0) continue;  // .glsl include files
    EXPECT_EQ(gl::ShaderSources::read(path).rfind("#version 450", 0), 0u) << path;
  }
}
