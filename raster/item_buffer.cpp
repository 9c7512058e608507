#include "raster/item_buffer.h"

#include "raster/gl_context.h"
#include "raster/tessellation.h"

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <shaders.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <map>
#include <optional>
#include <string>
#include <tuple>

namespace glint {

namespace {

GLuint compile(GLenum kind, const char* source) {
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw GlError(std::string("shader compilation failed: ") + log);
    }
    return shader;
}

// GLSL constants for the closed set of shapes, from its one table (trace/shapes/table.h), inserted
// after a shader's #version line: `const int SHAPE_SPHERE = 0;` and so on. A shader naming a shape
// that the table lacks fails to compile.
std::string with_shape_constants(std::string_view source) {
    std::string constants;
    const auto& names = EnumNames<ShapeKind>::names;
    for (std::size_t i = 0; i < names.size(); ++i) {
        std::string name(names[i]);
        for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        constants += "const int SHAPE_" + name + " = " + std::to_string(i) + ";\n";
    }
    const std::size_t line_end = source.find('\n') + 1;
    return std::string(source.substr(0, line_end)) + constants +
           std::string(source.substr(line_end));
}

GLuint link(const char* vertex, const char* fragment) {
    const GLuint v = compile(GL_VERTEX_SHADER, vertex), f = compile(GL_FRAGMENT_SHADER, fragment);
    const GLuint program = glCreateProgram();
    glAttachShader(program, v);
    glAttachShader(program, f);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw GlError(std::string("shader linking failed: ") + log);
    }
    return program;
}

// Clip coordinates of a camera-relative point p, matching PinholeCamera exactly: p lies on the
// ray of NDC (x, y) when p ∝ forward + x·R + y·U, so x = (p·R)/(|R|²·(p·forward)), and likewise
// y. Reverse-Z with an infinite far plane: z_clip = near, w_clip = p·forward, so the depth
// near / view depth keeps float's relative precision at every distance.
glm::dmat4 projection(const PinholeCamera& camera, double near) {
    const DVec3 r(camera.right_scaled()), u(camera.up_scaled()), f(camera.forward());
    glm::dmat4 p(0.0); // glm: p[column][row]
    for (int c = 0; c < 3; ++c) {
        p[c][0] = r[c] / glm::dot(r, r);
        p[c][1] = u[c] / glm::dot(u, u);
        p[c][3] = f[c];
    }
    p[3][2] = near;
    return p;
}

glm::dmat4 to_mat4(const Mat3& linear, Vec3 offset) {
    glm::dmat4 m{glm::dmat3(linear)};
    m[3] = glm::dvec4(DVec3(offset), 1.0);
    return m;
}

// A proxy mode box: the object-space bounds of a tessellated shape, which read only its
// parameters (never a mesh), as the corners lo and hi; an axis the bounds leave flat (a disk's)
// is thickened to ±0.01 so that the box has faces to rasterize.
std::array<float, 6> proxy_box(const Object& o) {
    SceneObject shape;
    shape.shape = o.shape;
    shape.top_radius = static_cast<float>(o.params.top_radius);
    shape.open = o.params.open;
    const auto [lo, hi] = *unit_box(shape, {});
    std::array<float, 6> corners{};
    for (int axis = 0; axis < 3; ++axis) {
        const bool flat = lo[axis] == hi[axis];
        corners[axis] = flat ? -0.01f : static_cast<float>(lo[axis]);
        corners[3 + axis] = flat ? 0.01f : static_cast<float>(hi[axis]);
    }
    return corners;
}

} // namespace

struct ItemBuffer::Impl {
    struct Geometry {
        GLuint vao = 0, vertices = 0, indices = 0, uvs = 0;
        GLsizei index_count = 0;
    };
    // One instance's attributes (item.vert, locations 1 to 15).
    struct Instance {
        glm::mat4 model_view_projection; // computed in double, as for single draws
        glm::mat4 model;
        std::uint32_t object_id; // object index + 1
        glm::vec3 diffuse;
        glm::mat4 world_to_object; // proxies: M⁻¹
        glm::vec3 shape;           // proxies: ShapeKind, top radius, open (0 or 1)
    };

