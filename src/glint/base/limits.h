#pragma once
// What one scene may ask for, as policy (docs/architecture.md, "Robustness"): each limit is far
// beyond any sensible render and exists so that a typo, a corrupt header or a hostile file gets a
// clear error, checked before the allocation it guards, instead of exhausting memory or running
// for a year. The limits a user may need to raise are named and set from the command line
// (`--limit NAME=N`); the rest are fixed.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace glint {

// Fixed: what no scene needs more of.
inline constexpr long long kMaxFilmSide = 1 << 16;  ///< pixels per side
inline constexpr long long kMaxSpp = 1 << 20;
inline constexpr long long kMaxDepth = 10000;
inline constexpr long long kMaxThreads = 1024;
/// Voxel grids: the bounding box of a grid's active voxels (a 512 MB brick index at most).
inline constexpr long long kMaxGridBoxVoxels = 1LL << 36;

/// The limits `--limit NAME=N` sets (process-wide; set before reading starts).
enum class Limit {
    kFilmPixels,     ///< film-pixels: pixels of the film (134M: 1.6 GB of float RGB)
    kTexturePixels,  ///< texture-pixels: pixels of one image map (134M)
    kTriangles,      ///< triangles: triangles of one mesh file or inline mesh (268M)
    kVertices,       ///< vertices: vertices of one mesh file or inline mesh (268M)
    kGridVoxels,     ///< grid-voxels: voxels stored by one grid medium (268M: 1 GB of floats)
    kNesting,        ///< nesting: depth of nested blocks (YAML, JSON, pbrt attributes, glTF nodes)
    kIncludes,       ///< includes: depth of files including files
    kMemory,         ///< memory: bytes a scene may allocate before the first pixel (the machine's RAM)
    kNodes,          ///< nodes: values one YAML/JSON file holds once its aliases are expanded (16M)
};
inline constexpr int kLimitCount = 9;

/// The current value of a limit.
long long limit(Limit l);
/// Sets a limit (for `--limit`, tests and fuzzers).
void set_limit(Limit l, long long value);
/// The limit named `name` ("triangles", ...), if any.
std::optional<Limit> limit_named(std::string_view name);
/// Every limit's name, comma-separated (for messages and --help).
std::string limit_names();
/// "NAME=N" from the command line: sets the limit, or throws IoError saying what is wrong. N may
/// carry a suffix k, M, G (powers of 1000) or KiB, MiB, GiB (powers of 1024).
void set_limit_from_text(const std::string& assignment);
/// The error text for `asked` over a limit, naming the flag that raises it:
/// "2000000000 triangles exceed the limit of 268435456 (raise it with --limit triangles=N)".
/// `cap`: the value to report when a caller applies a lower one than the limit's.
std::string over_limit(Limit l, long long asked, long long cap = 0);

/// The memory budget: the bytes a scene has asked to allocate so far (meshes, images, grids, the
/// film, the acceleration structure), charged before each large allocation. Reading a new scene
/// (parse_scene, parse_pbrt) resets it.
void reset_memory_budget();
/// Charges `bytes` for `what`; returns the error text if the total would exceed the memory limit
/// (the charge is then not made), empty otherwise. Thread-safe.
std::string charge_memory(long long bytes, std::string_view what);
/// Bytes charged since the last reset.
long long memory_charged();

}  // namespace glint
