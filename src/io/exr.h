// OpenEXR output of named float channels, written atomically: to a temporary name in the same
// folder, then renamed, so a failed or interrupted run never leaves a partial file.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace oceanref {

// One channel of a width × height image. A channel may be subsampled by an integer factor
// (EXR x/y sampling): it then holds (width/sampling) × (height/sampling) values, row-major.
struct ExrChannel {
  std::string name;
  int sampling = 1;
  std::vector<float> values;
};

struct ExrImage {
  int width = 0;
  int height = 0;
  std::vector<ExrChannel> channels;
  std::map<std::string, std::string> attributes;  // string header attributes
  bool srgb_chromaticities = false;  // write the standard chromaticities of linear sRGB (D65)
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
// Reads every channel as float (at its own sampling) and the string attributes.
ExrImage read_exr(const std::string& path);

}  // namespace oceanref