    GLuint mesh_program = 0, proxy_program = 0, cutout_program = 0, empty_vao = 0,
           instance_buffer = 0;
    GLuint framebuffer = 0, colour = 0, depth = 0;
    GLuint pack_buffers[2] = {0, 0}; // ids, depth
    GLuint flat_colour = 0; // RGBA8, attachment 1, made on the first flat-preview draw
    int width = 0, height = 0;
    int sample_grid = 1; // the draw's N: the target is N× the camera's image on each side
    std::vector<Geometry> geometries;
    std::vector<bool> proxy_geometry; // per geometry: a proxy box, drawn with proxy_program
    // Planes: full-screen passes of proxy_program, one by one with uniforms.
    std::vector<std::uint32_t> planes;
    // Per geometry, the objects drawn with it (a mesh, the tessellation of one shape, or one
    // proxy box): one instanced draw, each instance's attributes read from `instance_buffer`.
    std::vector<std::vector<std::uint32_t>> instances_of;
    // Cut-out meshes (DESIGN §13), drawn one by one with cutout_program: the object, its
    // geometry (positions and texture coordinates) and its alpha texture (0: none).
    struct CutOutDraw {
        std::uint32_t object;
        std::size_t geometry;
        GLuint alpha_texture;
    };
    std::vector<CutOutDraw> cut_outs;
    std::vector<GLuint> alpha_textures; // made by upload, one per image and wrap modes

    void release_alpha_textures() {
        if (!alpha_textures.empty())
            glDeleteTextures(static_cast<GLsizei>(alpha_textures.size()), alpha_textures.data());
        alpha_textures.clear();
    }

