#pragma once
// Checkpoints of a progressive render: the film's running sums after the completed passes, the
// samples done, and a fingerprint of the scene and the options, so that `--resume` continues the
// same render and refuses any other.
//
// The file (little-endian, version 3):
//   0   "GLINTCKP"                   magic
//   8   u32 version, u32 flags       bit 0: adaptive sampling, bit 1: AOVs
//   16  u64 fingerprint
//   24  i32 width, height, spp target, spp done, passes, 0
//   48  f64 seconds rendered, u64 rays traced
//   64  u64 payload bytes
//   72  the planes, pixel by pixel, row 0 first: sum (3 f32), weight (f32); adaptive: odd-sample
//       sum (3 f32), odd-sample weight (f32), sample count (u32), active (u8); AOVs: albedo
//       (3 f32), odd-sample albedo (3 f32), normal (3 f32), depth (f32), depth weight (f32)
//   end u64 checksum of every byte before it
// Written atomically (a temporary file, flushed to disk, then renamed), so a checkpoint on disk
// is always whole, whenever the process is killed.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "glint/builder/build.h"
#include "glint/render/progressive.h"

namespace glint {

/// A 64-bit hash of bytes, eight at a time (for checksums and fingerprints; not cryptographic).
std::uint64_t hash_bytes(const void* data, std::size_t size, std::uint64_t seed = 0);

/// What a checkpoint must match: `settings` (the options that change the image, as text), the
/// scene files' text (job.sources), every mesh's vertex data and indices, every image's texels,
/// the camera (rays through five film points) and the acceleration backend.
std::uint64_t render_fingerprint(const RenderJob& job, std::string_view settings);

void write_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint,
                      const ProgressiveState& state);

struct Checkpoint {
    std::uint64_t fingerprint = 0;
    ProgressiveState state;
};

/// Reads and checks a checkpoint: a damaged, truncated or foreign file is an IoError naming the
/// file and the byte offset; sizes are checked before anything is allocated.
Checkpoint read_checkpoint(const std::filesystem::path& path);

/// "90", "90s", "10m", "1h30m", "2.5h", "1d": seconds. Throws IoError naming `what` otherwise.
double parse_duration(const std::string& text, const std::string& what);

}  // namespace glint
