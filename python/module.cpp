// The Python module `glint` (docs/PYTHON.md): load a scene, render it into NumPy arrays, explain a
// pixel, compare two settings. Every call goes through app/library.h, which reads the keywords
// with the command line's own options; this file only turns Python values into the command
// line's words and glint's results into Python objects. The GIL is released while glint works,
// and Ctrl-C stops a render between tiles.
#include "app/library.h"

#include "frame/difference_maps.h"
#include "frame/gl_pass.h"
#include "io/error.h"
#include "trace/ray_tree.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <regex>
#include <thread>

namespace py = pybind11;

namespace glint {
namespace {

// Python values in the command line's words: True/False for flags, numbers as Python writes
// them (floats by repr: the shortest text that reads back to the same double), text as given,
// `size` (w, h) as WxH, `sample` (a, b) as A,B, and a list (aovs) as one value each.
std::vector<std::string> spelled(const std::string& name, py::handle value) {
    if (py::isinstance<py::bool_>(value)) return {value.cast<bool>() ? "true" : "false"};
    if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
    // Integers and floats, NumPy's scalars among them (np.int64 has __index__, np.float32
    // __float__).
    if (PyIndex_Check(value.ptr()))
        return {py::str(py::int_(py::reinterpret_borrow<py::object>(value))).cast<std::string>()};
    if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
        return {
            py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>()};
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
        const char* joint = name == "size" ? "x" : name == "sample" ? "," : nullptr;
        std::vector<std::string> values;
        for (const py::handle item : items) {
            if (py::isinstance<py::list>(item) || py::isinstance<py::tuple>(item))
                throw SettingError(name, name + ": a list of lists is not a value glint reads");
            values.push_back(spelled(name, item).front());
        }
        if (!joint) return values;
        if (values.size() != 2)
            throw SettingError(name, name + ": expected two numbers, (" +
                                         std::string(name == "size" ? "width, height" : "a, b") +
                                         ")");
        return {values[0] + joint + values[1]};
    }
    throw SettingError(name, name + ": a " +
                                 py::str(py::type::of(value).attr("__name__")).cast<std::string>() +
                                 " is not a value glint reads");
}

// The keyword arguments given (None: not given).
Keywords keywords(const py::kwargs& kwargs) {
    Keywords given;
    for (const auto& [key, value] : kwargs) {
        if (value.is_none()) continue;
        const std::string name = key.cast<std::string>();
        given.push_back({name, spelled(name, value)});
    }
    return given;
}

// A side of Scene.compare in `glint compare --a`'s words: a str as given ("--max-depth 2",
// "exact"), or a dict of keywords ({"max_depth": 2}; "exact": True starts from the exact image).
std::string side_flags(const char* which, py::handle side) {
    if (py::isinstance<py::str>(side)) return side.cast<std::string>();
    if (!py::isinstance<py::dict>(side))
        throw SettingError(which, std::string(which) + ": a dict of settings or a str of flags");
    bool exact = false;
    std::string flags;
    const auto add = [&](const std::string& word) { flags += (flags.empty() ? "" : " ") + word; };
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(side)) {
        const std::string name = key.cast<std::string>();
        if (name == "exact") {
            exact = value.cast<bool>();
            continue;
        }
        const std::string flag = flag_of(name);
        for (const std::string& v : spelled(name, value)) {
            if (v != "false") add(flag);
            if (v != "true" && v != "false") add(v);
        }
    }
    return exact ? "exact" + (flags.empty() ? "" : " " + flags) : flags;
}

// The calls' names in Python, for TypeError's message.
const char* call_name(Call call) {
    switch (call) {
    case Call::load:
        return "glint.load()";
    case Call::render:
        return "Scene.render()";
    case Call::explain:
        return "Scene.explain()";
    case Call::compare:
        return "Scene.compare()";
    }
    return "glint";
}

// Runs a call, turning an unknown keyword into Python's TypeError with the call's keywords.
template <class F> auto call(Call which, const F& body) {
    try {
        return body();
    } catch (const UnknownSetting& e) {
        std::string names;
        for (const std::string& name : keywords_of(which))
            names += (names.empty() ? "" : ", ") + name;
        throw py::type_error(std::string(call_name(which)) +
                             " got an unexpected keyword argument '" + e.what() +
                             "' (it takes: " + names + ")");
    }
}

