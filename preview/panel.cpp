#include "preview/panel.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <filesystem>

namespace glint {

namespace {

// The characters the explanation uses beyond ASCII: Latin-1 (·), superscripts (⁻¹), modifier
// letters (ᵀ), arrows (→), mathematical operators (Σ, ≤).
const ImWchar kGlyphs[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x1D00, 0x1DBF, 0x2070,
                           0x209F, 0x2190, 0x21FF, 0x2200, 0x22FF, 0};
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf";

} // namespace

Panel::Panel(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini in the user's directory
    if (std::filesystem::exists(kFont))
        io.Fonts->AddFontFromFileTTF(kFont, 13.0f, nullptr, kGlyphs);
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
}

Panel::~Panel() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void Panel::begin_frame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void Panel::end_frame() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool Panel::wants_mouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}

bool Panel::wants_keyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

ImDrawList* Panel::background() const {
    return ImGui::GetBackgroundDrawList();
}

} // namespace glint
