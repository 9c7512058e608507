// The preview's panel (docs/PREVIEW.md): Dear ImGui on the preview's own window and GL context,
// through the GLFW and OpenGL 3 back ends Debian's libimgui-dev ships. This class owns ImGui's
// context and frame; what the panel shows and does is the preview's (preview/session_panel.cpp).
#pragma once

struct GLFWwindow;
struct ImDrawList;

namespace glint {

class Panel {
  public:
    // Installs ImGui's input callbacks on `window`, chained to those already set there (the
    // preview's), and loads a font with the explanation's symbols (DejaVu Sans Mono, when
    // installed; ImGui's own font otherwise, which shows them as '?').
    explicit Panel(GLFWwindow* window);
    ~Panel();
    Panel(const Panel&) = delete;
    Panel& operator=(const Panel&) = delete;

    void begin_frame();
    void end_frame(); // draws what the frame built into the current framebuffer
    // Whether the panel has the mouse or keyboard (the pointer is over it, a slider is held):
    // the preview then leaves that input alone.
    bool wants_mouse() const;
    bool wants_keyboard() const;
    // Where the ray tree's lines go: behind the panel, over the image.
    ImDrawList* background() const;
};

} // namespace glint
