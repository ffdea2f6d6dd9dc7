#pragma once
// Complex refractive indices (eta + i k) of common metals, sampled at 650, 550 and 450 nm for
// the R, G and B channels (measured optical constants as tabulated at refractiveindex.info).
// Their normal-incidence reflectance ((eta-1)^2 + k^2) / ((eta+1)^2 + k^2) is gold's familiar
// (0.94, 0.78, 0.37), for instance (a test checks the table against that formula).
#include <array>
#include <string_view>
#include <utility>

#include "glint/math/color.h"

namespace glint {

struct MetalPreset {
    std::string_view name;
    Color eta, k;
};

inline constexpr std::array<MetalPreset, 7> kMetals{{
    {"aluminium", {1.5196f, 0.96565f, 0.53124f}, {7.6635f, 6.4581f, 5.0699f}},
    {"chromium", {3.6400f, 2.9008f, 1.9906f}, {4.3511f, 4.2311f, 3.7505f}},
    {"copper", {0.27105f, 0.67693f, 1.3164f}, {3.6092f, 2.6248f, 2.2921f}},
    {"gold", {0.18299f, 0.42108f, 1.3734f}, {3.4242f, 2.3459f, 1.7704f}},
    {"iron", {2.9114f, 2.9497f, 2.5845f}, {3.0893f, 2.9318f, 2.7670f}},
    {"platinum", {2.4390f, 2.0847f, 1.7998f}, {4.3677f, 3.7153f, 3.0211f}},
    {"silver", {0.16262f, 0.14512f, 0.13550f}, {4.0728f, 3.1900f, 2.1997f}},
}};

/// The RGB stand-in of a measured metal spectrum pbrt-v4 names ("metal-Au-eta", "metal-Au-k"):
/// the preset's eta or k where glint has the metal (silver, aluminium, gold, copper), so that a
/// named metal looks the same in RGB mode from every reader; null for any other name.
inline const Color* named_metal_rgb(std::string_view spectrum_name) {
    static constexpr std::pair<std::string_view, std::string_view> kElements[] = {
        {"Ag", "silver"}, {"Al", "aluminium"}, {"Au", "gold"}, {"Cu", "copper"}};
    if (!spectrum_name.starts_with("metal-")) return nullptr;
    for (const auto& [element, metal] : kElements) {
        const std::string_view rest = spectrum_name.substr(6);
        if (!rest.starts_with(element) || rest.size() <= element.size() || rest[element.size()] != '-') continue;
        const std::string_view part = rest.substr(element.size() + 1);
        if (part != "eta" && part != "k") return nullptr;
        for (const MetalPreset& p : kMetals)
            if (p.name == metal) return part == "k" ? &p.k : &p.eta;
    }
    return nullptr;
}

}  // namespace glint
