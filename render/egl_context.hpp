#pragma once
// Headless OpenGL through EGL: Mesa's surfaceless platform (no X server, no environment
// variables), falling back to the first EGL device; 3.3 core profile, no surface.

#include <memory>

#include "render/gl_context.hpp"

namespace fetic::render {

// Throws NoDisplayError when no EGL display or no 3.3 core context can be had.
std::unique_ptr<GlContext> make_egl_context();

}  // namespace fetic::render
