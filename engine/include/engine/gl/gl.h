#pragma once
// The one place that includes the OpenGL API (libepoxy resolves entry points for EGL and GLX).
#include <epoxy/gl.h>