    // The texture's alpha as an R8 GL texture sampled as the tracer samples it (bilinear between
    // texel centres, its wrap modes, no mipmaps).
    GLuint alpha_texture(const Texture& texture) {
        const TextureImage& image = *texture.image;
        GLuint name = 0;
        glGenTextures(1, &name);
        alpha_textures.push_back(name);
        glBindTexture(GL_TEXTURE_2D, name);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, image.width, image.height, 0, GL_RED,
                     GL_UNSIGNED_BYTE, image.alpha.data());
        const auto wrap = [](Wrap mode) {
            return mode == Wrap::clamp    ? GL_CLAMP_TO_EDGE
                   : mode == Wrap::mirror ? GL_MIRRORED_REPEAT
                                          : GL_REPEAT;
        };
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap(texture.wrap_s));
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap(texture.wrap_t));
        glBindTexture(GL_TEXTURE_2D, 0);
        return name;
    }

    ~Impl() {
        for (const Geometry& g : geometries) release(g);
        release_alpha_textures();
        glDeleteProgram(cutout_program);
        glDeleteProgram(mesh_program);
        glDeleteProgram(proxy_program);
        glDeleteVertexArrays(1, &empty_vao);
        glDeleteBuffers(1, &instance_buffer);
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteBuffers(2, pack_buffers);
        glDeleteTextures(1, &colour);
        glDeleteRenderbuffers(1, &flat_colour);
        glDeleteRenderbuffers(1, &depth);
    }

    static void release(const Geometry& g) {
        glDeleteVertexArrays(1, &g.vao);
        glDeleteBuffers(1, &g.vertices);
        glDeleteBuffers(1, &g.indices);
        glDeleteBuffers(1, &g.uvs);
    }

    // `uvs`: per vertex, at location 1 (cut-out meshes), or none.
    std::size_t add_geometry(const std::vector<Vec3>& vertices,
                             const std::vector<glm::uvec3>& triangles,
                             const std::vector<glm::vec2>& uvs = {}) {
        Geometry g;
        glGenVertexArrays(1, &g.vao);
        glBindVertexArray(g.vao);
        glGenBuffers(1, &g.vertices);
        glBindBuffer(GL_ARRAY_BUFFER, g.vertices);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vec3)),
                     vertices.data(), GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
        if (!uvs.empty()) {
            glGenBuffers(1, &g.uvs);
            glBindBuffer(GL_ARRAY_BUFFER, g.uvs);
            glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(uvs.size() * sizeof(glm::vec2)),
                         uvs.data(), GL_STATIC_DRAW);
            glEnableVertexAttribArray(1);
            glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(glm::vec2), nullptr);
        }
        glGenBuffers(1, &g.indices);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.indices);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(triangles.size() * sizeof(glm::uvec3)),
                     triangles.data(), GL_STATIC_DRAW);
        g.index_count = static_cast<GLsizei>(triangles.size() * 3);
        glBindVertexArray(0);
        geometries.push_back(g);
        proxy_geometry.push_back(false);
        return geometries.size() - 1;
    }

    void add_instance(std::size_t geometry, std::uint32_t object) {
        if (geometry >= instances_of.size()) instances_of.resize(geometry + 1);
        instances_of[geometry].push_back(object);
    }

    // Points a geometry's VAO at its instances' records (divisor 1) in the bound instance buffer.
    static void bind_instances(std::size_t first) {
        const auto stride = static_cast<GLsizei>(sizeof(Instance));
        const auto at = [&](std::size_t offset) {
            return reinterpret_cast<const void*>(first * sizeof(Instance) + offset);
        };
        for (int column = 0; column < 8; ++column) { // two mat4s, a vec4 per location
            const GLuint location = 1 + column;
            const std::size_t base =
                column < 4 ? offsetof(Instance, model_view_projection) : offsetof(Instance, model);
            glEnableVertexAttribArray(location);
            glVertexAttribPointer(location, 4, GL_FLOAT, GL_FALSE, stride,
                                  at(base + (column % 4) * sizeof(glm::vec4)));
            glVertexAttribDivisor(location, 1);
        }
        glEnableVertexAttribArray(9);
        glVertexAttribIPointer(9, 1, GL_UNSIGNED_INT, stride, at(offsetof(Instance, object_id)));
        glVertexAttribDivisor(9, 1);
        glEnableVertexAttribArray(10);
        glVertexAttribPointer(10, 3, GL_FLOAT, GL_FALSE, stride, at(offsetof(Instance, diffuse)));
        glVertexAttribDivisor(10, 1);
        for (int column = 0; column < 4; ++column) {
            const GLuint location = 11 + column;
            glEnableVertexAttribArray(location);
            glVertexAttribPointer(
                location, 4, GL_FLOAT, GL_FALSE, stride,
                at(offsetof(Instance, world_to_object) + column * sizeof(glm::vec4)));
            glVertexAttribDivisor(location, 1);
        }
        glEnableVertexAttribArray(15);
        glVertexAttribPointer(15, 3, GL_FLOAT, GL_FALSE, stride, at(offsetof(Instance, shape)));
        glVertexAttribDivisor(15, 1);
    }

    void resize(int w, int h) {
        if (w == width && h == height) return;
        width = w, height = h;
        if (!framebuffer) {
            glGenFramebuffers(1, &framebuffer);
            glGenTextures(1, &colour);
            glGenRenderbuffers(1, &depth);
        }
        glBindTexture(GL_TEXTURE_2D, colour);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, w, h, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        if (flat_colour) attach_flat_colour();
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw GlError(
                "the item buffer's framebuffer (R32UI + 32-bit float depth) is incomplete");
    }

    void attach_flat_colour() {
        if (!flat_colour) glGenRenderbuffers(1, &flat_colour);
        glBindRenderbuffer(GL_RENDERBUFFER, flat_colour);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER,
                                  flat_colour);
    }

    // Clears ids to 0 and depth to 0 (reverse-Z: larger is nearer) and sets the pass's state;
    // with `flat_background`, also binds the flat-preview attachment, cleared to that colour.
    void begin(int w, int h, const Vec3* flat_background = nullptr) {
        resize(w, h);
        if (flat_background && !flat_colour) attach_flat_colour();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glDrawBuffers(flat_background ? 2 : 1, buffers);
        glViewport(0, 0, w, h);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDisable(GL_CULL_FACE); // cameras may sit inside objects; proxies draw both sides alike
        const GLuint zero_ids[4] = {0, 0, 0, 0};
        const GLfloat far_depth = 0.0f;
        glClearBufferuiv(GL_COLOR, 0, zero_ids);
        glClearBufferfv(GL_DEPTH, 0, &far_depth);
        if (flat_background) {
            const GLfloat background[4] = {flat_background->x, flat_background->y,
                                           flat_background->z, 1.0f};
            glClearBufferfv(GL_COLOR, 1, background);
        }
    }

    // The flat-preview attachment as an image, top row first.
    Image read_flat() {
        std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
        glReadBuffer(GL_COLOR_ATTACHMENT1);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        Image image(width, height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                std::copy_n(&rgba[(static_cast<std::size_t>(height - 1 - y) * width + x) * 4], 3,
                            image.pixel(x, y));
        return image;
    }

    void use_proxy_program(const PinholeCamera& camera, float near, bool flat_preview,
                           bool instanced);
    void draw_plane(const World& world, std::uint32_t object, const glm::dmat4& clip, float near,
                    bool flat_preview);
    void draw_instanced(const World& world, const glm::dmat4& clip, float near, bool flat_preview);
    void draw_cut_outs(const World& world, const glm::dmat4& clip, bool flat_preview);

    ItemBufferResult read_back(float near) {
        const std::size_t pixels = static_cast<std::size_t>(width) * height;
        const auto bytes = static_cast<GLsizeiptr>(pixels * 4);
        // The result's buffers first: draw() flushed the pass, so llvmpipe's threads rasterize
        // while this thread allocates (and faults in) 2 × 4 bytes a pixel.
        ItemBufferResult result;
        result.ids.width = width, result.ids.height = height;
        result.ids.ids.resize(pixels);
        result.ids.view_depth.resize(pixels);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        // Ids and depth through pixel-pack buffers: once warm, Mesa copies R32UI into one as it
        // is (9 ms at 1600×1200 on llvmpipe), where a plain glReadPixels or glGetTexImage
        // converts pixel by pixel (65 ms); depth lands there with no copy of our own.
        if (!pack_buffers[0]) glGenBuffers(2, pack_buffers);
        const auto read = [&](GLuint buffer, GLenum attachment, GLenum format, GLenum type) {
            glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
            glBufferData(GL_PIXEL_PACK_BUFFER, bytes, nullptr, GL_STREAM_READ);
            if (attachment != GL_NONE) glReadBuffer(attachment);
            glReadPixels(0, 0, width, height, format, type, nullptr);
        };
        read(pack_buffers[0], GL_COLOR_ATTACHMENT0, GL_RED_INTEGER, GL_UNSIGNED_INT);
        read(pack_buffers[1], GL_NONE, GL_DEPTH_COMPONENT, GL_FLOAT);
        const auto map = [&](GLuint buffer) {
            glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
            return glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, bytes, GL_MAP_READ_BIT);
        };
        const void* mapped[2] = {map(pack_buffers[0]), map(pack_buffers[1])};
        const auto* drawn = static_cast<const std::uint32_t*>(mapped[0]);
        const auto* depths = static_cast<const float*>(mapped[1]);
        if (drawn && depths) {
            std::uint32_t* ids = result.ids.ids.data();
            float* view_depth = result.ids.view_depth.data();
            for (int y = 0; y < height; ++y) {
                const std::size_t from =
                    static_cast<std::size_t>(height - 1 - y) * width; // GL's row 0 is the bottom
                const std::size_t to = static_cast<std::size_t>(y) * width;
                for (int x = 0; x < width; ++x) {
                    ids[to + x] = drawn[from + x];
                    const float d = depths[from + x];
                    view_depth[to + x] = d > 0 ? near / d : kInfinity;
                }
            }
        }
        for (int k = 0; k < 2; ++k) {
            glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffers[k]);
            if (mapped[k]) glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
        }
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        if (const GLenum error = glGetError(); error != GL_NO_ERROR)
            throw GlError("OpenGL error " + std::to_string(error) + " in the item-buffer pass");
        if (!drawn || !depths) throw GlError("the item buffer's read-back could not be mapped");
        return result;
    }
};

