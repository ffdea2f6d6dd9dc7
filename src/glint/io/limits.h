#pragma once
// Limits on what a scene or the command line may ask for, checked before any large allocation.
// They are far beyond any sensible render and exist so that a typo (an extra zero or three)
// gets a clear error instead of exhausting memory or running for a year.
#include <cstdint>

namespace glint {

inline constexpr long long kMaxFilmSide = 1 << 16;           ///< pixels per side
inline constexpr long long kMaxFilmPixels = 1LL << 27;       ///< 134M pixels: 1.6 GB of float RGB
inline constexpr long long kMaxSpp = 1 << 20;
inline constexpr long long kMaxDepth = 10000;
inline constexpr long long kMaxThreads = 1024;
inline constexpr long long kMaxTexturePixels = 1LL << 27;  ///< per image: 1.6 GB as float RGB

}  // namespace glint

namespace glint {
/// Voxel grids: the bounding box of a grid's active voxels, and the voxels actually stored.
inline constexpr long long kMaxGridBoxVoxels = 1LL << 36;  ///< 4096^3: a 512 MB brick index at most
inline constexpr long long kMaxGridVoxels = 1LL << 28;     ///< 1 GB of float voxels
}  // namespace glint
