// viewer/gl.hpp — the OpenGL 3.3 core functions the GL layer calls, loaded per context.
//
// Every back-end hands over its own loader (OSMesaGetProcAddress, eglGetProcAddress,
// glfwGetProcAddress): libepoxy does not work with OSMesa, and one table for all three
// keeps the rendering code free of back-end cases. Calls read `gl.Clear(...)`.
#pragma once

#include <string>

#include <GL/glcorearb.h>

#include <nut/error.hpp>

namespace nut::viewer {

// X(type, name): the function gl<name> of glcorearb.h.
#define NUT_GL_FUNCTIONS(X)                                           \
  X(PFNGLGETSTRINGPROC, GetString)                                    \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                \
  X(PFNGLGETERRORPROC, GetError)                                      \
  X(PFNGLENABLEPROC, Enable)                                          \
  X(PFNGLDISABLEPROC, Disable)                                        \
  X(PFNGLVIEWPORTPROC, Viewport)                                      \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                  \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                  \
  X(PFNGLCLEARPROC, Clear)                                            \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                    \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                    \
  X(PFNGLCULLFACEPROC, CullFace)                                      \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                    \
  X(PFNGLFINISHPROC, Finish)                                          \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                  \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                  \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                          \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                            \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                  \
  X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                            \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                            \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                        \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                  \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                        \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)              \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)          \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                        \
  X(PFNGLCREATESHADERPROC, CreateShader)                              \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                              \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                            \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                      \
  X(PFNGLDELETESHADERPROC, DeleteShader)                              \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                            \
  X(PFNGLATTACHSHADERPROC, AttachShader)                              \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                              \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                    \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                            \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                  \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                  \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                    \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                    \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                    \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                    \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                      \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                        \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                  \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                        \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                  \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                            \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                  \
  X(PFNGLBUFFERDATAPROC, BufferData)                                  \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)        \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)              \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                  \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                \
  X(PFNGLCOLORMASKPROC, ColorMask)                                    \
  X(PFNGLGENQUERIESPROC, GenQueries)                                  \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                            \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                  \
  X(PFNGLENDQUERYPROC, EndQuery)                                      \
  X(PFNGLGETQUERYOBJECTUIVPROC, GetQueryObjectuiv)

struct Gl {
#define NUT_GL_MEMBER(type, name) type name = nullptr;
  NUT_GL_FUNCTIONS(NUT_GL_MEMBER)
#undef NUT_GL_MEMBER
};

// A back-end's lookup of a GL function by name ("glClear"); nullptr when there is none.
using GlProc = void (*)();
using GlProcLoader = GlProc (*)(const char* name);

// Loads every function of the table; fails naming the first that the context does not provide.
Result<Gl> loadGl(GlProcLoader loader);

// "GL_INVALID_OPERATION" and so on, for error messages.
std::string glErrorName(GLenum error);

}  // namespace nut::viewer
