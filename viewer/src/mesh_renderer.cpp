// Mesh upload and rasterisation with the shared shading.
#include <viewer/mesh_renderer.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

namespace nut::viewer {

namespace {

void describeVertexLayout(const Gl& gl, GLuint vertexArray, GLuint buffer, GLsizei stride) {
  gl.BindVertexArray(vertexArray);
  gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(0));
  gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
  // Bytes as they are (0..255): the shader works on sRGB bytes like the CPU renderers.
  gl.VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_FALSE, stride, reinterpret_cast<const void*>(6 * sizeof(float)));
  for (GLuint a = 0; a < 3; ++a) gl.EnableVertexAttribArray(a);
  gl.BindVertexArray(0);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace

Result<GpuMesh> GpuMesh::upload(const Gl& gl, const TriangleMesh& mesh) {
  if (mesh.triangleMaterial.size() != mesh.triangles.size())
    return Error{"mesh: " + std::to_string(mesh.triangles.size()) + " triangles but " +
                 std::to_string(mesh.triangleMaterial.size()) + " triangle materials"};
  for (std::uint16_t m : mesh.triangleMaterial)
    if (m >= mesh.materials.size())
      return Error{"mesh: material " + std::to_string(m) + " of " + std::to_string(mesh.materials.size())};
  GpuMesh out(gl);
  out.bounds_ = {glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t index : mesh.triangles[t]) {
      if (index >= mesh.positions.size())
        return Error{"mesh: triangle " + std::to_string(t) + " names vertex " + std::to_string(index) + " of " +
                     std::to_string(mesh.positions.size())};
      out.bounds_.min = glm::min(out.bounds_.min, mesh.positions[index]);
      out.bounds_.max = glm::max(out.bounds_.max, mesh.positions[index]);
    }
  if (mesh.triangles.empty()) out.bounds_ = {};
  out.anchorM = out.bounds_.centre();

  std::vector<Vertex> opaque;
  opaque.reserve(3 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    const double length = glm::length(normal);
    if (!(length > 0) || !std::isfinite(length)) continue;
    const Material& m = mesh.materials[mesh.triangleMaterial[t]];
    auto& into = m.opacity == 255 ? opaque : out.translucent_;
    for (const glm::dvec3& p : {a, b, c}) {
      Vertex v{};
      for (int i = 0; i < 3; ++i) {
        v.position[i] = static_cast<float>(p[i] - out.anchorM[i]);
        v.normal[i] = static_cast<float>(normal[i] / length);
      }
      v.material[0] = m.r, v.material[1] = m.g, v.material[2] = m.b, v.material[3] = m.opacity;
      into.push_back(v);
    }
  }
  const auto stride = static_cast<GLsizei>(sizeof(Vertex));
  out.vertexArray_ = makeVertexArray(gl);
  out.opaqueBuffer_ = makeBuffer(gl);
  gl.BindBuffer(GL_ARRAY_BUFFER, out.opaqueBuffer_.get());
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(opaque.size() * sizeof(Vertex)), opaque.data(), GL_STATIC_DRAW);
  describeVertexLayout(gl, out.vertexArray_.get(), out.opaqueBuffer_.get(), stride);
  out.opaqueVertices_ = static_cast<GLsizei>(opaque.size());
  out.translucentArray_ = makeVertexArray(gl);
  out.translucentBuffer_ = makeBuffer(gl);
  describeVertexLayout(gl, out.translucentArray_.get(), out.translucentBuffer_.get(), stride);
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) return Error{"mesh upload: " + glErrorName(error)};
  return out;
}

ProgramSpec meshProgramSpec() { return {"mesh", {"mesh.vert"}, {"mesh.frag"}, {}}; }

Result<MeshRenderer> MeshRenderer::create(const Context& context, const ShaderLibrary& library, int glslVersion) {
  auto program = Program::build(context.gl(), library, meshProgramSpec(),
                                glslVersion ? glslVersion : context.glslVersion());
  if (!program) return program.error();
  return MeshRenderer(context.gl(), std::move(*program));
}

void MeshRenderer::setUniforms(const FrameView& view, const GpuMesh& mesh) const {
  const Gl& gl = *gl_;
  gl.UseProgram(program_.id());
  const glm::vec3 anchor(mesh.anchorM - view.camera.eye);  // in double, then float
  gl.Uniform3f(program_.uniform("uAnchorFromEye"), anchor.x, anchor.y, anchor.z);
  gl.UniformMatrix4fv(program_.uniform("uClipFromEye"), 1, GL_FALSE, &view.clipFromEye[0][0]);
  gl.Enable(GL_DEPTH_TEST);
}

void MeshRenderer::drawOpaque(const FrameView& view, const GpuMesh& mesh) const {
  if (mesh.opaqueVertices_ == 0) return;
  const Gl& gl = *gl_;
  setUniforms(view, mesh);
  gl.DepthFunc(GL_LESS);
  gl.DepthMask(GL_TRUE);
  gl.BindVertexArray(mesh.vertexArray_.get());
  gl.DrawArrays(GL_TRIANGLES, 0, mesh.opaqueVertices_);
  gl.BindVertexArray(0);
  gl.UseProgram(0);
}

void MeshRenderer::probe(const FrameView& view, const GpuMesh& mesh, GLint first, GLsizei count) const {
  const Gl& gl = *gl_;
  setUniforms(view, mesh);
  gl.DepthFunc(GL_LEQUAL);
  gl.DepthMask(GL_FALSE);
  gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  gl.BindVertexArray(mesh.vertexArray_.get());
  gl.DrawArrays(GL_TRIANGLES, first, count);
  gl.BindVertexArray(0);
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.DepthMask(GL_TRUE);
  gl.UseProgram(0);
}

void MeshRenderer::drawTranslucent(const FrameView& view, GpuMesh& mesh) const {
  if (mesh.translucent_.empty()) return;
  const Gl& gl = *gl_;
  // Back to front by the distance of the centroid from the eye.
  const glm::dvec3 eye = view.camera.eye - mesh.anchorM;
  const std::size_t count = mesh.translucent_.size() / 3;
  std::vector<double> distance(count);
  for (std::size_t t = 0; t < count; ++t) {
    glm::dvec3 centroid(0.0);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) centroid[i] += mesh.translucent_[3 * t + static_cast<std::size_t>(k)].position[i] / 3.0;
    distance[t] = glm::length(centroid - eye);
  }
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return distance[a] > distance[b]; });
  std::vector<GpuMesh::Vertex> sorted;
  sorted.reserve(mesh.translucent_.size());
  for (std::size_t t : order)
    sorted.insert(sorted.end(), mesh.translucent_.begin() + static_cast<std::ptrdiff_t>(3 * t),
                  mesh.translucent_.begin() + static_cast<std::ptrdiff_t>(3 * t + 3));
  gl.BindBuffer(GL_ARRAY_BUFFER, mesh.translucentBuffer_.get());
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(sorted.size() * sizeof(GpuMesh::Vertex)), sorted.data(),
                GL_STREAM_DRAW);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);

  setUniforms(view, mesh);
  gl.DepthFunc(GL_LESS);
  gl.DepthMask(GL_FALSE);
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl.BindVertexArray(mesh.translucentArray_.get());
  gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(sorted.size()));
  gl.BindVertexArray(0);
  gl.Disable(GL_BLEND);
  gl.DepthMask(GL_TRUE);
  gl.UseProgram(0);
}

}  // namespace nut::viewer
