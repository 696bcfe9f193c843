// The Python module `tfu` (docs/python.md): the libraries the `tfu` command line calls, for
// notebooks. Every function here composes calls of tfu_cmodel, tfu_rtl and tfu_sweep as the
// subcommand of the same name does (sim/tfu/cmd_*.cpp); none computes a texel, a cycle or a
// statistic of its own. Arrays cross the boundary as numpy arrays (copied: an Image is row-major
// RGBA8 words, row 0 on top, so an H x W x 4 uint8 array); statistics as the dictionaries of the
// statistics file `tfu sim --stats` writes.
//
// Errors: tfu::InputError raises tfu.InputError (a ValueError), CheckFailed tfu.CheckFailed,
// DeadlockError tfu.DeadlockError (both RuntimeErrors), each with the one-line message the command
// line prints after "tfu: error: " and "tfu: check failed: ", and a deadlock's summary line (the
// command line also writes the per-stage dump to a file).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/bindings.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/q3_level.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_frame.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/trace.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/sweep/sweep_report.hpp"
#include "sim/sweep/sweep_run.hpp"
#include "sim/sweep/sweep_spec.hpp"
#include "sim/sweep/version.hpp"

namespace py = pybind11;

namespace tfu::python {
namespace {

using U8Array = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>;

// ---- Values between Python and the model ----

// A key's value as the tables read it (bindings.hpp, unit_config.hpp): text. Python's True/False
// become "true"/"false", numbers their decimal text.
std::string value_text(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  return py::str(v).cast<std::string>();
}

Params params_from_kwargs(const py::kwargs& kw) {
  Params p;
  for (const auto& [k, v] : kw) p[k.cast<std::string>()] = value_text(v);
  return p;
}

py::object json_to_python(const std::string& text) { return py::module_::import("json").attr("loads")(text); }
std::string python_to_json(const py::handle& obj) {
  return py::module_::import("json").attr("dumps")(obj).cast<std::string>();
}

py::array image_array(const Image& img) {
  U8Array a({static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width), py::ssize_t{4}});
  if (!img.texels.empty()) std::memcpy(a.mutable_data(), img.texels.data(), img.texels.size() * sizeof(Rgba8));
  return a;
}

py::array pixels_array(const std::vector<Rgba8>& px) {
  U8Array a({static_cast<py::ssize_t>(px.size()), py::ssize_t{4}});
  if (!px.empty()) std::memcpy(a.mutable_data(), px.data(), px.size() * sizeof(Rgba8));
  return a;
}

// An H x W x 4 uint8 array (RGBA8 words) as an image; `what` names it in errors.
Image image_from_array(const py::handle& obj, const std::string& what) {
  const U8Array a = U8Array::ensure(obj);
  if (!a || a.ndim() != 3 || a.shape(2) != 4)
    throw InputError(fmt::format("{}: expected an H x W x 4 uint8 array (RGBA8)", what));
  if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > kMaxTextureSize * 4 || a.shape(1) > kMaxTextureSize * 4)
    throw InputError(fmt::format("{}: {} x {} pixels is out of range", what, a.shape(1), a.shape(0)));
  Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
  std::memcpy(img.texels.data(), a.data(), img.texels.size() * sizeof(Rgba8));
  return img;
}

// ---- Textures and samplers ----

struct PyTexture {
  std::shared_ptr<const Texture> texture;
  TextureSpec spec;  // how it was made (a file, proc:, oa:, or "array:NAME" for numpy arrays)
};

// A texture from a file, proc:NAME[:SIZE] or oa:MAP:texture:NAME with the texture keys
// (load_texture_spec, as `--texture` and a trace's `# tfu-texture` line).
PyTexture texture_from_source(const std::string& source, const std::string& game_dir, const py::kwargs& keys) {
  PyTexture t;
  t.spec = {source, params_from_kwargs(keys)};
  py::gil_scoped_release unlocked;
  t.texture = load_texture_spec(t.spec, "texture", {}, game_dir).texture;
  return t;
}

// A texture from a numpy array: H x W x 4 uint8 (RGBA8 words; with format="vs16x2" the bytes of two
// Strzodka numbers, as the file key reinterprets a file), H x W uint8 (L8), or H x W x 2 int16
// (VS16X2 numerators, -32640..32640, packed by encode_texel). The keys then apply as to a file.
PyTexture texture_from_array(const py::array& array, const std::string& name, const py::kwargs& keys) {
  Texture tex;
  Params params = params_from_kwargs(keys);
  const std::string where = fmt::format("texture array:{}", name);
  if (array.ndim() == 3 && array.shape(2) == 2 && py::dtype::of<int16_t>().is(array.dtype())) {
    const auto a = py::array_t<int16_t, py::array::c_style | py::array::forcecast>::ensure(array);
    Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    const int16_t* v = a.data();
    const auto [lo, hi] = channel_range(TexelFormat::VS16X2);
    for (size_t i = 0; i < img.texels.size(); ++i) {
      if (v[2 * i] < lo || v[2 * i] > hi || v[2 * i + 1] < lo || v[2 * i + 1] > hi)
        throw InputError(
            fmt::format("{}: texel {} holds a numerator outside {}..{} (Strzodka's -1..+1)", where, i, lo, hi));
      img.texels[i] = encode_texel({v[2 * i], v[2 * i + 1], 0, 0}, TexelFormat::VS16X2);
    }
    tex.levels.push_back(std::move(img));
    if (params.contains("format") && params["format"] != "vs16x2")
      throw InputError(fmt::format("{}: key 'format': an int16 H x W x 2 array is vs16x2", where));
    params["format"] = "vs16x2";
  } else if (array.ndim() == 2 && py::dtype::of<uint8_t>().is(array.dtype())) {
    const auto a = U8Array::ensure(array);
    Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    for (size_t i = 0; i < img.texels.size(); ++i) img.texels[i] = {a.data()[i], a.data()[i], a.data()[i], 255};
    tex.levels.push_back(std::move(img));
    if (params.contains("format") && params["format"] != "l8")
      throw InputError(fmt::format("{}: key 'format': an H x W uint8 array is l8", where));
    params["format"] = "l8";
  } else if (array.ndim() == 3 && array.shape(2) == 4 && py::dtype::of<uint8_t>().is(array.dtype())) {
    tex.levels.push_back(image_from_array(array, where));
  } else {
    throw InputError(
        fmt::format("{}: expected H x W x 4 uint8 (RGBA8), H x W uint8 (L8) or H x W x 2 int16 (VS16X2), got "
                    "{} dimensions of {}",
                    where, array.ndim(), py::str(array.dtype()).cast<std::string>()));
  }
  tex.validate(where);
  PyTexture t;
  t.spec = {"array:" + name, params};
  py::gil_scoped_release unlocked;
  t.texture = std::make_shared<const Texture>(texture_with_params(std::move(tex), params, where));
  return t;
}

