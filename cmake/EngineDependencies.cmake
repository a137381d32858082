# Every dependency comes from a Debian package (scripts/setup installs them).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
find_package(glfw3 3.3 REQUIRED)
find_package(glm REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(TinyGLTF REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
pkg_get_variable(IMGUI_INCLUDE_DIR imgui includedir)

# Dear ImGui's platform/renderer backends ship as sources in libimgui-dev's examples.
set(ENGINE_IMGUI_BACKENDS_DIR /usr/share/doc/libimgui-dev/examples/backends
    CACHE PATH "Folder holding imgui_impl_glfw.cpp and imgui_impl_opengl3.cpp")
if(NOT EXISTS ${ENGINE_IMGUI_BACKENDS_DIR}/imgui_impl_opengl3.cpp)
  message(FATAL_ERROR "Dear ImGui backend sources not found in ${ENGINE_IMGUI_BACKENDS_DIR} "
                      "(Debian package libimgui-dev; run scripts/setup)")
endif()
