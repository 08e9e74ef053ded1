// `oceanref fields SCENE`: every wave field of every cascade as EXR channels (-o), or every
// field at one point from the FFT grid and by direct summation (--at).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>
#include <string>

#include "io/exr.h"
#include "scene/scene.h"
#include "waves/stages.h"

namespace oceanref::cli {

// The fields file (`fields -o`, docs/FILES.md): one part per cascade and grid (c<i>,
// c<i>.low) and the combined fields (sum), every channel at full resolution; the SHA-256 of the
// float32 channels and of the doubles behind them: every channel of every part in name order
// (names are unique across parts), each its name, a zero byte and its values, row-major, as
// binary32 (sha256) or binary64 (f64_sha256) little-endian.
struct FieldsImage {
  std::vector<ExrPart> parts;
  std::string sha256;
  std::string f64_sha256;
};
FieldsImage fields_image(const Scene& scene, const Ocean& ocean, int threads);

// An earlier stage (not Stage::fields) on every cascade's grids, one part per cascade and grid
// (c<i>, c<i>.low), channels <part>.<stage channel> (waves/stages.h), at scene.time.
std::vector<ExrPart> stage_image(const Scene& scene, const Ocean& ocean, Stage stage, int threads);

std::function<void(std::ostream& out)> add_fields_command(CLI::App& app);

}  // namespace oceanref::cli