struct PySampler {
  SamplerDescriptor descriptor;
};

PySampler make_sampler(const py::kwargs& keys) { return {sampler_from_params(params_from_kwargs(keys), "sampler")}; }

// The fields of a descriptor's register words, decoded by the field table: {name: value} (array
// fields as lists, one element per level).
template <size_t N>
py::dict register_fields(std::span<const RegisterField> table, const std::array<uint32_t, N>& words) {
  py::dict d;
  for (const RegisterField& f : table) {
    const auto field = [&](int k) {
      const int word = f.word + k * f.stride;
      const uint64_t mask = f.width >= 32 ? 0xffffffffu : (uint64_t{1} << f.width) - 1;
      return static_cast<uint64_t>(words[static_cast<size_t>(word)] >> f.lsb) & mask;
    };
    if (f.count == 1) {
      d[f.name] = field(0);
    } else {
      py::list l;
      for (int k = 0; k < f.count; ++k) l.append(field(k));
      d[f.name] = l;
    }
  }
  return d;
}

py::list field_table(std::span<const RegisterField> table) {
  py::list l;
  for (const RegisterField& f : table)
    l.append(py::dict(py::arg("name") = f.name, py::arg("word") = f.word, py::arg("lsb") = f.lsb,
                      py::arg("width") = f.width, py::arg("count") = f.count, py::arg("stride") = f.stride,
                      py::arg("meaning") = f.meaning));
  return l;
}

// ---- Traces ----

struct PyTrace {
  std::shared_ptr<Trace> trace;
  bool from_file = false;  // read from trace->source (Trace.load, a path)
  // A render's trace: the scene and the render (its frame, quad targets), so that simulate() runs it
  // as `tfu sim --scene` does (the cycle model's image composed from its outputs).
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const RenderResult> render;
  SceneRequest request;
  RenderOptions options;
};

int mode_columns(TraceMode m) { return m == TraceMode::Lod ? 3 : m == TraceMode::Grad ? 6 : 2; }

// A trace from numpy columns: (N, 2) quad (s, t; four consecutive rows a 2x2 quad), (N, 3) lod
// (s, t, lod) or (N, 6) grad (s, t, ds/dx, dt/dx, ds/dy, dt/dy); texture, sampler and stage indices
// per request (default 0). Read as binary32, as parse_trace reads the text.
PyTrace trace_from_arrays(const py::array& requests, const std::optional<std::string>& mode_name,
                          const py::object& texture, const py::object& sampler, const py::object& stage) {
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(requests);
  if (!a || a.ndim() != 2) throw InputError("requests: expected an N x 2 (quad), N x 3 (lod) or N x 6 (grad) array");
  const auto cols = static_cast<int>(a.shape(1));
  TraceMode mode = cols == 3 ? TraceMode::Lod : cols == 6 ? TraceMode::Grad : TraceMode::Quad;
  if (mode_name) mode = kTraceModeNames.from_name(*mode_name);
  if (cols != mode_columns(mode))
    throw InputError(fmt::format("requests: a {} trace has {} columns, the array {}", trace_mode_name(mode),
                                 mode_columns(mode), cols));
  const auto n = static_cast<size_t>(a.shape(0));
  if (n > kMaxTraceRequests) throw InputError(fmt::format("requests: more than {} requests", kMaxTraceRequests));
  if (mode == TraceMode::Quad && n % 4 != 0)
    throw InputError(fmt::format("requests: a quad trace has a multiple of 4 requests, not {}", n));
  auto tr = std::make_shared<Trace>();
  tr->mode = mode;
  tr->source = "requests";
  tr->requests.resize(n);
  const float* v = a.data();
  const auto index = [n](const py::object& o, const char* what, long max) {
    std::vector<long> out(n, 0);
    if (o.is_none()) return out;
    const auto x = py::array_t<long, py::array::c_style | py::array::forcecast>::ensure(o);
    if (!x || x.ndim() != 1 || static_cast<size_t>(x.shape(0)) != n)
      throw InputError(fmt::format("{}: expected {} indices, one per request", what, n));
    for (size_t i = 0; i < n; ++i) {
      if (x.data()[i] < 0 || x.data()[i] > max)
        throw InputError(fmt::format("{}: request {}: index {} outside 0..{}", what, i, x.data()[i], max));
      out[i] = x.data()[i];
    }
    return out;
  };
  const std::vector<long> tex = index(texture, "texture", kMaxTextureDescriptors - 1),
                          smp = index(sampler, "sampler", kMaxSamplerDescriptors - 1), stg = index(stage, "stage", 255);
  for (size_t i = 0; i < n; ++i) {
    TraceRequest& r = tr->requests[i];
    const float* row = v + i * static_cast<size_t>(cols);
    r.texture = static_cast<uint16_t>(tex[i]);
    r.sampler = static_cast<uint8_t>(smp[i]);
    r.stage = static_cast<uint8_t>(stg[i]);
    r.s = row[0];
    r.t = row[1];
    if (mode == TraceMode::Lod) r.lod = row[2];
    if (mode == TraceMode::Grad) {
      r.dsdx = row[2];
      r.dtdx = row[3];
      r.dsdy = row[4];
      r.dtdy = row[5];
    }
  }
  PyTrace t;
  t.trace = std::move(tr);
  return t;
}