// Runs `work(cancel)` on a thread of its own with the GIL released; the calling thread checks
// for Python's signals every 50 ms, and on one (Ctrl-C) sets `cancel`, waits for the work to
// stop between tiles, and raises the signal's exception (KeyboardInterrupt).
template <class F> auto interruptible(const F& work) {
    using Result = decltype(work(nullptr));
    std::atomic<bool> cancel{false};
    std::optional<Result> result;
    std::exception_ptr error;
    bool interrupted = false;
    {
        const py::gil_scoped_release release;
        std::mutex mutex;
        std::condition_variable finished;
        bool done = false;
        std::thread worker([&] {
            try {
                result.emplace(work(&cancel));
            } catch (...) {
                error = std::current_exception();
            }
            const std::lock_guard lock(mutex);
            done = true;
            finished.notify_one();
        });
        std::unique_lock lock(mutex);
        while (!finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
            if (interrupted) continue;
            lock.unlock();
            {
                const py::gil_scoped_acquire acquire;
                // Signals reach Python's main thread only; elsewhere this returns 0.
                if (PyErr_CheckSignals() != 0) interrupted = true; // the exception stays set
            }
            if (interrupted) cancel = true;
            lock.lock();
        }
        lock.unlock();
        worker.join();
    }
    if (interrupted) throw py::error_already_set(); // KeyboardInterrupt, or the handler's own
    if (error) std::rethrow_exception(error);
    return std::move(*result);
}

// An array over memory that `owner` keeps alive (no copy), read-only: glint's result is shared,
// not handed over (np.array(a) makes a copy to change).
template <class T>
py::array view(const py::object& owner, const T* data, std::vector<py::ssize_t> shape) {
    py::array_t<T> array(std::move(shape), data, owner);
    array.attr("flags").attr("writeable") = false;
    return array;
}

// An array that owns a vector glint made (moved, not copied).
template <class T, class Alloc>
py::array owned(std::vector<T, Alloc>&& values, std::vector<py::ssize_t> shape) {
    auto* held = new std::vector<T, Alloc>(std::move(values));
    const py::capsule free(held, [](void* p) { delete static_cast<std::vector<T, Alloc>*>(p); });
    return py::array_t<T>(std::move(shape), held->data(), free);
}

py::object parsed_json(const std::string& text) {
    return py::module_::import("json").attr("loads")(text);
}

// A Python Frame: one render's result, shared with the arrays made of it.
struct PyFrame {
    RenderedFrame rendered;
    int width() const { return rendered.width; }
    int height() const { return rendered.height; }
    bool has(Aov aov) const {
        return std::find(rendered.aovs.begin(), rendered.aovs.end(), aov) != rendered.aovs.end();
    }
};

// A layer that only aovs=[…] keeps: AttributeError saying how to ask for it.
void require(const PyFrame& f, Aov aov) {
    if (!f.has(aov)) {
        const std::string name(name_of(aov));
        throw py::attribute_error(name + ": not kept; render with aovs=['" + name + "']");
    }
}

// A Frame property that is a view of one of its layers: `data` finds the layer, `channels` a
// pixel (1: H×W), `aov` the layer render(aovs=[…]) must have asked for (none: always there).
template <class Data>
void add_layer(py::class_<PyFrame, std::shared_ptr<PyFrame>>& frame, const char* name,
               std::optional<Aov> aov, py::ssize_t channels, Data data, const char* doc) {
    frame.def_property_readonly(
        name,
        [aov, channels, data](const py::object& self) {
            const PyFrame& f = self.cast<const PyFrame&>();
            if (aov) require(f, *aov);
            std::vector<py::ssize_t> shape{f.height(), f.width()};
            if (channels > 1) shape.push_back(channels);
            return view(self, data(f), std::move(shape));
        },
        doc);
}

struct PyScene {
    LoadedScene loaded;
};

// glint.SceneError: bad input, with the file and the place the message names. Kept for the
// process's life (a py::object here would be released after the interpreter has gone).
PyObject* scene_error_type = nullptr;

// The file, the place (a JSON pointer, "line N" or "line N, column M") and what is wrong, from
// a SceneError's message ("file: /pointer: what", "file:LINE: what", "file:LINE:COL: what").
std::tuple<std::string, std::string, std::string> scene_error_parts(const std::string& message) {
    static const std::regex pointer(R"(^(.*?): (/[^:]*): (.*)$)");
    static const std::regex line(R"(^(.*?):(\d+)(?::(\d+))?: (.*)$)");
    static const std::regex file(R"(^(.*?): (.*)$)");
    std::smatch m;
    if (std::regex_match(message, m, line))
        return {m[1], "line " + m[2].str() + (m[3].matched ? ", column " + m[3].str() : ""), m[4]};
    if (std::regex_match(message, m, pointer)) return {m[1], m[2], m[3]};
    if (std::regex_match(message, m, file)) return {m[1], "", m[2]};
    return {"", "", message};
}

