#include "rtl/cache_stage.hpp"

#include <algorithm>
#include <bit>

#include "cmodel/block_formats.hpp"
#include "rtl/unit_stats.hpp"

namespace tfu::rtl {

CacheStage::CacheStage(sim::Simulator& s, sim::Channel<FootprintReq>& i, sim::Channel<FilterReq>& filter,
                       sim::Channel<FilterReq>& edge, const Registers& regs, const TextureMemory& memory, TexelCache& c,
                       MemoryModel& m, int miss_fifo_depth, int line_buffer_depth, const DecoderConfig& decoder)
    : Module(s, "texel_cache"),
      in_(i),
      filter_out_(filter),
      edge_out_(edge),
      regs_(regs),
      memory_(memory),
      cache_(c),
      mem_(m),
      fifo_(static_cast<size_t>(miss_fifo_depth)),
      line_buffer_depth_(line_buffer_depth),
      decoder_(decoder) {
  for (const SamplerDescriptor& d : regs.samplers) {
    any_edge_ = any_edge_ || d.mode.base == BaseFilter::EdgePreserving;
    record_shapes_ = record_shapes_ || (d.mode.base == BaseFilter::EdgePreserving && d.edge_shape == EdgeShape::CacheAware);
  }
  for (const TextureDescriptor& d : regs.textures) {
    compressed_.push_back(d.compressed ? 1 : 0);
    block_tags_.push_back(d.compressed && c.config().holds == CacheHolds::Compressed ? 1 : 0);
    any_compressed_ = any_compressed_ || d.compressed;
    first_readout_.push_back(readout_.size());
    for (int l = 0; l < d.levels; ++l) readout_.emplace_back(memory, d, l);
  }
  slots_.assign(stat_slots(regs.textures.size()), SlotCounters{});
  if (any_compressed_) {
    decoded_memo_.resize(kDecodedMemoEntries);
    decoded_levels_.resize(readout_.size());
    scratch_.resize(kHeldBlocks);
  }
}

uint64_t CacheStage::admit_blocks(int texture, int stage, int level, const TapGrid& lookup, uint64_t now,
                                  int& bank_cycles, FootprintResult& r) {
  const TextureDescriptor& d = regs_.textures[static_cast<size_t>(texture)];
  const BlockFormatInfo& b = d.block();
  if (cache_.config().holds == CacheHolds::Compressed) {  // `lookup` in blocks: the tags take it as it is
    const uint64_t in = admit_lines(texture, stage, level, lookup, now, bank_cycles, r);
    // The footprint's distinct blocks (for the statistics) and its taps (the decoders' texels).
    std::array<uint32_t, 16> seen;
    int blocks = 0, taps = 0;
    for (uint32_t cells = lookup.used; cells != 0; cells &= cells - 1, ++taps) {
      const auto c = static_cast<size_t>(std::countr_zero(cells));
      const uint32_t key = static_cast<uint32_t>(lookup.x[c & 3u]) << 16 | static_cast<uint32_t>(lookup.y[c >> 2]);
      int k = 0;
      while (k < blocks && seen[static_cast<size_t>(k)] != key) ++k;
      if (k == blocks) seen[static_cast<size_t>(blocks++)] = key;
    }
    return taps == 0 ? in : decode(in, taps, blocks, stat_slot(texture, stage));
  }
  r = cache_.access(texture, level, lookup);
  admitted_lines_ = r.misses;
  const size_t slot = stat_slot(texture, stage);
  SlotCounters& c = slots_[slot];
  c.level_hits[static_cast<size_t>(level)] += static_cast<uint64_t>(r.hits);
  c.level_misses[static_cast<size_t>(level)] += static_cast<uint64_t>(r.misses);
  c.sector_hits += static_cast<uint64_t>(r.sector_hits);
  c.sector_lookups += static_cast<uint64_t>(r.sector_lookups);
  c.memory_requests += static_cast<uint64_t>(r.misses);
  bank_cycles = r.cycles > 1 ? r.cycles : 1;
  uint64_t ready = now + static_cast<uint64_t>(bank_cycles) - 1;
  for (int m = 0; m < r.misses; ++m) {
    int texels = 0;
    const int blocks = cache_.fill_blocks(texture, level, r.missed_lines[static_cast<size_t>(m)], texels);
    c.memory_bytes += static_cast<uint64_t>(blocks * b.block_bytes);
    // The fill reads the line's blocks; the DRAM sees them at the line's address (a tile of blocks
    // is block rows apart in memory: docs/memory-system.md, what the model leaves out).
    const uint64_t line = r.missed_lines[static_cast<size_t>(m)];
    const uint64_t in = mem_.read(now, blocks * b.block_bytes, texture, line * static_cast<uint64_t>(cache_.config().line_bytes));
    ready = std::max(ready, decode(in, texels, blocks, slot));
  }
  return ready;
}

[[gnu::always_inline]] inline void CacheStage::accept(uint64_t now) {
  Entry& entry = fifo_.push_back();  // the footprint goes straight into the miss FIFO
  entry.f = in_.front();
  in_.pop();
  int bank_cycles = 1;
  entry.ready = admit(entry.f, now, bank_cycles);
  entry.lines = admitted_lines_;
  ++slots_[stat_slot(entry.f.tag.req)].footprints;
  lines_in_flight_ += admitted_lines_;
  port_free_ = now + static_cast<uint64_t>(bank_cycles);
}

[[gnu::always_inline]] inline uint64_t CacheStage::admit(FootprintReq& cur, uint64_t now, int& bank_cycles) {
  const bool edge = cur.tag.base == BaseFilter::EdgePreserving;
  const int texture = cur.tag.req.texture;
  // The grid the tags take: in blocks on a level of compressed lines (the address generator's), else in texels.
  const TapGrid& g = block_tags_[static_cast<size_t>(texture)] ? cur.blocks.blocks : cur.grid;
  if (edge && cur.optional != 0) {  // cache-aware: take an arm whose lines are resident (tag probe)
    for (const lee_jen::Arm& arm : lee_jen::kArms) {  // the four arms of the cross (Lee & Jen Fig. 4)
      const lee_jen::TexelMask bits = arm.mask;
      if ((cur.optional & bits) != bits) continue;
      bool resident = true;
      for (int n : arm.texels) {
        const uint8_t cell = kCrossCell[static_cast<size_t>(n - 1)];
        const size_t i = cell & 3u, j = cell >> 2;
        if (((g.used >> cell) & 1u) && !cache_.resident(texture, cur.level, g.x[i], g.y[j])) resident = false;
      }
      if (resident) cur.tag.shape = static_cast<lee_jen::TexelMask>(cur.tag.shape | bits);
    }
  }
  // The taps that read the cache: inside the texture (and, for the edge cross, in the shape).
  TapGrid lookup = g;
  if (edge) lookup.used = static_cast<uint16_t>(lookup.used & cross_cells(cur.tag.shape));
  FootprintResult r;
  const uint64_t ready = compressed_[static_cast<size_t>(texture)]
                             ? admit_blocks(texture, cur.tag.req.stage, cur.level, lookup, now, bank_cycles, r)
                             : admit_lines(texture, cur.tag.req.stage, cur.level, lookup, now, bank_cycles, r);
  if (probes_) {  // the waveform probes (accepted_id() ...)
    accepted_id_ = cur.tag.id;
    if (g.used != 0) {
      const auto cell = static_cast<size_t>(std::countr_zero(static_cast<uint32_t>(g.used)));
      const int tx = g.x[cell & 3u], ty = g.y[cell >> 2];  // texels, or blocks (line_of takes either as the tags do)
      if (tx >= 0 && ty >= 0) accepted_line_ = cache_.line_of(texture, cur.level, tx, ty);
    }
    accepted_ = cur;
    last_misses_ = r.misses;
    if (r.misses > 0) last_miss_line_ = r.missed_lines[static_cast<size_t>(r.misses - 1)];
  }
  if (edge) {
    int missing_arms = 0;
    for (const lee_jen::Arm& arm : lee_jen::kArms) missing_arms += (cur.tag.shape & arm.mask) == 0;
    ++slots_[stat_slot(cur.tag.req)].shapes[static_cast<size_t>(std::min(missing_arms, 2))];
    if (record_shapes_) shapes[cur.tag.id][2u * cur.tag.probe + (cur.tag.is_level1 ? 1u : 0u)] = cur.tag.shape;
  }
  return ready;
}

uint64_t CacheStage::admit_footprint(FootprintReq& f, uint64_t now, int& bank_cycles) { return admit(f, now, bank_cycles); }

uint64_t CacheStage::accepted_tap_address(int k) const {
  if (!probes_ || k < 0 || k >= accepted_.ntaps()) return 0;
  const TapGrid& g = accepted_.grid;
  size_t cell = 0;  // grid cell 4 j + i of tap k
  if (accepted_.cross) {
    if (((accepted_.tag.shape >> k) & 1u) == 0) return 0;
    cell = kCrossCell[static_cast<size_t>(k)];
  } else {
    cell = 4u * static_cast<size_t>(k / g.cols) + static_cast<size_t>(k % g.cols);
  }
  if (((g.used >> cell) & 1u) == 0) return 0;  // outside the texture: the border word
  const TextureDescriptor& d = regs_.textures[accepted_.tag.req.texture];
  if (d.compressed) {  // its block's address, at the address generator's block coordinates
    const TapGrid& b = accepted_.blocks.blocks;
    return d.block_address(accepted_.level, b.x[cell & 3u], b.y[cell >> 2]);
  }
  return d.texel_address(accepted_.level, g.x[cell & 3u], g.y[cell >> 2]);
}

// Texel read-out: the footprint's taps in FilterReq order (row-major over the grid; the cross in
// C order), the border word where a tap is outside the texture, zero where an edge shape has no
// texel (not read).
[[gnu::always_inline]] inline void CacheStage::emit() {
  const FootprintReq& cur = fifo_.front().f;
  read_out(cur, out_of(cur).push_slot());
  lines_in_flight_ -= fifo_.front().lines;  // its lines go from the line buffer into the cache
  fifo_.pop_front();
  sim_.progress();
}

void CacheStage::read_out_footprint(const FootprintReq& cur, FilterReq& f) const { read_out(cur, f); }

[[gnu::always_inline]] inline void CacheStage::read_out(const FootprintReq& cur, FilterReq& f) const {
  const TapGrid& g = cur.grid;
  f.tag = cur.tag;
  f.ntaps = cur.ntaps();
  const LevelReadout& level = level_readout(cur.tag.req.texture, cur.level);
  const auto border = [&] {  // the border word (clamp-to-border taps outside the texture)
    return regs_.textures[cur.tag.req.texture].content == TextureContent::BsplineCoefficients ? Rgba8{0, 0, 0, 0}
                                                                                             : regs_.samplers[cur.tag.req.sampler].border;
  };
  if (compressed_[static_cast<size_t>(cur.tag.req.texture)]) [[unlikely]] {
    read_out_blocks(cur, f, border());
    return;
  }
  if (!cur.cross && g.cols == g.rows && g.used == square_cells(g.cols, g.rows)) {
    switch (g.cols) {
      case 1: read_square_taps<1>(g, level, f.texels.data()); break;
      case 2: read_square_taps<2>(g, level, f.texels.data()); break;
      case 3: read_square_taps<3>(g, level, f.texels.data()); break;
      default: read_square_taps<4>(g, level, f.texels.data()); break;
    }
  } else {
    // The address parts of the grid's columns and rows, once (a border column or row, -1, is
    // never read: its cells are not used).
    std::array<size_t, 4> col{}, row{};
    for (size_t i = 0; i < static_cast<size_t>(g.cols); ++i) col[i] = level.column(g.x[i]);
    for (size_t j = 0; j < static_cast<size_t>(g.rows); ++j) row[j] = level.row(g.y[j]);
    const Rgba8 outside = border();
    const auto word = [&](size_t cell) { return ((g.used >> cell) & 1u) ? level.at(col[cell & 3] + row[cell >> 2]) : outside; };
    if (cur.cross) {
      // Every cross texel is read, at its address or, for a border cell, at the level's first
      // texel, and then selected: the texel, the border word, or zero outside the shape (selects,
      // not branches: the shape changes from pixel to pixel; the extra reads are the model's).
      const uint32_t outside_word = std::bit_cast<uint32_t>(outside);
#pragma GCC unroll 12
      for (size_t k = 0; k < lee_jen::kTexels; ++k) {
        const size_t cell = kCrossCell[k];
        const bool read = ((g.used >> cell) & 1u) != 0, in_shape = ((cur.tag.shape >> k) & 1u) != 0;
        const size_t offset = read ? col[cell & 3] + row[cell >> 2] : 0;
        uint32_t v = std::bit_cast<uint32_t>(level.at(offset));
        v = read ? v : outside_word;
        f.texels[k] = std::bit_cast<Rgba8>(in_shape ? v : 0u);
      }
    } else {
      size_t k = 0;
      for (size_t j = 0; j < static_cast<size_t>(g.rows); ++j)
        for (size_t i = 0; i < static_cast<size_t>(g.cols); ++i) f.texels[k++] = word(4 * j + i);
    }
  }
}

const Rgba8* CacheStage::decoded_block(const TextureDescriptor& d, uint64_t address, const HeldBlock* held, size_t n,
                                       Rgba8* scratch) const {
  const int shift = d.block().block_bytes == 8 ? 3 : 4;  // consecutive blocks, consecutive entries
  DecodedBlock& e = decoded_memo_[(address >> shift) & (kDecodedMemoEntries - 1)];
  if (e.address == address && e.format == d.block_format && e.rules == d.decode) return e.texels.data();
  for (size_t k = 0; k < n; ++k)
    if (held[k].texels == e.texels.data()) {  // the entry holds another block of this footprint
      decode_block(d.block_format, memory_.bytes_at(address), d.decode, scratch);
      return scratch;
    }
  decode_block(d.block_format, memory_.bytes_at(address), d.decode, e.texels.data());
  e.address = address;
  e.format = d.block_format;
  e.rules = d.decode;
  return e.texels.data();
}

void CacheStage::read_out_blocks(const FootprintReq& cur, FilterReq& f, Rgba8 outside) const {
  const TextureDescriptor& d = regs_.textures[static_cast<size_t>(cur.tag.req.texture)];
  const int block_w = d.block().block_w;
  const TapGrid& g = cur.blocks.blocks;  // the address generator's block coordinates
  std::array<HeldBlock, kHeldBlocks> blocks;  // the footprint's distinct blocks, each decoded once
  size_t n = 0;
  const auto texel = [&](size_t cell) {
    const uint64_t address = d.block_address(cur.level, g.x[cell & 3u], g.y[cell >> 2]);
    size_t k = 0;
    while (k < n && blocks[k].address != address) ++k;
    if (k == n) {
      blocks[n] = {address, decoded_block(d, address, blocks.data(), n, scratch_[n].data())};
      ++n;
    }
    return blocks[k].texels[texel_in_block(cur.blocks, cell, block_w)];
  };
  if (cur.cross) {  // the cross in C order: the texel, the border word, or zero outside the shape
    for (size_t k = 0; k < lee_jen::kTexels; ++k) {
      const size_t cell = kCrossCell[k];
      const bool in_shape = ((cur.tag.shape >> k) & 1u) != 0;
      f.texels[k] = !in_shape ? Rgba8{0, 0, 0, 0} : ((g.used >> cell) & 1u) ? texel(cell) : outside;
    }
    return;
  }
  size_t k = 0;
  for (size_t j = 0; j < static_cast<size_t>(g.rows); ++j)
    for (size_t i = 0; i < static_cast<size_t>(g.cols); ++i) {
      const size_t cell = 4 * j + i;
      f.texels[k++] = ((g.used >> cell) & 1u) ? texel(cell) : outside;
    }
}

void CacheStage::evaluate() {
  const uint64_t now = sim_.cycle();
  // Output side: the FIFO head leaves when its lines are in (one footprint per cycle).
  if (!fifo_.empty()) {
    if (now < fifo_.front().ready) {
      ++slots_[stat_slot(fifo_.front().f.tag.req)].stall_miss;
    } else if (!out_of(fifo_.front().f).can_push()) {
      ++slots_[stat_slot(fifo_.front().f.tag.req)].stall_back;
    } else {
      emit();
    }
  }
  // Input side: one tag lookup per cycle while the port is free, the FIFO has room and the line
  // buffer has room for the most lines a footprint can miss.
  if (in_.can_pop()) {
    if (now < port_free_) {
      ++slots_[stat_slot(in_.front().tag.req)].stall_bank;
    } else if (!fifo_.full()) {
      if (line_buffer_room()) {
        accept(now);
        sim_.progress();
      } else {
        ++slots_[stat_slot(in_.front().tag.req)].stall_line_buffer;
      }
    }
  }
}

uint64_t CacheStage::wake_cycle(uint64_t now) const {
  // A head whose lines arrive, or a port that frees, at `now` itself lets the block act now: that
  // wake (now) stops the jump. (Comparing with > dropped exactly that case, and a jump to a later
  // wake of the other side skipped the cycle in which the block would have acted.)
  uint64_t wake = kNever;
  if (!fifo_.empty() && fifo_.front().ready >= now) wake = fifo_.front().ready;
  if (in_.can_pop() && port_free_ >= now) wake = std::min(wake, port_free_);
  return wake;
}

void CacheStage::skip_cycles(uint64_t n) {
  // The skipped cycles all lie before wake_cycle(): the same stalls evaluate() would count.
  const uint64_t now = sim_.cycle();
  if (!fifo_.empty() && now < fifo_.front().ready)
    slots_[stat_slot(fifo_.front().f.tag.req)].stall_miss += n;
  else if (!fifo_.empty() && !out_of(fifo_.front().f).can_push())
    slots_[stat_slot(fifo_.front().f.tag.req)].stall_back += n;
  if (in_.can_pop() && now < port_free_) slots_[stat_slot(in_.front().tag.req)].stall_bank += n;
  else if (in_.can_pop() && !fifo_.full() && !line_buffer_room())
    slots_[stat_slot(in_.front().tag.req)].stall_line_buffer += n;
}

std::string CacheStage::state() const {
  return fmt::format("{}, {}, {}, miss fifo {}/{}, line buffer {}/{}{}", in_.state(), filter_out_.state(), edge_out_.state(),
                     fifo_.size(), fifo_.depth(), lines_in_flight_, line_buffer_depth_,
                     fifo_.empty() ? std::string() : fmt::format(", head ready at {}", fifo_.front().ready));
}

void CacheStage::publish(sim::Stats& st) const {
  uint64_t hits = 0, misses = 0;
  for (int l = 0; l < kMaxLevels; ++l) {  // counted by the cache's tag unit
    const uint64_t h = cache_.level_hits(l), m = cache_.level_misses(l);
    hits += h;
    misses += m;
    if (h + m == 0) continue;
    st.add(stat_key(UnitStat::CacheLineHitsLevel, l), h);
    st.add(stat_key(UnitStat::CacheLineMissesLevel, l), m);
  }
  add(st, UnitStat::CacheLineHits, hits);
  add(st, UnitStat::CacheLineMisses, misses);
  add(st, UnitStat::CacheSectorHits, cache_.sector_hits());
  add(st, UnitStat::CacheSectorLookups, cache_.sector_lookups());
  SlotCounters sum;
  for (const SlotCounters& c : slots_) {
    sum.footprints += c.footprints;
    sum.stall_miss += c.stall_miss;
    sum.stall_bank += c.stall_bank;
    sum.stall_back += c.stall_back;
    sum.stall_line_buffer += c.stall_line_buffer;
    for (size_t k = 0; k < 3; ++k) sum.shapes[k] += c.shapes[k];
    sum.decoded_blocks += c.decoded_blocks;
    sum.decoder_busy += c.decoder_busy;
    sum.decoder_stall += c.decoder_stall;
  }
  publish_stalls_shapes_decoders(st, sum);
}

void CacheStage::publish_slot(sim::Stats& st, size_t slot) const {
  const SlotCounters& c = slots_[slot];
  uint64_t hits = 0, misses = 0;
  for (size_t l = 0; l < c.level_hits.size(); ++l) {
    hits += c.level_hits[l];
    misses += c.level_misses[l];
    if (c.level_hits[l] + c.level_misses[l] == 0) continue;
    st.add(stat_key(UnitStat::CacheLineHitsLevel, static_cast<int>(l)), c.level_hits[l]);
    st.add(stat_key(UnitStat::CacheLineMissesLevel, static_cast<int>(l)), c.level_misses[l]);
  }
  add(st, UnitStat::CacheLineHits, hits);
  add(st, UnitStat::CacheLineMisses, misses);
  add(st, UnitStat::CacheSectorHits, c.sector_hits);
  add(st, UnitStat::CacheSectorLookups, c.sector_lookups);
  add(st, UnitStat::MemoryBytes, c.memory_bytes);
  add(st, UnitStat::MemoryRequests, c.memory_requests);
  publish_stalls_shapes_decoders(st, c);
}

void CacheStage::publish_stalls_shapes_decoders(sim::Stats& st, const SlotCounters& c) const {
  add(st, UnitStat::CacheFootprints, c.footprints);
  add(st, UnitStat::StallCacheMiss, c.stall_miss);
  add(st, UnitStat::StallBankConflict, c.stall_bank);
  add(st, UnitStat::StallBackpressure, c.stall_back);
  // Only where the line buffer ever stalled the tag stage (with a line buffer deep enough for the
  // latency it never does, and the statistics stay those of a unit without the bound).
  if (stalled_on_line_buffer()) add(st, UnitStat::StallLineBuffer, c.stall_line_buffer);
  if (any_compressed_) {
    add(st, UnitStat::DecodedBlocks, c.decoded_blocks);
    add(st, UnitStat::DecoderBusyCycles, c.decoder_busy);
    add(st, UnitStat::DecoderStallCycles, c.decoder_stall);
  }
  if (any_edge_) {
    add(st, UnitStat::ShapeCross, c.shapes[0]);
    add(st, UnitStat::ShapeT, c.shapes[1]);
    add(st, UnitStat::ShapeL, c.shapes[2]);
  }
}

}  // namespace tfu::rtl
