// OpenEXR output of named float channels, written whole or not at all through an OutputFile
// (io/output_file.h): a failed or interrupted run never leaves a partial file.
// Single-part files (write_exr/read_exr) and multi-part files (write_exr_parts/read_exr_parts).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "core/memory.h"

namespace oceanref {

// The widest or tallest data window the readers accept (OpenEXR's Header::setMaxImageSize and
// setMaxTileSize, set on the first read): four times the largest image oceanref renders.
inline constexpr int kMaxExrSide = 65536;

// One channel of a width × height image. A channel may be subsampled by an integer factor
// (EXR x/y sampling): it then holds (width/sampling) × (height/sampling) values, row-major.
struct ExrChannel {
  std::string name;
  int sampling = 1;
  std::vector<float> values;
};

// A 4×4 float matrix header attribute (Imf::M44fAttribute), m[row][column] as Imath stores it:
// OpenEXR's matrices act on row vectors, p' = p·M, so the translation is in row 3.
using ExrMatrix = std::array<std::array<float, 4>, 4>;

struct ExrImage {
  int width = 0;
  int height = 0;
  std::vector<ExrChannel> channels;
  std::map<std::string, std::string> attributes;  // string header attributes
  // M44f header attributes, e.g. the standard worldToCamera and worldToNDC.
  std::map<std::string, ExrMatrix> matrices;
  bool srgb_chromaticities = false;  // write the standard chromaticities of linear sRGB (D65)
  // Origin of the data window: pixel (column c, row r) of `channels` is EXR pixel
  // (origin_x + c, origin_y + r). 0, 0 for everything oceanref writes.
  int origin_x = 0;
  int origin_y = 0;
};

// One part of a multi-part EXR file (its `name` attribute), at one resolution level of a
// tiled multi-resolution part (0, 0 for scanline parts and the full-resolution level).
struct ExrPart {
  std::string name;
  int level_x = 0;
  int level_y = 0;
  ExrImage image;
};

// Writes with ZIP compression; throws std::runtime_error naming the file on failure.
void write_exr(const std::string& path, const ExrImage& image);
// Reads every channel as float (at its own sampling), the string and M44f attributes of a
// single-part file; a file with several parts is rejected (read it with read_exr_parts).
// At most `max_bytes` of pixels (as floats) are allocated: a larger file is refused before its
// pixels are read (readers also refuse data windows wider or taller than kMaxExrSide).
ExrImage read_exr(const std::string& path, double max_bytes = kDefaultMaxMemory);

// Writes a multi-part file (one part: an ordinary single-part file with a `name` attribute),
// atomically as write_exr, ZIP-compressed scanline parts of float channels. Every part needs a
// unique non-empty name, level 0, 0, its own size (data window) and attributes; the display
// window, shared by all parts, is the bounding box of the data windows. Subsampled channels and the
// reserved attribute names `name` and `type` are rejected (std::invalid_argument).
void write_exr_parts(const std::string& path, const std::vector<ExrPart>& parts);
// Reads every part of any OpenEXR file, scanline or tiled, and every resolution level of a
// tiled mip- or rip-mapped part: one ExrPart per part and level, in file order (levels in
// increasing level_y, then level_x). Channels are converted to float whatever their pixel type
// (half, float, uint); subsampled channels keep their sampling (equal in x and y); a data window
// not starting at 0, 0 sets origin_x/origin_y. The part's name is in ExrPart::name ("" for an
// unnamed single-part file), not in the attributes. Deep parts are rejected; every failure is a
// std::runtime_error naming the file (and the part). At most `max_bytes` of pixels in all (as
// floats) are allocated: a file needing more is refused with the size it needs.
std::vector<ExrPart> read_exr_parts(const std::string& path, double max_bytes = kDefaultMaxMemory);

}  // namespace oceanref
