// Block-compressed texture files: a BlockImage (cmodel/block_formats.hpp) with all its MIP levels
// read from and written to the standard containers (docs/compressed-files.md):
//   * DDS (Microsoft DirectDraw Surface, "DDS " + DDS_HEADER of 124 bytes, the DX10 header of 20
//     bytes where a format needs it): the BC formats. BC1-BC3 linear are written with the legacy
//     FourCCs DXT1/DXT3/DXT5 (BC1 with DDPF_ALPHAPIXELS set is bc1a), BC4/BC5 with BC4U/BC4S/BC5U/
//     BC5S, BC7 and every sRGB variant with the DX10 header and the table's DXGI code (BC1 opaque:
//     DDS_ALPHA_MODE_OPAQUE in miscFlags2). Read also: ATI1, ATI2.
//   * KTX version 1 (Khronos, "«KTX 11»"): every format, by the table's GL internal format (the
//     linear or the sRGB enum). KTX1 rather than KTX2: its header names a compressed format by the
//     GL enum the table already holds (KTX2 needs a VkFormat and a Data Format Descriptor for each
//     format, a second table), and Mesa, ARM's astcenc and PVRTexTool read and write it.
//   * ARM's .astc file (magic 0x5CA1AB13, block and texel sizes in a 16-byte header): one ASTC
//     level, no sRGB flag (read as linear).
// The container is found by its magic, never by the file's extension. Every reader checks the
// header against the file: magic, header sizes, format codes, 2D only (no cube maps, arrays or
// volumes), sizes 1..kMaxTextureSize, MIP counts at most the full chain's, each level's bytes
// against its block count, truncation and trailing bytes; a bad file is one InputError line
// "LABEL: CONTAINER: what is wrong". The file goes through cmodel/input_file.hpp (a regular file of
// at most kMaxImageBytes) and its bytes and blocks are charged to the memory budget
// (cmodel/memory_budget.hpp) before they are read.
// Tested: TextureContainers.* (testbench/test_texture_containers.cpp), fuzz_containers.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cmodel/block_formats.hpp"
#include "cmodel/enum_names.hpp"

namespace tfu {

enum class BlockContainer : uint8_t { DDS, KTX, ASTC };
inline constexpr EnumNames<BlockContainer, 3> kBlockContainerNames{
    "container", {{{BlockContainer::DDS, "dds"}, {BlockContainer::KTX, "ktx"}, {BlockContainer::ASTC, "astc"}}}};
const char* block_container_name(BlockContainer c);
// "a DDS file", "a KTX file", "an .astc file": for messages.
const char* container_file_text(BlockContainer c);

// Whether the container can hold the format: DDS the BC family, KTX all, .astc the ASTC family.
bool container_holds(BlockContainer c, BlockFormat f);
// Where a format goes by default: DDS for BC, KTX for ETC/EAC and ASTC (all MIP levels).
BlockContainer default_container(BlockFormat f);
// The container whose magic the bytes start with, if any.
std::optional<BlockContainer> container_by_magic(std::span<const uint8_t> bytes);
// True when `path` is a regular file that starts with a container's magic (its first 16 bytes are
// read; anything else, a FIFO or a device included, is false without reading: the image reader's
// input checks then refuse it). What load_texture asks before choosing the image reader.
bool is_block_container_file(const std::string& path);

// Throws InputError (naming `label`) unless the image is well formed: every level's size follows
// the MIP rule from level 0 (1..kMaxTextureSize), at most the full chain, and holds
// block_level_bytes of blocks; a signed or sRGB-less format without the sRGB flag.
void validate_block_image(const BlockImage& image, const std::string& label);

// Parses a container from memory (the magic chooses the reader). `label` names the input in errors.
BlockImage parse_block_image(std::span<const uint8_t> bytes, const std::string& label);
// Reads a file (input checks, memory budget, parse). `label` defaults to the quoted path.
BlockImage read_block_image(const std::string& path, const std::string& label = {});

// The file's bytes. InputError (naming `label`) when the container cannot hold the format, the
// image is not well formed, or (.astc) it has more than one level.
std::vector<uint8_t> serialize_block_image(const BlockImage& image, BlockContainer c, const std::string& label);

}  // namespace tfu