py::array trace_requests(const PyTrace& t) {
  const Trace& tr = *t.trace;
  const int cols = mode_columns(tr.mode);
  py::array_t<float> a({static_cast<py::ssize_t>(tr.requests.size()), static_cast<py::ssize_t>(cols)});
  float* out = a.mutable_data();
  for (const TraceRequest& r : tr.requests) {
    *out++ = r.s;
    *out++ = r.t;
    if (tr.mode == TraceMode::Lod) *out++ = r.lod;
    if (tr.mode == TraceMode::Grad)
      for (float x : {r.dsdx, r.dtdx, r.dsdy, r.dtdy}) *out++ = x;
  }
  return a;
}

template <typename F>
py::array trace_column(const PyTrace& t, F get) {
  py::array_t<int32_t> a(static_cast<py::ssize_t>(t.trace->requests.size()));
  int32_t* out = a.mutable_data();
  for (const TraceRequest& r : t.trace->requests) *out++ = get(r);
  return a;
}

// The trace as a file holds it: a render's trace with the header lines that describe its frame
// (loadable_trace, as `tfu render --trace-out`), any other as it was read or made.
std::string trace_text(const PyTrace& t) {
  std::ostringstream os;
  write_trace(os, t.render ? loadable_trace(t.render->frame->frame, *t.trace) : *t.trace);
  return os.str();
}

template <typename T>
std::vector<T> one_or_list(const py::object& o) {
  if (o.is_none()) return {};
  if (py::isinstance<T>(o)) return {o.cast<T>()};
  return o.cast<std::vector<T>>();
}

// The frame of a trace and the textures and samplers given: a trace whose header binds textures
// and samplers loads them (frame_from_trace, as `tfu sample` and `tfu sim --requests`), else the
// requests' indices name textures[i] and samplers[j] (a request of a trace without index columns:
// 0 and 0). Requests are bound in `trace` (a copy of the caller's).
Frame frame_of(Trace& trace, const std::vector<PyTexture>& textures, const std::vector<PySampler>& samplers,
               int line_bytes, const std::string& game_dir, const Params& sampler_overrides) {
  if (!trace.textures.empty() || !trace.samplers.empty()) {
    if (!textures.empty())
      throw InputError(fmt::format("texture: {} binds its own textures (give it none)", trace.textures.front().where));
    if (!samplers.empty() && !trace.samplers.empty())
      throw InputError(fmt::format("sampler: {} binds its own samplers (give sampler keys to override them)",
                                   trace.samplers.front().where));
    FrameDefaults d;
    d.game_dir = game_dir;
    d.sampler_overrides = sampler_overrides;
    if (!samplers.empty()) d.sampler = sampler_to_params(samplers.front().descriptor);
    return frame_from_trace(trace, d, line_bytes);
  }
  if (textures.empty()) throw InputError(fmt::format("{} binds no texture: give texture", trace.source));
  FrameBuilder b(line_bytes);
  for (const PyTexture& t : textures) b.add_texture(t.texture, t.spec);
  if (samplers.empty()) {
    b.add_sampler(sampler_from_params(sampler_overrides, "sampler"), false);
  } else {
    for (const PySampler& s : samplers)
      b.add_sampler(sampler_from_params(sampler_overrides, "sampler (override)", s.descriptor), false);
  }
  bind_requests(b, trace);
  return b.finish();
}

PyTrace as_trace(const py::object& requests, const std::optional<std::string>& mode) {
  if (py::isinstance<PyTrace>(requests)) return requests.cast<PyTrace>();
  if (py::isinstance<py::str>(requests) || py::isinstance(requests, py::module_::import("pathlib").attr("PurePath"))) {
    PyTrace t;
    t.trace = std::make_shared<Trace>(load_trace(py::str(requests).cast<std::string>()));
    t.from_file = true;
    return t;
  }
  return trace_from_arrays(py::array::ensure(requests), mode, py::none(), py::none(), py::none());
}

// ---- sample: the golden model on requests (tfu sample) ----
py::array sample(const py::object& texture, const py::object& sampler, const py::object& requests,
                 const std::optional<std::string>& mode, const std::string& game_dir) {
  const PyTrace t = as_trace(requests, mode);
  const std::vector<PyTexture> textures = one_or_list<PyTexture>(texture);
  const std::vector<PySampler> samplers = one_or_list<PySampler>(sampler);
  std::vector<Rgba8> out;
  {
    py::gil_scoped_release unlocked;
    Trace tr = *t.trace;
    // Tiles of the texture's tile_bytes (one cache line), as `tfu sample --tile-bytes` (default 64).
    const int line_bytes = textures.size() == 1 ? textures.front().texture->tile_bytes : 64;
    // A render's trace names the descriptors of the render's frame.
    if (t.render && (!textures.empty() || !samplers.empty()))
      throw InputError(
          "a render's trace samples the textures and samplers of its render: give texture and sampler None");
    const Frame frame = t.render ? Frame{} : frame_of(tr, textures, samplers, line_bytes, game_dir, {});
    const GoldenUnit golden(t.render ? t.render->frame->frame : frame);
    out.resize(tr.requests.size());
    AnisoLod lod;
    for (size_t i = 0; i < tr.requests.size(); ++i) {
      const TraceRequest& r = tr.requests[i];
      if (tr.mode != TraceMode::Quad || i % 4 == 0) lod = golden.lod(tr, i);  // a quad's LOD from its four pixels
      out[i] = golden.sample(r, lod);
    }
  }
  return pixels_array(out);
}

