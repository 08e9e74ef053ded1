// A render split over processes (`oceanref render --tile I/N`, `oceanref merge`; docs/FILES.md
// "Render pieces"): tile I of N is the band of pixel rows [I·H/N, (I+1)·H/N), rendered alone
// (RenderJob::first_row/last_row, each pixel the same bits as in a whole render) and written
// with its double-precision buffers; merging the N pieces gives the RenderedImage of one
// process, so the EXR, the PNG and every printed figure written from it are the same bytes.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raster/renderer.h"
#include "scene/scene.h"

namespace oceanref {

// A piece file that cannot be read, or pieces that do not merge; `what()` names the file.
class RenderPieceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Tile `index` of `count` over an image of `height` rows: its pixel rows [first, last).
// Requires 0 ≤ index < count ≤ height.
std::pair<int, int> tile_rows(int index, int count, int height);

struct RenderPiece {
  std::string scene_sha256;  // of the scene's canonical form (Scene::canonical)
  int tile = 0, tiles = 1;   // tile `tile` of `tiles`
  int samples_per_axis = 1;
  bool layers = false;       // the band holds the --aov layers
  bool adaptive = false;     // and the sample counts of adaptive sampling (pixel_samples)
  bool antialiased = false;  // rendered with render.mastin_antialiasing (its count in the header)
  RenderedImage band;  // width × rows from band.first_row (unresolved, bound, counts included)
};

// Writes the piece atomically (io/output_file.h). Format (docs/FILES.md): the line
// "oceanref render piece 3", a one-line JSON header, then the band's buffers as binary64
// little-endian, row-major: radiance RGB, lighting_error RGB, pixel_error RGB, coverage, with
// adaptive sampling pixel_samples, and with layers sun, sky, sea, foam RGB, depth, normal xyz,
// x0 xyz.
void write_render_piece(const std::string& path, const RenderPiece& piece);
// Reads and checks a piece: the magic line, every header field (types and ranges), and the size
// of the file against the header, before anything large is allocated. Throws RenderPieceError.
RenderPiece read_render_piece(const std::string& path);

// The whole image from the pieces of one render of `scene` (paths name them in messages): every
// piece of this scene (its hash), the same tile count, samples and layers, each tile exactly
// once, the same unresolved slope variance and displacement bound; the counts are summed.
// Throws RenderPieceError naming the offending file.
RenderedImage merge_render_pieces(const Scene& scene, const std::vector<RenderPiece>& pieces,
                                  const std::vector<std::string>& paths);

}  // namespace oceanref
