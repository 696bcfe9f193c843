#include "cmodel/frame.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "cmodel/bspline_prefilter.hpp"
#include "cmodel/error.hpp"

namespace tfu {

FrameBuilder::FrameBuilder(int line_bytes) {
  if (!valid_tile_bytes(line_bytes))
    throw InputError(fmt::format("cache line of {} bytes (expected 64, 256 or 1024)", line_bytes));
  frame_.line_bytes = line_bytes;
}

int FrameBuilder::add_texture(std::shared_ptr<const Texture> tex, TextureSpec spec) {
  if (const auto it = placed_.find(tex); it != placed_.end()) return it->second;
  std::shared_ptr<const Texture> key = tex;  // kept alive: its address cannot name another texture
  if (tex->layout == MemoryLayout::Tiled && tex->tile_bytes != frame_.line_bytes) {
    // The driver tiles for the unit's cache line: one tile per line.
    auto t = std::make_shared<Texture>(*tex);
    t->tile_bytes = frame_.line_bytes;
    tex = std::move(t);
  }
  if (frame_.textures.size() >= kMaxTextureDescriptors)
    throw InputError(fmt::format("more than {} textures in one frame", kMaxTextureDescriptors));
  frame_.regs.textures.push_back(place_texture(frame_.memory, *tex, static_cast<uint64_t>(frame_.line_bytes)));
  frame_.textures.push_back({spec.source, std::move(spec), std::move(tex), -1});
  const int index = static_cast<int>(frame_.textures.size()) - 1;
  placed_.emplace(std::move(key), index);
  return index;
}

int FrameBuilder::add_sampler(const SamplerDescriptor& s, bool share_equal) {
  s.validate();
  auto& v = frame_.regs.samplers;
  for (size_t i = 0; share_equal && i < v.size(); ++i)
    if (v[i] == s) return static_cast<int>(i);
  if (v.size() >= kMaxSamplerDescriptors)
    throw InputError(fmt::format("more than {} samplers in one frame", kMaxSamplerDescriptors));
  v.push_back(s);
  return static_cast<int>(v.size()) - 1;
}

int FrameBuilder::bind(int texture, int sampler) {
  const SamplerDescriptor& s = frame_.regs.samplers.at(static_cast<size_t>(sampler));
  if (s.mode.base != BaseFilter::Cubic || s.kernel != kBsplineInterp) return texture;
  const auto key = std::tuple{texture, s.wrap_s, s.wrap_t};
  if (const auto it = coefficients_.find(key); it != coefficients_.end()) return it->second;
  const FrameTexture& src = frame_.textures.at(static_cast<size_t>(texture));
  const BsplineCoefficients c = prefilter_bspline(*src.texels, s.wrap_s, s.wrap_t);
  TextureDescriptor d =
      place_texture(frame_.memory, bspline_coefficient_texture(*src.texels, c), static_cast<uint64_t>(frame_.line_bytes));
  d.content = TextureContent::BsplineCoefficients;
  d.coeff_scale_q = c.scale_q;
  d.coeff_bias_q = c.bias_q;
  if (frame_.textures.size() >= kMaxTextureDescriptors)
    throw InputError(fmt::format("more than {} textures in one frame", kMaxTextureDescriptors));
  frame_.regs.textures.push_back(d);
  frame_.textures.push_back({fmt::format("bspline({})", src.name), src.spec, src.texels, texture});
  const int index = static_cast<int>(frame_.textures.size()) - 1;
  coefficients_[key] = index;
  return index;
}

void bind_requests(FrameBuilder& b, Trace& trace) {
  const auto ntex = b.frame().textures.size(), nsmp = b.frame().regs.samplers.size();
  std::map<std::pair<int, int>, int> memo;
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    TraceRequest& r = trace.requests[i];
    if (r.texture >= ntex || r.sampler >= nsmp)
      throw InputError(fmt::format("{}: request {} names texture {} and sampler {}, but {} textures and {} samplers are bound",
                                   trace.source, i, r.texture, r.sampler, ntex, nsmp));
    const auto key = std::pair{int{r.texture}, int{r.sampler}};
    auto it = memo.find(key);
    if (it == memo.end()) it = memo.emplace(key, b.bind(r.texture, r.sampler)).first;
    r.texture = static_cast<uint16_t>(it->second);
  }
}

Frame frame_from_trace(Trace& trace, const FrameDefaults& defaults, int line_bytes) {
  FrameBuilder b(line_bytes);
  const std::string base_dir = std::filesystem::path(trace.source).parent_path().string();
  std::vector<const TraceBinding*> tex(trace.textures.size(), nullptr), smp(trace.samplers.size(), nullptr);
  const auto order = [](const std::vector<TraceBinding>& list, std::vector<const TraceBinding*>& by_index, const char* kind) {
    for (const TraceBinding& bd : list) {
      const auto i = static_cast<size_t>(bd.index);
      if (i >= by_index.size()) throw InputError(fmt::format("{}: {} {} leaves a gap (bind 0..{} in any order)", bd.where, kind, i, list.size() - 1));
      if (by_index[i]) throw InputError(fmt::format("{}: {} {} bound twice", bd.where, kind, i));
      by_index[i] = &bd;
    }
  };
  order(trace.textures, tex, "texture");
  order(trace.samplers, smp, "sampler");
  if (tex.empty()) {
    if (!defaults.texture) throw InputError(fmt::format("{}: the trace binds no texture (give one, e.g. --texture)", trace.source));
    const LoadedTexture t = load_texture_spec(*defaults.texture, "--texture");
    b.add_texture(t.texture, *defaults.texture);
  }
  for (const TraceBinding* bd : tex) {
    const TextureSpec spec{bd->spec, bd->params};
    const LoadedTexture t = load_texture_spec(spec, bd->where, base_dir, defaults.game_dir);
    b.add_texture(t.texture, spec);  // binding N is descriptor N (each binding loads its own texture)
  }
  const auto make_sampler = [&](const Params& p, const std::string& where) {
    SamplerDescriptor s = sampler_from_params(p, where);
    s = sampler_from_params(defaults.sampler_overrides, where + " (override)", s);
    if (defaults.filter) s.mode = *defaults.filter;
    return s;
  };
  if (smp.empty()) b.add_sampler(make_sampler(defaults.sampler.value_or(Params{}), "sampler options"), false);
  for (const TraceBinding* bd : smp) b.add_sampler(make_sampler(bd->params, bd->where), false);
  bind_requests(b, trace);
  return b.finish();
}

void describe_frame(const Frame& f, Trace& trace) {
  trace.textures.clear();
  trace.samplers.clear();
  for (size_t i = 0; i < f.textures.size(); ++i) {
    if (f.textures[i].coefficients_of >= 0) continue;
    trace.textures.push_back({static_cast<int>(i), f.textures[i].spec.source, f.textures[i].spec.params, {}});
  }
  for (size_t i = 0; i < f.regs.samplers.size(); ++i)
    trace.samplers.push_back({static_cast<int>(i), {}, sampler_to_params(f.regs.samplers[i]), {}});
}

}  // namespace tfu
