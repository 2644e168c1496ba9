// HNI atlas upload and the instanced proxy-box draw of the GLSL ray caster.
#include <viewer/hni_renderer.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include <glm/matrix.hpp>

#include <nut/format.hpp>

namespace nut::viewer {

namespace {

// Per-instance vertex data, as hni_proxy.vert declares it.
struct InstanceData {
  float eyeUnits[3];
  float worldFromRoot[9];  // columns
  GLint atlasOrigin[2];
};

}  // namespace

Result<HniAtlas> HniAtlas::create(const Gl& gl, int width, int height) {
  if (Status s = checkTextureSize(gl, "HNI atlas", width, height); !s) return s.error();
  HniAtlas atlas(gl, width, height);
  atlas.texture_ = makeTexture(gl);
  gl.BindTexture(GL_TEXTURE_2D, atlas.texture_.get());
  // Integer textures must not be filtered (or the texture is incomplete); texelFetch never does.
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8UI, width, height, 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, nullptr);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR)
    return Error{"HNI atlas " + std::to_string(width) + "x" + std::to_string(height) + ": " + glErrorName(error)};
  return atlas;
}

Status HniAtlas::put(const Image& hni, glm::ivec2 at) {
  if (at.x < 0 || at.y < 0 || at.x + hni.width > width_ || at.y + hni.height > height_)
    return Error{"HNI atlas " + std::to_string(width_) + "x" + std::to_string(height_) + ": a " + std::to_string(hni.width) + "x" +
                 std::to_string(hni.height) + " HNI at (" + std::to_string(at.x) + ", " + std::to_string(at.y) + ") does not fit"};
  gl_->BindTexture(GL_TEXTURE_2D, texture_.get());
  gl_->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_->TexSubImage2D(GL_TEXTURE_2D, 0, at.x, at.y, hni.width, hni.height, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, hni.pixels.data());
  gl_->BindTexture(GL_TEXTURE_2D, 0);
  return Ok{};
}

ProgramSpec hniRayCasterSpec(Lookup lookup) {
  const bool exact = lookup == Lookup::Exact;
  return {exact ? "HNI ray caster (exact lookup)" : "HNI ray caster",
          {"hni_access.glsl", "hni_proxy.vert"},
          {"hni_access.glsl", "solids.glsl", "hni_raycast.frag"},
          {exact ? "NUT_EXACT_LOOKUP 1" : "NUT_EXACT_LOOKUP 0"}};
}

Result<HniRenderer> HniRenderer::create(const Context& context, const ShaderLibrary& library, int glslVersion) {
  const Gl& gl = context.gl();
  const auto build = [&](Lookup lookup) {
    return Program::build(gl, library, hniRayCasterSpec(lookup), glslVersion ? glslVersion : context.glslVersion());
  };
  auto heuristic = build(Lookup::Heuristic);
  if (!heuristic) return heuristic.error();
  auto exact = build(Lookup::Exact);
  if (!exact) return exact.error();
  HniRenderer r(gl, std::move(*heuristic), std::move(*exact));
  r.vertexArray_ = makeVertexArray(gl);
  r.instanceBuffer_ = makeBuffer(gl);
  gl.BindVertexArray(r.vertexArray_.get());
  gl.BindBuffer(GL_ARRAY_BUFFER, r.instanceBuffer_.get());
  const auto stride = static_cast<GLsizei>(sizeof(InstanceData));
  const auto at = [](std::size_t offset) { return reinterpret_cast<const void*>(offset); };
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, at(offsetof(InstanceData, eyeUnits)));
  for (GLuint column = 0; column < 3; ++column)
    gl.VertexAttribPointer(1 + column, 3, GL_FLOAT, GL_FALSE, stride,
                           at(offsetof(InstanceData, worldFromRoot) + 3 * column * sizeof(float)));
  gl.VertexAttribIPointer(4, 2, GL_INT, stride, at(offsetof(InstanceData, atlasOrigin)));
  for (GLuint attribute = 0; attribute < 5; ++attribute) {
    gl.EnableVertexAttribArray(attribute);
    gl.VertexAttribDivisor(attribute, 1);
  }
  gl.BindVertexArray(0);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);
  return r;
}

void HniRenderer::draw(const FrameView& view, const HniAtlas& atlas, std::span<const HniInstance> instances,
                       const RayCastOptions& options) const {
  if (instances.empty()) return;
  const Gl& gl = *gl_;
  std::vector<InstanceData> data(instances.size());
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const HniInstance& instance = instances[i];
    // The eye in the root block's frame, in units, computed in double as the CPU caster does.
    const glm::vec3 eye(glm::transpose(instance.worldFromRoot) * (view.camera.eye - instance.originM) /
                        format::kMetresPerUnit);
    for (int a = 0; a < 3; ++a) data[i].eyeUnits[a] = eye[a];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) data[i].worldFromRoot[3 * c + r] = static_cast<float>(instance.worldFromRoot[c][r]);
    data[i].atlasOrigin[0] = instance.atlasOrigin.x;
    data[i].atlasOrigin[1] = instance.atlasOrigin.y;
  }
  gl.BindBuffer(GL_ARRAY_BUFFER, instanceBuffer_.get());
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(InstanceData)), data.data(),
                GL_STREAM_DRAW);
  gl.BindBuffer(GL_ARRAY_BUFFER, 0);

  const Program& program = options.lookup == Lookup::Exact ? exact_ : heuristic_;
  gl.UseProgram(program.id());
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, atlas.texture());
  gl.Uniform1i(program.uniform("uHni"), 0);
  gl.UniformMatrix4fv(program.uniform("uClipFromEye"), 1, GL_FALSE, &view.proxyClipFromEye[0][0]);
  gl.Uniform3f(program.uniform("uForward"), view.forward.x, view.forward.y, view.forward.z);
  gl.Uniform3f(program.uniform("uRight"), view.right.x, view.right.y, view.right.z);
  gl.Uniform3f(program.uniform("uUp"), view.up.x, view.up.y, view.up.z);
  gl.Uniform2f(program.uniform("uTanHalf"), view.tanHalf.x, view.tanHalf.y);
  gl.Uniform2f(program.uniform("uViewportSize"), static_cast<float>(view.camera.width),
               static_cast<float>(view.camera.height));
  gl.Uniform2f(program.uniform("uDepthFromEyeZ"), view.depthFromEyeZ.x, view.depthFromEyeZ.y);
  gl.Uniform1f(program.uniform("uPixelAngle"), view.pixelAngle);
  gl.Uniform1f(program.uniform("uLodPx"), static_cast<float>(options.lodPx));
  gl.Uniform1i(program.uniform("uLodAuto"), options.lodAuto ? 1 : 0);
  gl.Uniform1i(program.uniform("uMaxIterations"), options.maxIterations);
  gl.Uniform1i(program.uniform("uHeatMap"), options.heatMap ? 1 : 0);

  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LEQUAL);  // capped rays are drawn at depth 1, the cleared value
  gl.DepthMask(GL_TRUE);
  gl.Enable(GL_CULL_FACE);
  gl.CullFace(GL_FRONT);
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_ONE, GL_SRC_ALPHA);
  gl.BindVertexArray(vertexArray_.get());
  gl.DrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(instances.size()));
  gl.BindVertexArray(0);
  gl.Disable(GL_BLEND);
  gl.Disable(GL_CULL_FACE);
  gl.UseProgram(0);
}

}  // namespace nut::viewer
