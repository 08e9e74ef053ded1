// The HTML report of a comparison (`oceanref compare --report DIR`): one self-contained page
// (every image a PNG data: URI, the script inline, nothing fetched) that opens offline.
//
// Per part: the tone-mapped golden and candidate (when both have R, G, B) with a flip toggle.
// Per compared channel: the golden and candidate values (grey, scaled to the golden's range)
// with a flip (button, or hover), a heat map of the relative error e on a log scale (the same
// scale for every channel: 10^-9 … 10^0, e = 0 black, non-finite mismatches cyan, legend with
// numbers and the channel's threshold marked), a fail mask (failing values red) and crops of
// 15 × 15 values around the worst values (golden, candidate, error; enlarged). The page's script
// wires the flips and writes a marker element, id "rendered-channels", listing every channel whose
// images it decoded; a script error writes an element with id "script-error".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "conformance/compare.h"

namespace oceanref {

// The heat map colour of a relative error e on the report's log scale (black for 0, cyan for
// a non-finite value): dark blue → purple → orange → yellow over 10^kHeatLowDecade … 10^0.
inline constexpr int kHeatLowDecade = -9;
inline constexpr int kHeatHighDecade = 0;
std::array<std::uint8_t, 3> heat_colour(double e);

// Writes DIR/index.html and DIR/diff.exr (per part 0, the largest e over the full-resolution
// channels per pixel). Creates DIR if needed; each file is written atomically.
void write_report(const std::string& directory, const std::string& golden_name,
                  const std::string& candidate_name, const std::vector<ExrPart>& golden,
                  const std::vector<ExrPart>& candidate, const Comparison& comparison);

}  // namespace oceanref
