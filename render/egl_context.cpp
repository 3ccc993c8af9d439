#include "render/egl_context.hpp"

#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

namespace fetic::render {
namespace {

std::string egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + std::to_string(error);
  }
}

class EglContext final : public GlContext {
 public:
  EglContext() {
    const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display)
      throw NoDisplayError(
          "no EGL display: libEGL offers no eglGetPlatformDisplayEXT (is Mesa's EGL installed? "
          "apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri)");
    display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    platform_ = "surfaceless";
    if (!initialize()) {
      const std::string surfaceless_error = egl_error_name(eglGetError());
      display_ = first_device_display(get_platform_display);
      platform_ = "device";
      if (!initialize())
        throw NoDisplayError("no EGL display: neither Mesa's surfaceless platform (" +
                             surfaceless_error +
                             ") nor an EGL device could be opened; install libegl-mesa0 and "
                             "libgl1-mesa-dri for software rendering");
    }
    create_context();
  }

  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      eglTerminate(display_);
    }
  }

  void make_current() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw RenderError("cannot make the EGL context current (" + egl_error_name(eglGetError()) +
                        ")");
  }

  std::string description() const override {
    const auto text = [](GLenum name) {
      const auto* value = reinterpret_cast<const char*>(glGetString(name));
      return std::string(value ? value : "?");
    };
    return "EGL " + std::to_string(major_) + "." + std::to_string(minor_) + " (" + platform_ +
           "), OpenGL " + text(GL_VERSION) + ", " + text(GL_RENDERER);
  }

 private:
  bool initialize() {
    return display_ != EGL_NO_DISPLAY && eglInitialize(display_, &major_, &minor_) == EGL_TRUE;
  }

  static EGLDisplay first_device_display(PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display) {
    const auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!query_devices) return EGL_NO_DISPLAY;
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (!query_devices(8, devices, &count) || count < 1) return EGL_NO_DISPLAY;
    return get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
  }

  void create_context() {
    if (!eglBindAPI(EGL_OPENGL_API))
      throw NoDisplayError("EGL display without desktop OpenGL (" + egl_error_name(eglGetError()) +
                           ")");
    // The default EGL_SURFACE_TYPE (window) matches no surfaceless config; ask for pbuffer.
    const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                        EGL_PBUFFER_BIT,
                                        EGL_RENDERABLE_TYPE,
                                        EGL_OPENGL_BIT,
                                        EGL_RED_SIZE,
                                        8,
                                        EGL_GREEN_SIZE,
                                        8,
                                        EGL_BLUE_SIZE,
                                        8,
                                        EGL_ALPHA_SIZE,
                                        8,
                                        EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attributes, &config, 1, &count) || count < 1)
      throw NoDisplayError("EGL display without an 8-bit RGBA OpenGL configuration");
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attributes);
    if (context_ == EGL_NO_CONTEXT)
      throw NoDisplayError("cannot create an OpenGL 3.3 core context through EGL (" +
                           egl_error_name(eglGetError()) + ")");
    make_current();
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLint major_ = 0, minor_ = 0;
  std::string platform_;
};

}  // namespace

std::unique_ptr<GlContext> make_egl_context() {
  return std::make_unique<EglContext>();
}

}  // namespace fetic::render