// ---- render: the golden renderer (tfu render) ----
RenderOptions render_options(const std::optional<std::string>& filter, const py::object& max_aniso,
                             const std::optional<std::string>& aniso_rounding,
                             const std::optional<std::string>& shape_policy) {
  RenderOptions ro;
  if (filter) ro.filter = filter_mode_from_name(*filter);
  const auto set = [&ro](const char* key, const std::string& value) {
    SamplerDescriptor scratch;
    try {
      set_sampler_param(scratch, key, value);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", key, e.what()));
    }
    ro.sampler_overrides[key] = value;
  };
  if (!max_aniso.is_none()) set("max_aniso", value_text(max_aniso));
  if (aniso_rounding) set("aniso_rounding", *aniso_rounding);
  if (shape_policy) set("edge_shape", *shape_policy);
  return ro;
}

void check_size(int width, int height) {
  if (width < 0 || height < 0 || width == 1 || height == 1 || width > kMaxRenderSize || height > kMaxRenderSize)
    throw InputError(fmt::format("width/height must be in 2..{} (0: the scene's own size)", kMaxRenderSize));
}

py::tuple render(const std::string& scene_name, int width, int height, const std::optional<std::string>& filter,
                 const py::object& max_aniso, const std::optional<std::string>& aniso_rounding,
                 const std::optional<std::string>& shape_policy, const std::string& game_dir, int line_bytes,
                 int threads) {
  check_size(width, height);
  PyTrace t;
  t.request = {scene_name, width, height, game_dir};
  t.options = render_options(filter, max_aniso, aniso_rounding, shape_policy);
  t.options.trace = true;
  t.options.line_bytes = line_bytes;
  t.options.threads = threads;
  {
    py::gil_scoped_release unlocked;
    if (!valid_tile_bytes(line_bytes))
      throw InputError(fmt::format("line_bytes {} must be 64, 256 or 1024", line_bytes));
    t.scene = std::make_shared<const Scene>(open_scene(t.request));
    auto r = std::make_shared<RenderResult>(render_scene(*t.scene, t.options));
    t.trace = std::make_shared<Trace>(r->trace);
    t.render = std::move(r);
  }
  return py::make_tuple(image_array(t.render->image), t);
}

// ---- simulate: the cycle model with the golden compare (tfu sim) ----

// A unit configuration: None (the defaults), a dict (nested as the JSON file, or dotted keys
// "cache.capacity_bytes"), or a path to a configuration JSON or a statistics file (its recorded
// configuration, as `tfu sim --config`); every problem an InputError as the command line's.
rtl::UnitConfig unit_config_of(const py::object& config) {
  if (config.is_none()) return {};
  if (py::isinstance<py::dict>(config)) {
    nlohmann::json j = nlohmann::json::parse(python_to_json(config));
    nlohmann::json nested = nlohmann::json::object();
    for (const auto& [key, value] : j.items()) {
      nlohmann::json* at = &nested;
      std::string k = key;
      for (size_t dot; (dot = k.find('.')) != std::string::npos; k = k.substr(dot + 1)) {
        at = &(*at)[k.substr(0, dot)];
        if (!at->is_object() && !at->is_null())
          throw InputError(
              fmt::format("config: key '{}': its part before '{}' is a value", quote_input(key), quote_input(k)));
      }
      if (value.is_object() && at->contains(k)) {
        (*at)[k].update(value);
      } else {
        (*at)[k] = value;
      }
    }
    return rtl::unit_config_from_json(nested.dump(), "config");
  }
  const std::string path = py::str(config).cast<std::string>();
  return rtl::unit_config_from_json(
      unit_config_text(read_input_file(path, "config " + quoted_path(path), kMaxTextInputBytes)), quote_path(path));
}

py::object stats_dict(const sim::Stats& stats, const RunRecord& rec) {
  return json_to_python(stats_document(stats, provenance_json(rec)));
}

