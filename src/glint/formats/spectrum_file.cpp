#include "glint/formats/spectrum_file.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace glint {

std::optional<std::vector<double>> read_spectrum_file(const std::filesystem::path& file, std::string& error) {
    std::ifstream in(file);
    if (!in) {
        error = fmt::format("{} cannot be read", file.string());
        return std::nullopt;
    }
    std::vector<double> numbers;
    std::string line;
    while (std::getline(in, line)) {
        line = line.substr(0, line.find('#'));
        std::istringstream words(line);
        std::string w;
        while (words >> w) {
            char* end = nullptr;
            const double v = std::strtod(w.c_str(), &end);
            if (end == w.c_str() || *end != '\0' || !std::isfinite(v)) {
                error = fmt::format("{}: \"{}\" is not a number", file.string(), w);
                return std::nullopt;
            }
            numbers.push_back(v);
            if (numbers.size() > 1'000'000) {
                error = fmt::format("{}: more than a million values", file.string());
                return std::nullopt;
            }
        }
    }
    return numbers;
}

std::optional<PiecewiseLinearSpectrum> spectrum_from_pairs(std::span<const double> numbers, std::string& error) {
    if (numbers.size() < 2 || numbers.size() % 2 != 0) {
        error = fmt::format("a spectrum is wavelength-value pairs; got {} values", numbers.size());
        return std::nullopt;
    }
    std::vector<float> lambda, value;
    for (std::size_t i = 0; i + 1 < numbers.size(); i += 2) {
        if (!lambda.empty() && !(numbers[i] > lambda.back())) {
            error = fmt::format("the wavelengths of a spectrum must increase ({} after {})", numbers[i], lambda.back());
            return std::nullopt;
        }
        if (!(numbers[i + 1] >= 0) || !std::isfinite(numbers[i + 1])) {
            error = fmt::format("value {} at {} nm; a spectrum's values are finite and not negative", numbers[i + 1],
                                numbers[i]);
            return std::nullopt;
        }
        lambda.push_back(float(numbers[i]));
        value.push_back(float(numbers[i + 1]));
    }
    return PiecewiseLinearSpectrum(std::move(lambda), std::move(value));
}

}  // namespace glint
