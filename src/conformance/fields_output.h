// The fields file (`oceanref fields -o`, docs/FILES.md "The fields EXR") and the stage files
// (`fields --stage`): the parts, channels and attributes oceanref writes, and the fields hashes
// the golden suite checks; every field at one point from the grids and by direct summation.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/memory.h"
#include "io/exr.h"
#include "scene/scene.h"
#include "waves/stages.h"

namespace oceanref {

// The fields file: one part per cascade and grid (c<i>, c<i>.low) and the combined fields
// (sum), every field at full resolution as channel exr_channel_name(field) ("c0.height.V",
// conformance/channel_name.h); the SHA-256 of the float32 channels and of the doubles behind
// them: every field of every part in field-name order (names are unique across parts), each its
// field name (without ".V"), a zero byte and its values, row-major, as binary32 (sha256) or
// binary64 (f64_sha256) little-endian.
struct FieldsImage {
  std::vector<ExrPart> parts;
  std::string sha256;
  std::string f64_sha256;
};
// Every large buffer fields_image (and stage_image, which needs less) allocates for `scene`
// (bytes): the wave grids, each output value as float and double and in the hash input, the
// combined fields and the foam accumulation.
MemoryEstimate fields_memory_estimate(const Scene& scene);
// `log` (may be empty) receives progress notes.
FieldsImage fields_image(const Scene& scene, const Ocean& ocean, int threads,
                         const std::function<void(const std::string&)>& log = {});

// An earlier stage (not Stage::fields) on every cascade's grids, one part per cascade and grid
// (c<i>, c<i>.low), fields <part>.<stage channel> (waves/stages.h) as channels
// exr_channel_name(field) ("c0.low.h0.re.V"), at scene.time.
std::vector<ExrPart> stage_image(const Scene& scene, const Ocean& ocean, Stage stage, int threads);

// One field at a point (x, z) [m] at scene.time: from the FFT grids (exact at nodes, bilinear
// between) and by direct summation of every component. Rows: cascade "<i>" and every field of
// kFieldNames, then cascade "sum": height, slope_x, slope_z, jacobian, normal_x, normal_y,
// normal_z, foam, combined as shading.normals says.
struct PointFieldRow {
  std::string cascade;
  std::string field;
  double fft = 0.0;
  double direct = 0.0;
};
std::vector<PointFieldRow> fields_at_point(const Scene& scene, const Ocean& ocean, double x,
                                           double z, int threads);

}  // namespace oceanref