py::tuple simulate(const py::object& source, const py::object& config, const py::object& texture,
                   const py::object& sampler, int width, int height, const std::optional<std::string>& filter,
                   const py::object& max_aniso, const std::optional<std::string>& aniso_rounding,
                   const std::optional<std::string>& shape_policy, int units, const std::string& engine,
                   const std::string& game_dir, bool check) {
  const rtl::UnitConfig unit = unit_config_of(config);
  const rtl::UnitEngine eng = rtl::unit_engine_from_name(engine);
  RunRecord rec;
  rec.command = "sim";
  rec.config = &unit;
  rec.engine = eng;
  std::string mismatch;
  sim::Stats stats;
  py::object pixels;
  PyTrace given;
  bool is_scene = false;
  if (py::isinstance<PyTrace>(source)) {
    given = source.cast<PyTrace>();
    is_scene = given.render != nullptr;
  } else if (py::isinstance<py::str>(source)) {
    is_scene =
        true;  // a scene name (built-in, JSON file, oa:MAP[:SPAWN]); a trace file: simulate(tfu.Trace.load(path))
  } else {
    given = as_trace(source, std::nullopt);
  }
  if (is_scene) {
    if (!texture.is_none() || !sampler.is_none())
      throw InputError(
          "texture and sampler apply to request traces; a scene's stages carry their own (filter, max_aniso, "
          "aniso_rounding and shape_policy override the base stage's)");
    std::shared_ptr<const Scene> scene = given.scene;
    std::shared_ptr<const RenderResult> render = given.render;
    SceneRequest request = given.request;
    RenderOptions ro = given.options;
    if (scene) {
      if (width || height || filter || !max_aniso.is_none() || aniso_rounding || shape_policy)
        throw InputError(
            "a render's trace is simulated as rendered: give width, height and sampler overrides to render()");
      if (ro.line_bytes != unit.cache.line_bytes)
        throw InputError(fmt::format(
            "the trace was rendered for {}-byte cache lines and the unit has {} (render(..., line_bytes={}))",
            ro.line_bytes, unit.cache.line_bytes, unit.cache.line_bytes));
    } else {
      check_size(width, height);
      request = {source.cast<std::string>(), width, height, game_dir};
      ro = render_options(filter, max_aniso, aniso_rounding, shape_policy);
      ro.trace = true;
      ro.line_bytes = unit.cache.line_bytes;
    }
    rtl::SceneSimOptions so;
    so.units = units;
    so.engine = eng;
    rtl::SceneSimResult res;
    {
      py::gil_scoped_release unlocked;
      if (units < 1 || units > 1024) throw InputError("units must be in 1..1024");
      if (!scene) scene = std::make_shared<const Scene>(open_scene(request));
      if (!render) render = std::make_shared<const RenderResult>(render_scene(*scene, ro));
      res = rtl::simulate_scene(*scene, *render, unit, so);
      rec.scene = request;
      rec.width = scene->width;
      rec.height = scene->height;
      rec.filter = ro.filter ? filter_mode_name(*ro.filter) : std::string("scene");
      rec.sampler_overrides = ro.sampler_overrides;
      rec.units = units;
      rec.textures = frame_texture_names(render->frame->frame);
      if (const auto level = requested_level(request))
        for (const auto& [field, n] : q3::level_count_fields(*level))
          res.stats.add("level_" + field, static_cast<uint64_t>(n));
    }
    mismatch = res.mismatch;
    stats = std::move(res.stats);
    pixels = image_array(res.image);
  } else {
    const std::vector<PyTexture> textures = one_or_list<PyTexture>(texture);
    const std::vector<PySampler> samplers = one_or_list<PySampler>(sampler);
    if (width || height || units != 1)
      throw InputError("width, height and units apply to scene runs, not to request traces");
    if (filter || !max_aniso.is_none() || aniso_rounding)
      throw InputError(
          "filter, max_aniso and aniso_rounding apply to scene runs: give a request trace's sampler keys with "
          "tfu.Sampler");
    Params overrides;
    if (shape_policy) overrides["edge_shape"] = *shape_policy;
    rtl::UnitOutput got;
    {
      py::gil_scoped_release unlocked;
      Trace tr = *given.trace;
      const Frame frame = frame_of(tr, textures, samplers, unit.cache.line_bytes, game_dir, overrides);
      rec.has_scene = false;
      rec.trace = tr.source;
      if (!given.from_file) {  // no file to hash: the trace file's text that save() writes
        std::ostringstream text;
        write_trace(text, *given.trace);
        rec.trace = "(numpy array)";
        rec.trace_fnv1a64 = hex64(fnv1a64(text.str()));
      }
      rec.textures = frame_texture_names(frame);
      std::string modes;
      for (const SamplerDescriptor& s : frame.regs.samplers)
        modes += (modes.empty() ? "" : ", ") + filter_mode_name(s.mode);
      rec.filter = modes;
      rec.sampler_overrides = overrides;
      got = rtl::run_unit(frame, tr, unit, eng, rtl::VcdOptions{});
      const GoldenUnit golden(frame);
      mismatch = rtl::first_mismatch(tr, rtl::golden_outputs(golden, tr, got), got);
    }
    stats = std::move(got.stats);
    pixels = pixels_array(got.pixels);
  }
  py::object st = stats_dict(stats, rec);
  st["golden_compare"] = mismatch.empty() ? py::str("all equal") : py::str(mismatch);
  if (check && !mismatch.empty()) throw CheckFailed(mismatch);
  return py::make_tuple(st, pixels);
}

// ---- Sweeps (tfu sweep): run one, and read a finished one's results as rows ----

// One row per point, as results.csv holds it (sweep_report.hpp: the keys, scene, filter, then the
// result columns), with typed values: unit-field keys as integers (named fields as names), sampler
// keys as text, numbers as numbers (psnr "inf" as float('inf')), golden_equal as bool, and the
// point id and error text; a point that could not run has None in its result columns.
py::list sweep_rows_of(const sweep::Spec& spec, const std::vector<sweep::Point>& points,
                       const std::vector<nlohmann::json>& files) {
  py::list rows;
  for (size_t i = 0; i < points.size(); ++i) {
    const sweep::Point& p = points[i];
    py::dict row;
    for (size_t k = 0; k < spec.keys.size(); ++k) {
      const sweep::Key& key = spec.keys[k];
      const std::string& v = p.values[k];
      if (key.field && key.field->names.empty() && !v.empty()) {
        row[key.name.c_str()] = py::int_(py::str(v));
      } else {
        row[key.name.c_str()] = v;
      }
    }
    row["scene"] = p.scene;
    row["filter"] = p.filter;
    const nlohmann::json& f = files[i];
    const bool ran = f.contains("result");
    for (const sweep::Column& c : sweep::result_columns()) {
      if (c.name == "point") {
        row["point"] = p.id;
      } else if (c.name == "error") {
        row["error"] = f.contains("error") ? f["error"].get<std::string>() : std::string();
      } else if (!ran) {
        row[c.name.c_str()] = py::none();
      } else {
        const nlohmann::json& v = f["result"][c.name];
        if (v.is_string()) {
          row[c.name.c_str()] = py::float_(std::numeric_limits<double>::infinity());  // NumberOrInf: "inf"
        } else {
          row[c.name.c_str()] = json_to_python(v.dump());
        }
      }
    }
    rows.append(row);
  }
  return rows;
}

