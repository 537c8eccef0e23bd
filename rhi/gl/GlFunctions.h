// The OpenGL 4.5 entry points the backend uses, loaded at run time through the context's
// getProcAddress (EGL, OSMesa or GLFW) - never by linking libGL, which would clash with OSMesa.
// One X-macro list, so adding a function is one line.
#pragma once

#include <GL/glcorearb.h>

#include "platforms/GlContext.h"

namespace lpv::rhi::gl {

#define LPV_GL_FUNCTIONS(X)                                                                                  \
    X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                                                   \
    X(PFNGLGETSTRINGPROC, glGetString)                                                                       \
    X(PFNGLGETSTRINGIPROC, glGetStringi)                                                                     \
    X(PFNGLENABLEPROC, glEnable)                                                                             \
    X(PFNGLDISABLEPROC, glDisable)                                                                           \
    X(PFNGLENABLEIPROC, glEnablei)                                                                           \
    X(PFNGLDISABLEIPROC, glDisablei)                                                                         \
    X(PFNGLCLIPCONTROLPROC, glClipControl)                                                                   \
    X(PFNGLVIEWPORTINDEXEDFPROC, glViewportIndexedf)                                                         \
    X(PFNGLDEPTHRANGEFPROC, glDepthRangef)                                                                   \
    X(PFNGLSCISSORPROC, glScissor)                                                                           \
    X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                                                       \
    X(PFNGLDEPTHMASKPROC, glDepthMask)                                                                       \
    X(PFNGLSTENCILFUNCPROC, glStencilFunc)                                                                   \
    X(PFNGLSTENCILOPPROC, glStencilOp)                                                                       \
    X(PFNGLSTENCILMASKPROC, glStencilMask)                                                                   \
    X(PFNGLCOLORMASKIPROC, glColorMaski)                                                                     \
    X(PFNGLBLENDFUNCSEPARATEIPROC, glBlendFuncSeparatei)                                                     \
    X(PFNGLBLENDEQUATIONSEPARATEIPROC, glBlendEquationSeparatei)                                             \
    X(PFNGLCULLFACEPROC, glCullFace)                                                                         \
    X(PFNGLFRONTFACEPROC, glFrontFace)                                                                       \
    X(PFNGLPOLYGONOFFSETPROC, glPolygonOffset)                                                               \
    X(PFNGLFINISHPROC, glFinish)                                                                             \
    X(PFNGLFLUSHPROC, glFlush)                                                                               \
    X(PFNGLGETERRORPROC, glGetError)                                                                         \
    X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                                                   \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, glDebugMessageCallback)                                                 \
    X(PFNGLDEBUGMESSAGECONTROLPROC, glDebugMessageControl)                                                   \
    X(PFNGLOBJECTLABELPROC, glObjectLabel)                                                                   \
    X(PFNGLPUSHDEBUGGROUPPROC, glPushDebugGroup)                                                             \
    X(PFNGLPOPDEBUGGROUPPROC, glPopDebugGroup)                                                               \
    X(PFNGLCREATEBUFFERSPROC, glCreateBuffers)                                                               \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage)                                                     \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, glNamedBufferSubData)                                                     \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, glGetNamedBufferSubData)                                               \
    X(PFNGLCOPYNAMEDBUFFERSUBDATAPROC, glCopyNamedBufferSubData)                                             \
    X(PFNGLMAPNAMEDBUFFERRANGEPROC, glMapNamedBufferRange)                                                   \
    X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                                               \
    X(PFNGLBINDBUFFERRANGEPROC, glBindBufferRange)                                                           \
    X(PFNGLBINDBUFFERPROC, glBindBuffer)                                                                     \
    X(PFNGLCREATETEXTURESPROC, glCreateTextures)                                                             \
    X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D)                                                         \
    X(PFNGLTEXTURESTORAGE3DPROC, glTextureStorage3D)                                                         \
    X(PFNGLTEXTURESUBIMAGE2DPROC, glTextureSubImage2D)                                                       \
    X(PFNGLTEXTURESUBIMAGE3DPROC, glTextureSubImage3D)                                                       \
    X(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage)                                                           \
    X(PFNGLTEXTUREPARAMETERIPROC, glTextureParameteri)                                                       \
    X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                                                             \
    X(PFNGLBINDTEXTUREUNITPROC, glBindTextureUnit)                                                           \
    X(PFNGLBINDIMAGETEXTUREPROC, glBindImageTexture)                                                         \
    X(PFNGLCLEARTEXIMAGEPROC, glClearTexImage)                                                               \
    X(PFNGLCOPYIMAGESUBDATAPROC, glCopyImageSubData)                                                         \
    X(PFNGLCREATESAMPLERSPROC, glCreateSamplers)                                                             \
    X(PFNGLSAMPLERPARAMETERIPROC, glSamplerParameteri)                                                       \
    X(PFNGLSAMPLERPARAMETERFPROC, glSamplerParameterf)                                                       \
    X(PFNGLSAMPLERPARAMETERFVPROC, glSamplerParameterfv)                                                     \
    X(PFNGLBINDSAMPLERPROC, glBindSampler)                                                                   \
    X(PFNGLDELETESAMPLERSPROC, glDeleteSamplers)                                                             \
    X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers)                                                     \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture)                                           \
    X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, glNamedFramebufferTextureLayer)                                 \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, glNamedFramebufferDrawBuffers)                                   \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, glNamedFramebufferDrawBuffer)                                     \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, glNamedFramebufferReadBuffer)                                     \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, glCheckNamedFramebufferStatus)                                   \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                                           \
    X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                                                     \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, glClearNamedFramebufferfv)                                           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFIPROC, glClearNamedFramebufferfi)                                           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, glClearNamedFramebufferuiv)                                         \
    X(PFNGLBLITNAMEDFRAMEBUFFERPROC, glBlitNamedFramebuffer)                                                 \
    X(PFNGLCREATESHADERPROC, glCreateShader)                                                                 \
    X(PFNGLSHADERSOURCEPROC, glShaderSource)                                                                 \
    X(PFNGLCOMPILESHADERPROC, glCompileShader)                                                               \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                                                   \
    X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                                                         \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                                               \
    X(PFNGLATTACHSHADERPROC, glAttachShader)                                                                 \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                                                   \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                                                 \
    X(PFNGLGETPROGRAMINTERFACEIVPROC, glGetProgramInterfaceiv)                                               \
    X(PFNGLGETPROGRAMRESOURCEIVPROC, glGetProgramResourceiv)                                                 \
    X(PFNGLGETUNIFORMIVPROC, glGetUniformiv)                                                                 \
    X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                                                       \
    X(PFNGLDELETESHADERPROC, glDeleteShader)                                                                 \
    X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                                               \
    X(PFNGLUSEPROGRAMPROC, glUseProgram)                                                                     \
    X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                                                     \
    X(PFNGLUNIFORM1IPROC, glUniform1i)                                                                       \
    X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays)                                                     \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, glVertexArrayAttribFormat)                                           \
    X(PFNGLVERTEXARRAYATTRIBIFORMATPROC, glVertexArrayAttribIFormat)                                         \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, glVertexArrayAttribBinding)                                         \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, glEnableVertexArrayAttrib)                                           \
    X(PFNGLVERTEXARRAYBINDINGDIVISORPROC, glVertexArrayBindingDivisor)                                       \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, glVertexArrayVertexBuffer)                                           \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, glVertexArrayElementBuffer)                                         \
    X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                                                           \
    X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                                                     \
    X(PFNGLDRAWARRAYSINSTANCEDBASEINSTANCEPROC, glDrawArraysInstancedBaseInstance)                           \
    X(PFNGLDRAWELEMENTSINSTANCEDBASEVERTEXBASEINSTANCEPROC, glDrawElementsInstancedBaseVertexBaseInstance)   \
    X(PFNGLMULTIDRAWELEMENTSINDIRECTPROC, glMultiDrawElementsIndirect)                                       \
    X(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute)                                                           \
    X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier)                                                               \
    X(PFNGLCREATEQUERIESPROC, glCreateQueries)                                                               \
    X(PFNGLQUERYCOUNTERPROC, glQueryCounter)                                                                 \
    X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v)                                                   \
    X(PFNGLGETQUERYOBJECTIVPROC, glGetQueryObjectiv)                                                         \
    X(PFNGLDELETEQUERIESPROC, glDeleteQueries)                                                               \
    X(PFNGLFENCESYNCPROC, glFenceSync)                                                                       \
    X(PFNGLCLIENTWAITSYNCPROC, glClientWaitSync)                                                             \
    X(PFNGLDELETESYNCPROC, glDeleteSync)

struct Functions {
#define LPV_GL_DECLARE(type, name) type name = nullptr;
    LPV_GL_FUNCTIONS(LPV_GL_DECLARE)
#undef LPV_GL_DECLARE

    // Throws BackendUnavailable naming the first entry point the context does not provide.
    void load(platforms::GlContext& context);
};

} // namespace lpv::rhi::gl
