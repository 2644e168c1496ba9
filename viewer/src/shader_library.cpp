// Shader sources (embedded or from disk) and program building with readable errors.
#include <viewer/shader_library.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <tuple>

#include <shaders/embedded.hpp>

namespace nut::viewer {

namespace {

constexpr const char* kGeneratedConstants = "format_constants.glsl";
constexpr const char* kCommon = "common.glsl";

Result<std::string> embedded(const std::string& name) {
  for (const shaders::EmbeddedShader& s : shaders::embeddedShaders())
    if (name == s.name) return std::string(s.source);
  return Error{"shader " + name + ": not embedded in this program"};
}

std::string infoLog(const Gl& gl, GLuint object, bool isProgram) {
  GLint length = 0;
  (isProgram ? gl.GetProgramiv : gl.GetShaderiv)(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  (isProgram ? gl.GetProgramInfoLog : gl.GetShaderInfoLog)(object, length, nullptr, log.data());
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log;
}

// Rewrites the line numbers of an info log ("0:123(4): error" from Mesa, "0(123) : error" from
// NVIDIA) as file and line: "hni_raycast.frag:17(4): error". Drivers number the lines of the one
// assembled string; #line with a source-string number would be the standard way to name files, but
// Mesa ignores the number, so the mapping is done here.
std::string annotate(const std::string& log, const StageSource& source) {
  const auto where = [&source](int line) {
    auto it = std::upper_bound(source.fileAtLine.begin(), source.fileAtLine.end(), line,
                               [](int l, const std::pair<int, std::string>& f) { return l < f.first; });
    if (it == source.fileAtLine.begin()) return std::string("#version or #define line");
    --it;
    return it->second + ":" + std::to_string(line - it->first + 1);
  };
  // The number before the line is the source string: always 0 here (one string per stage).
  static const std::regex reference(R"((^|\n)\d+(:(\d+)\(|\((\d+)\)))");
  std::string out;
  std::size_t last = 0;
  for (std::sregex_iterator m(log.begin(), log.end(), reference), end; m != end; ++m) {
    const bool mesa = (*m)[3].matched;
    out += log.substr(last, static_cast<std::size_t>(m->position(0)) - last);
    out += (*m)[1].str() + where(std::stoi((*m)[mesa ? 3 : 4].str())) + (mesa ? "(" : "");
    last = static_cast<std::size_t>(m->position(0) + m->length(0));
  }
  return out + log.substr(last);
}

}  // namespace

Result<StageSource> assembleStage(const ShaderLibrary& library, const std::vector<std::string>& files,
                                  const std::vector<std::string>& defines, int glslVersion, GlslDialect dialect) {
  std::vector<std::string> parts{kGeneratedConstants, kCommon};
  parts.insert(parts.end(), files.begin(), files.end());
  StageSource out;
  out.text = dialect == GlslDialect::Es300
                 ? "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp usampler2D;\n"
                 : "#version " + std::to_string(glslVersion) + " core\n";
  for (const std::string& define : defines) out.text += "#define " + define + "\n";
  int line = 1 + static_cast<int>(std::count(out.text.begin(), out.text.end(), '\n'));
  for (const std::string& part : parts) {
    auto text = library.source(part);
    if (!text) return text.error();
    out.fileAtLine.emplace_back(line, part);
    out.text += *text;
    if (out.text.back() != '\n') out.text += '\n';
    line += static_cast<int>(std::count(text->begin(), text->end(), '\n')) + (text->empty() || text->back() != '\n');
  }
  return out;
}

ShaderLibrary ShaderLibrary::fromEnvironment() {
  const char* directory = std::getenv("NUT_SHADER_DIR");
  return ShaderLibrary(directory ? directory : "");
}

Result<std::string> ShaderLibrary::source(const std::string& name) const {
  if (const auto it = added_.find(name); it != added_.end()) return it->second;
  if (directory_.empty() || name == kGeneratedConstants) return embedded(name);
  const std::string path = directory_ + "/" + name;
  std::ifstream file(path, std::ios::binary);
  if (!file) return Error{"shader " + path + ": cannot open"};
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

Result<Program> Program::build(const Gl& gl, const ShaderLibrary& library, const ProgramSpec& spec, int glslVersion) {
  GlObject program(gl, gl.CreateProgram(), [](const Gl& g, GLuint n) { g.DeleteProgram(n); });
  const std::string version = "GLSL " + std::to_string(glslVersion);
  std::vector<GlObject> shaders;
  for (const auto& [stage, files, name] : {std::tuple{GL_VERTEX_SHADER, &spec.vertexFiles, "vertex"},
                                           std::tuple{GL_FRAGMENT_SHADER, &spec.fragmentFiles, "fragment"}}) {
    auto source = assembleStage(library, *files, spec.defines, glslVersion);
    if (!source) return Error{spec.role + ": " + source.error().message};
    GlObject shader(gl, gl.CreateShader(static_cast<GLenum>(stage)), [](const Gl& g, GLuint n) { g.DeleteShader(n); });
    const char* text = source->text.c_str();
    gl.ShaderSource(shader.get(), 1, &text, nullptr);
    gl.CompileShader(shader.get());
    GLint compiled = GL_FALSE;
    gl.GetShaderiv(shader.get(), GL_COMPILE_STATUS, &compiled);
    if (compiled != GL_TRUE)
      return Error{spec.role + ": " + name + " shader, " + version + ":\n" + annotate(infoLog(gl, shader.get(), false), *source)};
    gl.AttachShader(program.get(), shader.get());
    shaders.push_back(std::move(shader));
  }
  gl.LinkProgram(program.get());
  GLint linked = GL_FALSE;
  gl.GetProgramiv(program.get(), GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) return Error{spec.role + ": link, " + version + ": " + infoLog(gl, program.get(), true)};
  return Program(gl, std::move(program));
}

GLint Program::uniform(const char* name) const {
  auto it = uniforms_.find(name);
  if (it == uniforms_.end()) it = uniforms_.emplace(name, gl_->GetUniformLocation(program_.get(), name)).first;
  return it->second;
}

}  // namespace nut::viewer
