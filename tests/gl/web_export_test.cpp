// The browser viewer's export (viewer/web_export.hpp, docs/WEB.md). Its programs are the desktop
// programs' sources line for line under the GLSL ES prelude, so the two cannot drift, and they
// compile as GLSL ES 3.00 (OSMesa accepts "#version 300 es"); the export writes every file of web/
// as it is on disk, and the generated module holds exactly the assembled programs. The page itself
// runs in headless Chromium in tests/web.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include <nut/png_io.hpp>
#include <viewer/context.hpp>
#include <viewer/hni_renderer.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/shader_library.hpp>
#include <viewer/web_export.hpp>

namespace nut {
namespace {

struct NamedSpec {
  const char* name;  // its key in js/generated.js
  viewer::ProgramSpec spec;
};

std::vector<NamedSpec> webPrograms() {
  return {{"hniHeuristic", viewer::hniRayCasterSpec(Lookup::Heuristic)},
          {"hniExact", viewer::hniRayCasterSpec(Lookup::Exact)},
          {"mesh", viewer::meshProgramSpec()}};
}

std::string withoutLines(const std::string& text, int lines) {
  std::size_t at = 0;
  for (int i = 0; i < lines; ++i) at = text.find('\n', at) + 1;
  return text.substr(at);
}

// The programs object of js/generated.js ("export const programs = {...};").
nlohmann::json generatedPrograms() {
  auto module = viewer::generatedWebModule(viewer::ShaderLibrary{});
  EXPECT_TRUE(module.ok()) << module.error().message;
  const std::string prefix = "export const programs = ";
  const std::size_t begin = module->find(prefix) + prefix.size();
  const std::size_t end = module->find(";\n\nexport const constants = ");
  return nlohmann::json::parse(module->substr(begin, end - begin));
}

TEST(WebExport, ProgramsAreTheDesktopSourcesUnderTheEsPrelude) {
  const viewer::ShaderLibrary library;
  const nlohmann::json generated = generatedPrograms();
  for (const NamedSpec& program : webPrograms())
    for (const auto& [stage, files] : {std::pair{"vertex", &program.spec.vertexFiles},
                                       std::pair{"fragment", &program.spec.fragmentFiles}}) {
      auto desktop = viewer::assembleStage(library, *files, program.spec.defines, 330);
      auto es = viewer::assembleStage(library, *files, program.spec.defines, 0, viewer::GlslDialect::Es300);
      ASSERT_TRUE(desktop.ok() && es.ok());
      EXPECT_EQ(desktop->text.substr(0, desktop->text.find('\n')), "#version 330 core");
      EXPECT_EQ(es->text.substr(0, es->text.find('\n')), "#version 300 es");
      // One version line on the desktop; the version and three precision statements in ES.
      EXPECT_EQ(withoutLines(desktop->text, 1), withoutLines(es->text, 4)) << program.name << " " << stage;
      ASSERT_EQ(desktop->fileAtLine.size(), es->fileAtLine.size());
      for (std::size_t i = 0; i < es->fileAtLine.size(); ++i)
        EXPECT_EQ(es->fileAtLine[i].first, desktop->fileAtLine[i].first + 3);
      // The module the page imports holds exactly this text and its line map.
      EXPECT_EQ(generated[program.name][stage]["source"].get<std::string>(), es->text) << program.name << " " << stage;
      EXPECT_EQ(generated[program.name][stage]["fileAtLine"].size(), es->fileAtLine.size());
    }
}

TEST(WebExport, ProgramsCompileAsGlslEs300) {
  auto context = viewer::createContext(viewer::Backend::OSMesa);
  ASSERT_TRUE(context.ok()) << context.error().message;
  const viewer::Gl& gl = (*context)->gl();
  const nlohmann::json generated = generatedPrograms();
  for (const NamedSpec& program : webPrograms())
    for (const auto& [stage, type] : {std::pair{"vertex", GL_VERTEX_SHADER}, std::pair{"fragment", GL_FRAGMENT_SHADER}}) {
      const std::string source = generated[program.name][stage]["source"].get<std::string>();
      const char* text = source.c_str();
      const GLuint shader = gl.CreateShader(static_cast<GLenum>(type));
      gl.ShaderSource(shader, 1, &text, nullptr);
      gl.CompileShader(shader);
      GLint compiled = GL_FALSE;
      gl.GetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
      std::string log(4096, '\0');
      gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
      EXPECT_EQ(compiled, GL_TRUE) << program.name << " " << stage << ":\n" << log.c_str();
      gl.DeleteShader(shader);
    }
}

TEST(WebExport, WritesEveryFileOfWebAndTheGeneratedModule) {
  const std::filesystem::path web = std::filesystem::path(NUT_SOURCE_DIR) / "web";
  const std::filesystem::path out = std::filesystem::path(NUT_TEST_OUTPUT_DIR) / "web_export";
  std::filesystem::remove_all(out);
  auto written = viewer::exportWeb(out.string(), viewer::ShaderLibrary{});
  ASSERT_TRUE(written.ok()) << written.error().message;
  // Every file of web/ is embedded (a file missing from viewer/CMakeLists.txt fails here), and
  // written as it is on disk, with meshoptimizer's decoder as npm installed it.
  const std::string decoder = "js/meshopt_decoder.mjs";
  std::set<std::string> onDisk{decoder}, embedded;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(web))
    if (entry.is_regular_file()) onDisk.insert(std::filesystem::relative(entry.path(), web).generic_string());
  for (const viewer::EmbeddedWebFile& file : viewer::embeddedWebFiles()) {
    embedded.insert(file.path);
    auto text = readTextFile((out / file.path).string());
    ASSERT_TRUE(text.ok()) << text.error().message;
    const std::string source = file.path == decoder ? NUT_MESHOPT_DECODER : (web / file.path).string();
    EXPECT_EQ(*text, *readTextFile(source)) << file.path;
  }
  EXPECT_EQ(embedded, onDisk);
  EXPECT_EQ(*written, static_cast<int>(embedded.size()) + 1);
  auto module = readTextFile((out / "js" / "generated.js").string());
  ASSERT_TRUE(module.ok()) << module.error().message;
  EXPECT_EQ(*module, *viewer::generatedWebModule(viewer::ShaderLibrary{}));
  // No temporary file is left beside them.
  for (const auto& entry : std::filesystem::recursive_directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(WebExport, AFolderThatCannotBeMadeIsNamed) {
  const std::filesystem::path out = std::filesystem::path(NUT_TEST_OUTPUT_DIR) / "web_export_blocked";
  std::filesystem::create_directories(out.parent_path());
  ASSERT_TRUE(writeTextFile(out.string(), "a file where the folder should go\n").ok());
  auto written = viewer::exportWeb(out.string(), viewer::ShaderLibrary{});
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find(out.string()), std::string::npos) << written.error().message;
}

}  // namespace
}  // namespace nut
