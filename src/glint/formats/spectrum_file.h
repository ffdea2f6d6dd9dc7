#pragma once
// Spectra as files and number lists, shared by the readers (pbrt-v4's "spectrum" parameters,
// YAML's `{file: ...}`): pbrt-v4's .spd format is whitespace-separated numbers, wavelength-value
// pairs, with '#' comments.
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "glint/spectra/spectrum.h"

namespace glint {

/// The numbers of a spectrum file; nullopt with `error` set if it cannot be read, holds something
/// that is not a finite number, or more than a million values.
std::optional<std::vector<double>> read_spectrum_file(const std::filesystem::path& file, std::string& error);

/// Wavelength-value pairs as a spectrum; nullopt with `error` set for an odd or too small count,
/// wavelengths that do not increase, or a negative or non-finite value.
std::optional<PiecewiseLinearSpectrum> spectrum_from_pairs(std::span<const double> numbers, std::string& error);

}  // namespace glint