void translate(std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const SceneError& e) {
        const auto [file, place, what] = scene_error_parts(e.what());
        py::object instance = py::reinterpret_borrow<py::object>(scene_error_type)(e.what());
        instance.attr("file") = file;
        instance.attr("place") = place.empty() ? py::object(py::none()) : py::str(place);
        instance.attr("detail") = what;
        PyErr_SetObject(scene_error_type, instance.ptr());
    } catch (const UsageError& e) {
        PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const GlError& e) {
        const std::string message = std::string("no OpenGL for the item buffer: ") + e.what() +
                                    " (render without GL with mode='ray')";
        PyErr_SetString(PyExc_RuntimeError, message.c_str());
    } catch (const Cancelled&) {
        PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
}

// Scene.compare's result: the measures (`glint compare --json`'s), the per-pixel error and cause,
// the maps, and each side's frame.
py::dict comparison(ComparedSides c) {
    const FrameDifference& d = c.difference;
    const py::ssize_t h = d.height, w = d.width;
    py::dict out;
    out["measures"] = parsed_json(c.json);
    std::vector<std::uint8_t> causes(d.causes.size());
    for (std::size_t i = 0; i < causes.size(); ++i)
        causes[i] = static_cast<std::uint8_t>(d.causes[i]);
    py::list names;
    for (std::size_t k = 0; k < kCauses; ++k)
        names.append(std::string(name_of(static_cast<Cause>(k))));
    const auto a = std::make_shared<PyFrame>(PyFrame{side_frame(*c.a)}); // its bytes made once
    out["error"] = owned(std::vector<float>(d.error), {h, w});
    out["causes"] = owned(std::move(causes), {h, w});
    out["cause_names"] = names;
    // The maps as `glint compare -o` writes them: the frame's pixels, then the legend's strip.
    const auto picture = [](Image image) {
        const py::ssize_t rows = image.height, columns = image.width;
        return owned(std::move(image.rgb), {rows, columns, 3});
    };
    out["heat_map"] = picture(heat_map(d));
    out["cause_map"] = picture(cause_map(d, a->rendered.image));
    out["a"] = py::cast(a);
    out["b"] = py::cast(std::make_shared<PyFrame>(PyFrame{side_frame(*c.b)}));
    return out;
}

} // namespace
} // namespace glint

