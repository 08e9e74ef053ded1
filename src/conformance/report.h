// The HTML report of a comparison: golden, candidate and a difference heat map side by side
// with the metrics table (`oceanref compare --report DIR`).
#pragma once

#include <string>

#include "conformance/compare.h"

namespace oceanref {

// Writes DIR/diff.exr (the largest |a − b| per pixel), DIR/golden.png, DIR/candidate.png (both
// tone-mapped with the golden image's exposure; grey of the first channel when there is no
// R, G, B), DIR/diff.png (heat map, black → red → yellow → white up to the largest difference)
// and DIR/index.html. Creates DIR if needed.
void write_report(const std::string& directory, const std::string& golden_name,
                  const std::string& candidate_name, const ExrImage& golden,
                  const ExrImage& candidate, const Comparison& comparison);

}  // namespace oceanref