ItemBuffer::ItemBuffer() : impl_(std::make_unique<Impl>()) {
    Impl& gl = *impl_;
    gl.mesh_program = link(shaders::kItemVert, shaders::kItemMeshFrag);
    gl.proxy_program =
        link(shaders::kItemVert, with_shape_constants(shaders::kItemProxyFrag).c_str());
    gl.cutout_program = link(shaders::kItemCutoutVert, shaders::kItemCutoutFrag);
    glGenVertexArrays(1, &gl.empty_vao); // core profile draws need a VAO even with no attributes
    // llvmpipe compiles a program's machine code at its first draw (~0.1–0.2 s): draw each once
    // into a 1×1 target now, so that this cost counts as shader compilation, not as a frame.
    gl.begin(1, 1);
    glBindVertexArray(gl.empty_vao);
    for (const GLuint program : {gl.mesh_program, gl.proxy_program, gl.cutout_program}) {
        glUseProgram(program);
        glUniform1i(glGetUniformLocation(program, "full_screen"), 1);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glBindVertexArray(0);
}

ItemBuffer::~ItemBuffer() = default;

// One pass over the objects, sorting each by its shape's RasterAs into planes (full-screen), shared
// meshes, proxy boxes and instanced tessellations (the cases share the geometry maps built along
// the way).
void ItemBuffer::upload(const World& world, RasterMode mode, int tessellation) {
    Impl& gl = *impl_;
    for (const auto& g : gl.geometries) Impl::release(g);
    gl.geometries.clear();
    gl.proxy_geometry.clear();
    gl.planes.clear();
    gl.instances_of.clear();
    gl.cut_outs.clear();
    gl.release_alpha_textures();
    std::map<const Mesh*, std::size_t> mesh_geometry; // each mesh uploaded once
    // With the texture coordinates the alpha test reads, by set.
    std::map<std::pair<const Mesh*, int>, std::size_t> cut_out_geometry;
    std::map<std::tuple<const TextureImage*, Wrap, Wrap>, GLuint> alpha_of;
    deviations_.assign(world.objects().size(), 0.0f);
    // One proxy box per distinct object-space box, and one tessellation per distinct shape and
    // parameters (cones: per top radius; open or capped), shared by every object using it.
    std::map<std::array<float, 6>, std::size_t> proxies;
    // Tessellations are made when first asked for (auto mode reads their triangle counts), and
    // uploaded when first drawn.
    struct Shared {
        Tessellation tessellation;
        std::optional<std::size_t> geometry;
    };
    std::map<std::tuple<ShapeKind, float, bool>, Shared> shared;
    proxies_ = tessellated_ = 0;
    const PinholeCamera& camera = world.camera();
    for (std::uint32_t i = 0; i < world.objects().size(); ++i) {
        const Object& o = world.objects()[i];
        const ShapeTraits& traits = shape_traits(o.shape);
        if (traits.raster == RasterAs::analytic) {
            gl.planes.push_back(i);
            continue;
        }
        // Meshes that cut out or are one-sided (DESIGN §13, §14): drawn one by one, with the
        // alpha test and the face culling their intersections apply.
        if (traits.raster == RasterAs::triangles && o.params.cut_out) {
            const Mesh& mesh = *o.params.mesh;
            const CutOut& cut = *o.params.cut_out;
            const Texture* texture = cut.cuts ? cut.texture : nullptr;
            const int set = texture ? texture->set : 0;
            auto [it, added] = cut_out_geometry.emplace(std::pair{&mesh, set}, 0);
            if (added)
                it->second = gl.add_geometry(mesh.vertices, mesh.triangles, mesh_uvs(mesh, set));
            GLuint alpha = 0;
            if (texture && !mesh_uvs(mesh, set).empty() && !texture->image->alpha.empty()) {
                auto [t, made] = alpha_of.emplace(
                    std::make_tuple(texture->image.get(), texture->wrap_s, texture->wrap_t), 0);
                if (made) t->second = gl.alpha_texture(*texture);
                alpha = t->second;
            }
            gl.cut_outs.push_back({i, it->second, alpha});
            continue;
        }
        if (traits.raster == RasterAs::triangles) {
            auto [it, added] = mesh_geometry.emplace(o.params.mesh, 0);
            if (added) {
                const Mesh& mesh = *o.params.mesh;
                it->second = gl.add_geometry(mesh.vertices, mesh.triangles);
            }
            gl.add_instance(it->second, i);
            continue;
        }
        const ShapeKeys& keys = traits.keys;
        const float top_radius = keys.top_radius ? float(o.params.top_radius) : 0.0f;
        const bool open = keys.open && o.params.open;
        const auto key = std::make_tuple(o.shape, top_radius, open);
        const auto tessellation_of = [&]() -> Shared& {
            auto it = shared.find(key);
            if (it == shared.end())
                it = shared
                         .emplace(key, Shared{tessellate(o.shape, top_radius, tessellation, open),
                                              std::nullopt})
                         .first;
            return it->second;
        };
        // Auto: the cost model, with the object's projected bounds (all of the image when they
        // reach behind the eye).
        const auto proxy_pays = [&] {
            const std::optional<PixelRect> rect =
                project_bounds(camera, o.bounds, camera.width(), camera.height()).pixels;
            const double pixels = rect ? rect->area(camera.width(), camera.height())
                                       : double(camera.width()) * camera.height();
            return proxy_is_cheaper(double(tessellation_of().tessellation.triangles.size()),
                                    pixels);
        };
        if (traits.in_proxy_shader &&
            (mode == RasterMode::proxy || (mode == RasterMode::automatic && proxy_pays()))) {
            ++proxies_;
            const std::array<float, 6> box = proxy_box(o);
            auto [it, added] = proxies.emplace(box, 0);
            if (added) {
                const Vec3 lo(box[0], box[1], box[2]), hi(box[3], box[4], box[5]);
                Tessellation unit = tessellate(ShapeKind::box, 0, 4);
                for (Vec3& v : unit.vertices) v = lo + (v + 1.0f) * 0.5f * (hi - lo);
                it->second = gl.add_geometry(unit.vertices, unit.triangles);
                gl.proxy_geometry[it->second] = true;
            }
            gl.add_instance(it->second, i);
            continue;
        }
        Shared& mesh = tessellation_of();
        if (!mesh.geometry)
            mesh.geometry =
                gl.add_geometry(mesh.tessellation.vertices, mesh.tessellation.triangles);
        gl.add_instance(*mesh.geometry, i);
        ++tessellated_;
        // World-space bound: object deviation times ‖L‖_F ≥ ‖L‖₂, the most L stretches a length.
        const Mat3& l = o.transform.linear;
        const float stretch =
            std::sqrt(glm::dot(l[0], l[0]) + glm::dot(l[1], l[1]) + glm::dot(l[2], l[2]));
        deviations_[i] = mesh.tessellation.max_deviation * stretch;
    }
}

namespace {

// Near plane: 1e-24 of the scene's extent. Reverse-Z float depth (near / view depth) keeps its
// relative precision at every distance, so the near plane costs nothing by being close: it only
// has to keep the farthest depth, near / extent, a normal float (≥ 1.2e-38). Objects nearer than
// it to the eye are clipped; at a millionth of the extent a sphere one unit from the eye in a
// scene 1e6 across would lose the rim of its silhouette, and exact resolve could not
// recover pixels the id buffer never named it in (GlStability.ReverseZ…).
float near_plane(const World& world) {
    float extent = 1.0f;
    for (const Object& o : world.objects())
        if (o.bounded)
            extent = std::max({extent, max_component(glm::abs(o.bounds.lo)),
                               max_component(glm::abs(o.bounds.hi))});
    return extent * 1e-24f;
}

} // namespace

// The proxy program, with what every fragment of the frame shares: the camera, the near plane.
void ItemBuffer::Impl::use_proxy_program(const PinholeCamera& camera, float near, bool flat_preview,
                                         bool instanced) {
    glUseProgram(proxy_program);
    const auto uniform = [&](const char* name) {
        return glGetUniformLocation(proxy_program, name);
    };
    glUniform1i(uniform("flat_preview"), flat_preview);
    glUniform1i(uniform("instanced"), instanced);
    glUniform1i(uniform("full_screen"), !instanced);
    glUniform3fv(uniform("forward"), 1, glm::value_ptr(camera.forward()));
    const Vec3 right = camera.right_scaled(), up = camera.up_scaled();
    glUniform3fv(uniform("right_scaled"), 1, glm::value_ptr(right));
    glUniform3fv(uniform("up_scaled"), 1, glm::value_ptr(up));
    glUniform2f(uniform("viewport"), static_cast<float>(camera.width() * sample_grid),
                static_cast<float>(camera.height() * sample_grid));
    glUniform1f(uniform("near"), near);
}

// A plane: a full-screen pass of the proxy program, its object's M⁻¹, shape, id and colour as
// uniforms.
void ItemBuffer::Impl::draw_plane(const World& world, std::uint32_t object, const glm::dmat4& clip,
                                  float near, bool flat_preview) {
    const Object& o = world.objects()[object];
    use_proxy_program(world.camera(), near, flat_preview, false);
    const auto uniform = [&](const char* name) {
        return glGetUniformLocation(proxy_program, name);
    };
    const glm::dmat4 model = to_mat4(o.transform.linear, o.transform.offset);
    glUniformMatrix4fv(uniform("model_view_projection"), 1, GL_FALSE,
                       glm::value_ptr(glm::mat4(clip * model)));
    glUniform3fv(uniform("diffuse"), 1, glm::value_ptr(world.material(object).diffuse));
    glUniform1ui(uniform("object_id"), object + 1);
    const glm::mat4 inverse(to_mat4(o.transform.inverse_linear, o.transform.inverse_offset));
    glUniformMatrix4fv(uniform("world_to_object"), 1, GL_FALSE, glm::value_ptr(inverse));
    glUniform1i(uniform("shape"), static_cast<int>(o.shape));
    glUniform1f(uniform("top_radius"), o.params.top_radius);
    glUniform1i(uniform("open"), o.params.open);
    glBindVertexArray(empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Every tessellated shape, mesh and proxy box: one instanced draw per geometry, with the
// instances' matrices composed in double (as for planes), then uploaded in one buffer.
void ItemBuffer::Impl::draw_instanced(const World& world, const glm::dmat4& clip, float near,
                                      bool flat_preview) {
    Impl& gl = *this;
    std::vector<Impl::Instance> instances;
    for (const std::vector<std::uint32_t>& objects : gl.instances_of)
        for (const std::uint32_t object : objects) {
            const Object& o = world.objects()[object];
            const glm::dmat4 model = to_mat4(o.transform.linear, o.transform.offset);
            instances.push_back(
                {glm::mat4(clip * model), glm::mat4(model), object + 1,
                 world.material(object).diffuse,
                 glm::mat4(to_mat4(o.transform.inverse_linear, o.transform.inverse_offset)),
                 glm::vec3(static_cast<float>(o.shape), o.params.top_radius,
                           o.params.open ? 1.0f : 0.0f)});
        }
    if (!gl.instance_buffer) glGenBuffers(1, &gl.instance_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, gl.instance_buffer);
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(instances.size() * sizeof(Impl::Instance)),
                 instances.data(), GL_STREAM_DRAW);
    // Each program's uniforms are its own state: set once, kept while the other draws.
    use_proxy_program(world.camera(), near, flat_preview, true);
    glUseProgram(gl.mesh_program);
    const auto uniform = [&](const char* name) {
        return glGetUniformLocation(gl.mesh_program, name);
    };
    glUniform1i(uniform("flat_preview"), flat_preview);
    glUniform1i(uniform("instanced"), 1);
    glUniform1i(uniform("full_screen"), 0);
    std::size_t first = 0;
    for (std::size_t geometry = 0; geometry < gl.instances_of.size(); ++geometry) {
        const std::size_t count = gl.instances_of[geometry].size();
        if (count == 0) continue;
        glUseProgram(gl.proxy_geometry[geometry] ? gl.proxy_program : gl.mesh_program);
        glBindVertexArray(gl.geometries[geometry].vao);
        Impl::bind_instances(first);
        glDrawElementsInstanced(GL_TRIANGLES, gl.geometries[geometry].index_count, GL_UNSIGNED_INT,
                                nullptr, static_cast<GLsizei>(count));
        first += count;
    }
}

// Cut-out meshes, one draw each: matrices composed in double as for the others, and the alpha
// test's factor, cut-off and texture as uniforms.
void ItemBuffer::Impl::draw_cut_outs(const World& world, const glm::dmat4& clip,
                                     bool flat_preview) {
    glUseProgram(cutout_program);
    const auto uniform = [&](const char* name) {
        return glGetUniformLocation(cutout_program, name);
    };
    glUniform1i(uniform("flat_preview"), flat_preview);
    glUniform1i(uniform("alpha_texture"), 0);
    glActiveTexture(GL_TEXTURE0);
    // Looked up once, set per object.
    const GLint mvp_at = uniform("model_view_projection"), model_at = uniform("model"),
                id_at = uniform("object_id"), diffuse_at = uniform("diffuse"),
                alpha_at = uniform("alpha"), cutoff_at = uniform("cutoff"),
                textured_at = uniform("textured"), uv_at = uniform("uv_transform");
    for (const CutOutDraw& d : cut_outs) {
        const Object& o = world.objects()[d.object];
        const CutOut& cut = *o.params.cut_out;
        const glm::dmat4 model = to_mat4(o.transform.linear, o.transform.offset);
        glUniformMatrix4fv(mvp_at, 1, GL_FALSE, glm::value_ptr(glm::mat4(clip * model)));
        glUniformMatrix4fv(model_at, 1, GL_FALSE, glm::value_ptr(glm::mat4(model)));
        glUniform1ui(id_at, d.object + 1);
        glUniform3fv(diffuse_at, 1, glm::value_ptr(world.material(d.object).diffuse));
        glUniform1f(alpha_at, cut.alpha);
        glUniform1f(cutoff_at, cut.cuts ? cut.cutoff : 0.0f);
        // One-sided faces: the side the intersection keeps (counter-clockwise in object space)
        // is GL's front face, counter-clockwise in the window under a positive determinant and
        // clockwise under a negative one (glTF 2.0, 3.7.4).
        if (cut.one_sided) {
            glEnable(GL_CULL_FACE);
            glCullFace(GL_BACK);
            glFrontFace(glm::determinant(o.transform.linear) > 0 ? GL_CCW : GL_CW);
        } else {
            glDisable(GL_CULL_FACE);
        }
        glUniform1i(textured_at, d.alpha_texture != 0);
        const glm::mat3 uv_transform = cut.texture ? cut.texture->uv_transform : glm::mat3(1.0f);
        glUniformMatrix3fv(uv_at, 1, GL_FALSE, glm::value_ptr(uv_transform));
        glBindTexture(GL_TEXTURE_2D, d.alpha_texture);
        glBindVertexArray(geometries[d.geometry].vao);
        glDrawElements(GL_TRIANGLES, geometries[d.geometry].index_count, GL_UNSIGNED_INT, nullptr);
    }
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glBindTexture(GL_TEXTURE_2D, 0);
}

ItemBufferResult ItemBuffer::draw(const World& world, bool flat_preview, int samples) {
    Impl& gl = *impl_;
    const PinholeCamera& camera = world.camera();
    const float near = near_plane(world);
    // The projection maps the view to NDC whatever the target's size: drawn at N× the size, GL
    // pixel (N·i + a, N·j + b)'s centre is sample (a, b) of pixel (i, j) (DESIGN §11).
    const glm::dmat4 clip = projection(camera, near);
    const Vec3 background = world.background();
    const int width = camera.width() * samples, height = camera.height() * samples;
    GLint limits[3] = {0, 0, 0}, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits[0]);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &limits[1]);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    limits[2] = std::min(viewport[0], viewport[1]);
    const int limit = *std::min_element(limits, limits + 3);
    if (std::max(width, height) > limit)
        throw GlError("an item buffer of " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds this GL's largest target side, " + std::to_string(limit));
    gl.sample_grid = samples;
    ++draws_;
    gl.begin(width, height, flat_preview ? &background : nullptr);
    for (const std::uint32_t plane : gl.planes)
        gl.draw_plane(world, plane, clip, near, flat_preview);
    if (!gl.instances_of.empty()) gl.draw_instanced(world, clip, near, flat_preview);
    if (!gl.cut_outs.empty()) gl.draw_cut_outs(world, clip, flat_preview);
    glBindVertexArray(0);
    glFlush(); // llvmpipe starts rasterizing on its threads; read_back waits for it
    ItemBufferResult result = gl.read_back(near);
    if (flat_preview) result.flat = gl.read_flat();
    return result;
}

ItemBufferResult ItemBuffer::draw_triangle_for_test(const World& world, const Vec3 (&corners)[3],
                                                    std::uint32_t object_id) {
    Impl& gl = *impl_;
    const PinholeCamera& camera = world.camera();
    const float near = near_plane(world);
    const std::size_t geometry = gl.add_geometry({corners[0], corners[1], corners[2]}, {{0, 1, 2}});
    gl.begin(camera.width(), camera.height());
    glUseProgram(gl.mesh_program);
    const glm::mat4 mvp(projection(camera, near));
    glUniformMatrix4fv(glGetUniformLocation(gl.mesh_program, "model_view_projection"), 1, GL_FALSE,
                       glm::value_ptr(mvp));
    glUniform1i(glGetUniformLocation(gl.mesh_program, "full_screen"), 0);
    glUniform1i(glGetUniformLocation(gl.mesh_program, "instanced"), 0);
    glUniform1ui(glGetUniformLocation(gl.mesh_program, "object_id"), object_id);
    glBindVertexArray(gl.geometries[geometry].vao);
    glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    return gl.read_back(near);
}

} // namespace glint