PYBIND11_MODULE(glint, m) {
    using namespace glint;
    m.doc() = "glint: a hybrid item-buffer / ray-tracing renderer, in NumPy arrays "
              "(docs/PYTHON.md)";
    scene_error_type =
        PyErr_NewExceptionWithDoc("glint.SceneError",
                                  "Bad input in a scene file: .file, .place (a JSON pointer or "
                                  "'line N'; None where the message names none) and .detail",
                                  PyExc_Exception, nullptr);
    if (!scene_error_type) throw py::error_already_set();
    m.attr("SceneError") = py::reinterpret_borrow<py::object>(scene_error_type);
    py::register_exception_translator(&translate);

    py::class_<PyFrame, std::shared_ptr<PyFrame>> frame(
        m, "Frame", "One render: arrays share its memory (read-only) and live as long as it");
    frame.def_property_readonly("width", &PyFrame::width)
        .def_property_readonly("height", &PyFrame::height);
    const auto radiance = [](const PyFrame& f) {
        return f.rendered.frame.result.radiance.rgb.data();
    };
    const auto bytes = [](const PyFrame& f) { return f.rendered.image.rgb.data(); };
    const auto aovs = [](const PyFrame& f) -> const PrimaryAovs& {
        return f.rendered.frame.result.aovs;
    };
    add_layer(frame, "rgb", std::nullopt, 3, radiance,
              "float32 H×W×3: linear radiance, unclamped (the EXR's R, G, B)");
    add_layer(frame, "image", std::nullopt, 3, bytes, "uint8 H×W×3: the PNG's bytes");
    add_layer(
        frame, "depth", Aov::depth, 1, [aovs](const PyFrame& f) { return aovs(f).depth.data(); },
        "float32 H×W: the pixel centre's primary hit distance, inf for none "
        "(aovs=['depth'])");
    add_layer(
        frame, "normal", Aov::normal, 3, [aovs](const PyFrame& f) { return aovs(f).normal.data(); },
        "float32 H×W×3: the unit shading normal facing the eye (aovs=['normal'])");
    add_layer(
        frame, "id", Aov::id, 1, [aovs](const PyFrame& f) { return aovs(f).id.data(); },
        "uint32 H×W: object index + 1, 0 for none (aovs=['id'])");
    add_layer(
        frame, "cutoff", Aov::cutoff, 1, [](const PyFrame& f) { return f.rendered.cutoff.data(); },
        "float32 H×W: the radiance the cut-off may have left out, a bound "
        "(aovs=['cutoff'])");
    frame
        .def_property_readonly(
            "stats",
            [](const PyFrame& f) -> py::object {
                if (f.rendered.stats.empty()) return py::none();
                return parsed_json(f.rendered.stats);
            },
            "`glint render --stats`'s fields as a dict (None for a comparison's sides)")
        .def("__repr__", [](const PyFrame& f) {
            return "<glint.Frame " + std::to_string(f.width()) + "x" + std::to_string(f.height()) +
                   ">";
        });

    py::class_<PyScene>(m, "Scene", "A scene read by glint.load")
        .def_property_readonly("path", [](const PyScene& s) { return s.loaded.path.string(); })
        .def_property_readonly("size",
                               [](const PyScene& s) {
                                   return py::make_tuple(s.loaded.scene->camera.width,
                                                         s.loaded.scene->camera.height);
                               })
        .def_property_readonly("objects",
                               [](const PyScene& s) { return s.loaded.scene->objects.size(); })
        .def(
            "render",
            [](const PyScene& s, const py::kwargs& kwargs) {
                const Keywords given = call(Call::render, [&] { return keywords(kwargs); });
                RenderedFrame r = call(Call::render, [&] {
                    return interruptible([&](const std::atomic<bool>* cancel) {
                        return render_by_keywords(s.loaded, given, cancel);
                    });
                });
                return std::make_shared<PyFrame>(PyFrame{std::move(r)});
            },
            "render(mode=, size=(w, h), samples=, aa=, max_depth=, min_reflectivity=, accel=, "
            "raster=, tess=, resolve=, threads=, aovs=[…], …) -> Frame: `glint render`'s "
            "settings by keyword")
        .def(
            "explain",
            [](const PyScene& s, int x, int y, const py::object& sample, const py::kwargs& kwargs) {
                Keywords given = call(Call::explain, [&] { return keywords(kwargs); });
                if (!sample.is_none()) given.push_back({"sample", spelled("sample", sample)});
                std::string json;
                {
                    const py::gil_scoped_release release;
                    json = call(Call::explain,
                                [&] { return explain_by_keywords(s.loaded, x, y, given); });
                }
                return parsed_json(json);
            },
            py::arg("x"), py::arg("y"), py::arg("sample") = py::none(),
            "explain(x, y, sample=(a, b), **settings) -> dict: `glint explain --json`'s tree "
            "(against=… as --against)")
        .def(
            "compare",
            [](const PyScene& s, const py::object& a, const py::object& b,
               const py::kwargs& kwargs) {
                const Keywords given = call(Call::compare, [&] { return keywords(kwargs); });
                const std::string a_flags = a.is_none() ? "--mode ray" : side_flags("a", a);
                const std::string b_flags = b.is_none() ? "--mode hybrid" : side_flags("b", b);
                ComparedSides c = call(Call::compare, [&] {
                    return interruptible([&](const std::atomic<bool>* cancel) {
                        return compare_by_keywords(s.loaded, a_flags, b_flags, given, cancel);
                    });
                });
                return comparison(std::move(c));
            },
            py::arg("a") = py::none(), py::arg("b") = py::none(),
            "compare(a={…}, b={…}, **settings) -> dict: `glint compare --a --b`'s measures, the "
            "per-pixel error and causes, the heat and cause maps, and both sides' frames "
            "(default: ray against hybrid)")
        .def("__repr__", [](const PyScene& s) {
            return "<glint.Scene " + s.loaded.path.string() + ", " +
                   std::to_string(s.loaded.scene->objects.size()) + " objects>";
        });

    m.def(
        "load",
        [](const std::string& path, const py::kwargs& kwargs) {
            const Keywords given = call(Call::load, [&] { return keywords(kwargs); });
            const py::gil_scoped_release release;
            return call(Call::load, [&] { return PyScene{load_by_keywords(path, given)}; });
        },
        py::arg("path"),
        "load(path, camera=None, time=None, animation=None) -> Scene: JSON, NFF, OBJ, glTF or "
        "GLB; glint.SceneError on bad input");
    m.def(
        "keywords",
        [](const std::string& which) {
            static const std::map<std::string, Call> calls = {{"load", Call::load},
                                                              {"render", Call::render},
                                                              {"explain", Call::explain},
                                                              {"compare", Call::compare}};
            const auto it = calls.find(which);
            if (it == calls.end())
                throw py::value_error("keywords: load, render, explain or compare");
            return keywords_of(it->second);
        },
        "The settings a call takes, by keyword (the command line's flags, - as _)");
}
