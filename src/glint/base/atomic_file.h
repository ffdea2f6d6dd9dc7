#pragma once
// Files written whole or not at all, the one way glint writes every file it makes (images,
// checkpoints, converted scenes, an animation's frames from other ranks): the bytes go to a
// temporary file beside the target, which is renamed over the target only once complete. A
// failed or killed run never leaves a truncated file and never clobbers an existing one.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace glint {

/// The temporary file a write to `target` goes through before its rename: in the same folder,
/// named after the target and the process, so that a signal handler can find and remove it.
std::filesystem::path temporary_path(const std::filesystem::path& target);

/// `bytes` into `path`'s temporary file (not renamed yet). `what` names the file in errors
/// ("the image"): IoError "PATH: cannot write WHAT: REASON", the temporary removed. `durable`:
/// flushed to the disk before it is closed (checkpoints: a power cut leaves the old or the new).
void write_temporary(const std::filesystem::path& path, std::span<const std::uint8_t> bytes, std::string_view what,
                     bool durable = false);

/// Renames `path`'s temporary file (written by write_temporary, or by a library given
/// temporary_path) over `path`; on failure removes it and throws IoError "PATH: cannot move
/// WHAT into place: REASON". `durable`: the rename itself flushed to the disk.
void move_into_place(const std::filesystem::path& path, std::string_view what, bool durable = false);

/// write_temporary, then move_into_place.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes,
                           std::string_view what = "the file", bool durable = false);

}  // namespace glint