py::list sweep_rows(const std::string& dir) {
  sweep::Spec spec;
  std::vector<sweep::Point> points;
  std::vector<nlohmann::json> files;
  {
    py::gil_scoped_release unlocked;
    spec = sweep::load_sweep_dir(dir);
    points = sweep::expand(spec);
    files = sweep::read_point_files(dir, points);
  }
  return sweep_rows_of(spec, points, files);
}

// Runs a sweep spec (a file, or a dict: written into DIR as spec.json first) into DIR on the local
// runner, as `tfu sweep SPEC --out DIR` (resumable, results.csv, columns.json and summary.md), and
// returns its rows. The plots: `tfu sweep --collect DIR --plot`, or matplotlib on the rows.
py::list run_sweep(const py::object& spec_source, const std::string& dir, int workers, bool force, bool progress,
                   bool check) {
  // A dict is the spec file OUT/spec.json (relative scene paths: relative to OUT), written once the
  // directory is prepared.
  const bool from_dict = py::isinstance<py::dict>(spec_source);
  const std::string spec_path =
      from_dict ? (std::filesystem::path(dir) / "spec.json").string() : py::str(spec_source).cast<std::string>();
  const std::string dict_text = from_dict ? python_to_json(spec_source) + "\n" : std::string();
  if (workers < 0 || workers > 1024) throw InputError("workers must be in 0..1024 (0: every hardware thread)");
  sweep::Spec spec;
  std::vector<sweep::Point> points;
  std::vector<nlohmann::json> files;
  {
    py::gil_scoped_release unlocked;
    spec = from_dict ? sweep::parse_spec(dict_text, spec_path) : sweep::load_spec(spec_path);
    points = sweep::expand(spec);
    sweep::prepare_sweep_dir(dir, spec, force);
    if (from_dict) write_file_atomic(spec_path, dict_text, "sweep spec");
    sweep::run_points(spec, points, dir, {workers, 0, 1, progress});
    files = sweep::read_point_files(dir, points);
    write_file_atomic((std::filesystem::path(dir) / "results.csv").string(), sweep::results_csv(spec, points, files),
                      "results.csv");
    write_file_atomic((std::filesystem::path(dir) / "columns.json").string(), sweep::columns_json(spec),
                      "columns.json");
    write_file_atomic((std::filesystem::path(dir) / "summary.md").string(),
                      sweep::summary_markdown(spec, points, files, {}), "summary.md");
  }
  if (const size_t failed = sweep::failed_points(files); check && failed > 0)  // as tfu sweep
    throw CheckFailed(
        fmt::format("{} of {} points failed the golden compare or could not run (results.csv: golden_equal, error)",
                    failed, points.size()));
  return sweep_rows_of(spec, points, files);
}

// ---- compare: two images (tfu compare) ----
py::dict compare(const py::object& a, const py::object& b) {
  const auto image = [](const py::object& o, const char* what) {
    if (py::isinstance<py::str>(o)) return load_image(o.cast<std::string>());
    return image_from_array(o, what);
  };
  const Image ia = image(a, "a"), ib = image(b, "b");
  if (ia.width != ib.width || ia.height != ib.height)
    throw InputError(fmt::format("images differ in size: {}x{} vs {}x{}", ia.width, ia.height, ib.width, ib.height));
  const ImageMetrics m = compare_images(ia, ib);
  return py::dict(py::arg("psnr_db") = m.psnr_db, py::arg("ssim") = m.ssim, py::arg("mse") = m.mse,
                  py::arg("max_abs_diff") = m.diff.max_abs, py::arg("max_abs_diff_rgba") = m.diff.max_abs_channel,
                  py::arg("mean_abs_diff") = m.diff.mean_abs);
}

}  // namespace
}  // namespace tfu::python

