#pragma once
// Complex refractive indices (eta + i k) of common metals, sampled at 650, 550 and 450 nm for
// the R, G and B channels (measured optical constants as tabulated at refractiveindex.info).
// Their normal-incidence reflectance ((eta-1)^2 + k^2) / ((eta+1)^2 + k^2) is gold's familiar
// (0.94, 0.78, 0.37), for instance (a test checks the table against that formula).
#include <array>
#include <string_view>

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

}  // namespace glint