PYBIND11_MODULE(tfu, m) {
  using namespace tfu;
  using namespace tfu::python;
  m.doc() = "The texture filter unit model: golden sampler, renderer, cycle model and sweeps (docs/python.md)";
  m.attr("__version__") = tool_version();

  // Exceptions: the command line's error kinds, with its one-line messages.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<CheckFailed> check_failed(m, "CheckFailed", PyExc_RuntimeError);
  static py::exception<DeadlockError> deadlock(m, "DeadlockError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(one_line(e.what()).c_str());
    } catch (const CheckFailed& e) {
      check_failed(one_line(e.what()).c_str());
    } catch (const DeadlockError& e) {
      deadlock(one_line(e.what()).c_str());
    } catch (const std::filesystem::filesystem_error& e) {  // as report_error: a path the user gave
      input_error(e.path1().empty()
                      ? e.code().message().c_str()
                      : fmt::format("'{}': {}", quote_input(e.path1().string()), e.code().message()).c_str());
    }
  });

  py::class_<PyTexture>(m, "Texture",
                        "A texture: levels of texel words in a format, with its memory layout (cmodel/texture.hpp)")
      .def(
          py::init(&texture_from_source), py::arg("source"), py::kw_only(), py::arg("game_dir") = "",
          "A texture from an image file (PNG, JPEG, TIFF, ...; DDS, KTX and .astc read as blocks), proc:NAME[:SIZE] or "
          "oa:MAP:texture:NAME, with the texture keys (format, mipmaps, alpha, layout, tile_bytes, compress) as "
          "keyword arguments")
      .def_static("from_array", &texture_from_array, py::arg("array"), py::kw_only(), py::arg("name") = "0",
                  "A texture from a numpy array: H x W x 4 uint8 (RGBA8), H x W uint8 (L8) or H x W x 2 int16 (VS16X2 "
                  "numerators); the texture keys as keyword arguments (mipmaps default: box)")
      .def_property_readonly("width", [](const PyTexture& t) { return t.texture->width(); })
      .def_property_readonly("height", [](const PyTexture& t) { return t.texture->height(); })
      .def_property_readonly("format",
                             [](const PyTexture& t) { return std::string(texel_format_name(t.texture->format)); })
      .def_property_readonly("levels", [](const PyTexture& t) { return t.texture->levels.size(); })
      .def_property_readonly("layout",
                             [](const PyTexture& t) { return std::string(memory_layout_name(t.texture->layout)); })
      .def_property_readonly("tile_bytes", [](const PyTexture& t) { return t.texture->tile_bytes; })
      .def_property_readonly("compressed", [](const PyTexture& t) { return t.texture->compressed != nullptr; })
      .def_property_readonly("source", [](const PyTexture& t) { return t.spec.source; })
      .def_property_readonly("keys", [](const PyTexture& t) { return t.spec.params; })
      .def(
          "level",
          [](const PyTexture& t, int i) {
            if (i < 0 || i > t.texture->max_level())
              throw InputError(fmt::format("level {} outside 0..{}", i, t.texture->max_level()));
            return image_array(t.texture->levels[static_cast<size_t>(i)]);
          },
          py::arg("i") = 0,
          "Level i's texel words as an H x W x 4 uint8 array (compressed textures: the decoded texels)")
      .def(
          "descriptor",
          [](const PyTexture& t, int line_bytes) {
            FrameBuilder b(line_bytes);
            b.add_texture(t.texture, t.spec);
            return register_fields(texture_descriptor_fields(), encode(b.frame().regs.textures.front()));
          },
          py::arg("line_bytes") = 64,
          "The texture descriptor the driver writes for it alone in a texel memory (cache lines of line_bytes): "
          "{field: value} by the register field table (docs/descriptors.md)")
      .def("__repr__", [](const PyTexture& t) {
        return fmt::format("tfu.Texture('{}', {}x{}, {}, {} levels)", t.spec.source, t.texture->width(),
                           t.texture->height(), texel_format_name(t.texture->format), t.texture->levels.size());
      });

  py::class_<PySampler>(m, "Sampler", "A sampler descriptor: how a texture is filtered (cmodel/descriptors.hpp)")
      .def(py::init(&make_sampler),
           "A sampler from the sampler keys as keyword arguments (filter='trilinear', wrap_s='clamp-to-edge', "
           "max_aniso=4, ...; tfu.sampler_keys() lists them)")
      .def_property_readonly(
          "keys", [](const PySampler& s) { return sampler_to_params(s.descriptor); },
          "Every key with its value (what a trace header records)")
      .def(
          "registers", [](const PySampler& s) { return encode(s.descriptor); }, "The descriptor's register words")
      .def(
          "descriptor",
          [](const PySampler& s) { return register_fields(sampler_descriptor_fields(), encode(s.descriptor)); },
          "{field: value} by the register field table (docs/descriptors.md)")
      .def("__repr__", [](const PySampler& s) {
        return fmt::format("tfu.Sampler(filter='{}')", filter_mode_name(s.descriptor.mode));
      });

  py::class_<PyTrace>(m, "Trace", "Requests that name a texture and a sampler (docs/traces.md)")
      .def(py::init(&trace_from_arrays), py::arg("requests"), py::kw_only(), py::arg("mode") = py::none(),
           py::arg("texture") = py::none(), py::arg("sampler") = py::none(), py::arg("stage") = py::none(),
           "A trace from an N x 2 (quad), N x 3 (lod) or N x 6 (grad) float array and optional per-request texture, "
           "sampler and "
           "stage indices")
      .def_static(
          "load",
          [](const std::string& path) {
            PyTrace t;
            t.trace = std::make_shared<Trace>(load_trace(path));
            t.from_file = true;
            return t;
          },
          py::arg("path"), "Reads a trace file (its header's texture and sampler bindings included)")
      .def_property_readonly("mode", [](const PyTrace& t) { return std::string(trace_mode_name(t.trace->mode)); })
      .def_property_readonly("requests", &trace_requests, "The coordinates: N x 2, 3 or 6 float32 by the mode")
      .def_property_readonly(
          "texture", [](const PyTrace& t) { return trace_column(t, [](const TraceRequest& r) { return r.texture; }); })
      .def_property_readonly(
          "sampler", [](const PyTrace& t) { return trace_column(t, [](const TraceRequest& r) { return r.sampler; }); })
      .def_property_readonly(
          "stage", [](const PyTrace& t) { return trace_column(t, [](const TraceRequest& r) { return r.stage; }); })
      .def_property_readonly(
          "scene",
          [](const PyTrace& t) { return t.scene ? py::object(py::str(t.request.name)) : py::object(py::none()); })
      .def("__len__", [](const PyTrace& t) { return t.trace->requests.size(); })
      .def("text", &trace_text,
           "The trace file's text (a render's with the header that binds its textures and samplers)")
      .def(
          "save", [](const PyTrace& t, const std::string& path) { write_file_atomic(path, trace_text(t), "trace"); },
          py::arg("path"), "Writes the trace file (as tfu render --trace-out)");

  m.def("sample", &sample, py::arg("texture"), py::arg("sampler"), py::arg("requests"), py::kw_only(),
        py::arg("mode") = py::none(), py::arg("game_dir") = "",
        "The golden model on requests (as tfu sample): an N x 4 uint8 array of RGBA8 outputs. texture and sampler: one "
        "each or "
        "lists (the requests' indices name them), None for a trace whose header binds them; requests: a tfu.Trace, a "
        "trace "
        "file's path, or an N x 2 (quad) / N x 3 (lod) / N x 6 (grad) array");
  m.def("render", &render, py::arg("scene"), py::kw_only(), py::arg("width") = 0, py::arg("height") = 0,
        py::arg("filter") = py::none(), py::arg("max_aniso") = py::none(), py::arg("aniso_rounding") = py::none(),
        py::arg("shape_policy") = py::none(), py::arg("game_dir") = "", py::arg("line_bytes") = 64,
        py::arg("threads") = 0,
        "Renders a built-in scene, a scene JSON file or oa:MAP[:SPAWN] through the golden sampler (as tfu render): (H "
        "x W x 4 "
        "uint8 image, tfu.Trace of its requests); filter, max_aniso, aniso_rounding and shape_policy override every "
        "base stage");
  m.def("simulate", &simulate, py::arg("source"), py::arg("config") = py::none(), py::kw_only(),
        py::arg("texture") = py::none(), py::arg("sampler") = py::none(), py::arg("width") = 0, py::arg("height") = 0,
        py::arg("filter") = py::none(), py::arg("max_aniso") = py::none(), py::arg("aniso_rounding") = py::none(),
        py::arg("shape_policy") = py::none(), py::arg("units") = 1, py::arg("engine") = "recurrence",
        py::arg("game_dir") = "", py::arg("check") = true,
        "The cycle model with the golden compare (as tfu sim): (statistics dict as tfu sim --stats writes it, plus "
        "'golden_compare'; pixels). source: a scene name (the image as pixels), a render's tfu.Trace (likewise), or a "
        "request trace (tfu.Trace, path or array; N x 4 outputs). config: None, a dict (nested or dotted keys) or a "
        "configuration/statistics file. A mismatch raises tfu.CheckFailed unless check=False");
  m.def(
      "unit_config",
      [](const py::object& config) { return json_to_python(rtl::unit_config_to_json(unit_config_of(config))); },
      py::arg("config") = py::none(), "The effective unit configuration, every field (as tfu sim --config-out)");
  m.def(
      "unit_config_fields",
      [] {
        py::list l;
        for (const rtl::UnitField& f : rtl::unit_config_fields()) {
          py::list names;
          for (const char* n : f.names) names.append(n);
          l.append(py::dict(py::arg("key") = f.key, py::arg("flag") = f.flag, py::arg("meaning") = f.meaning,
                            py::arg("lo") = f.lo, py::arg("hi") = f.hi, py::arg("allowed") = f.allowed,
                            py::arg("names") = names,
                            py::arg("default") = json_to_python(f.value_text(rtl::UnitConfig{}))));
        }
        return l;
      },
      "The unit configuration's field table (rtl/unit_config.hpp; tfu sim --config-fields)");
  m.def(
      "sampler_keys",
      [] {
        py::dict d;
        for (const SamplerParam& p : sampler_params()) d[p.key] = p.meaning;
        return d;
      },
      "The sampler keys and what they mean (cmodel/bindings.hpp)");
  m.def(
      "texture_keys",
      [] {
        py::list l;
        for (const char* k : texture_param_keys()) l.append(k);
        return l;
      },
      "The texture keys (cmodel/bindings.hpp)");
  m.def(
      "descriptor_fields",
      [](const std::string& which) {
        if (which == "texture") return field_table(texture_descriptor_fields());
        if (which == "sampler") return field_table(sampler_descriptor_fields());
        throw InputError(fmt::format("descriptor_fields: '{}' is neither 'texture' nor 'sampler'", quote_input(which)));
      },
      py::arg("which"), "The register field table of the texture or sampler descriptor (docs/descriptors.md)");
  m.def(
      "scenes", [] { return builtin_scene_names(); }, "The built-in scenes' names");
  m.def(
      "filter_modes",
      [] {
        std::vector<std::string> names;
        for (const FilterMode& f : all_filter_modes()) names.push_back(filter_mode_name(f));
        return names;
      },
      "The 12 filter modes' canonical names");
  m.def("compare", &compare, py::arg("a"), py::arg("b"),
        "Two images (H x W x 4 uint8 arrays or files), as tfu compare: psnr_db, ssim, mse, max_abs_diff, "
        "max_abs_diff_rgba, mean_abs_diff");
  m.def("sweep", &run_sweep, py::arg("spec"), py::arg("out"), py::kw_only(), py::arg("workers") = 0,
        py::arg("force") = false, py::arg("progress") = false, py::arg("check") = true,
        "Runs a sweep spec (file or dict) into the directory out, as tfu sweep SPEC --out DIR; returns its rows "
        "(tfu.sweep_rows); "
        "a point that failed its golden compare or could not run raises tfu.CheckFailed unless check=False");
  m.def("sweep_rows", &sweep_rows, py::arg("dir"),
        "A finished sweep's results as rows: one dict per point with results.csv's columns, typed");
}
