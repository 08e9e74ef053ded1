// OpenEXR output of named float channels, written whole or not at all through an OutputFile
// (io/output_file.h): a failed or interrupted run never leaves a partial file.
// Single-part files (write_exr/read_exr, or band by band: ExrRowWriter/read_exr_rows) and
// multi-part files (write_exr_parts/read_exr_parts).
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <span>
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

// Writes with ZIP compression; throws std::runtime_error naming the file on failure. Images whose
// channels all have sampling 1 are written by an ExrRowWriter in one band (the same bytes).
void write_exr(const std::string& path, const ExrImage& image);

// Reads every channel as float (at its own sampling), the string and M44f attributes of a
// single-part file; a file with several parts is rejected (read it with read_exr_parts).
// At most `max_bytes` of pixels (as floats) are allocated: a larger file is refused before its
// pixels are read (readers also refuse data windows wider or taller than kMaxExrSide).
ExrImage read_exr(const std::string& path, double max_bytes = kDefaultMaxMemory);

// A single-part EXR written band by band (bounded memory): the same bytes as write_exr of the
// whole image. `layout`: size, origin, channels (unique names; sampling 1; values ignored),
// attributes, matrices, chromaticities. Attributes named in `deferred` (name -> final length in
// bytes; each must be a string attribute of `layout`, whose value is ignored) are written as
// placeholders of that length and must be given with set_deferred before finish (e.g. a hash of
// the pixels, known only at the end): OpenEXR writes the header first, so the writer patches the
// placeholder's bytes in place (seeking through the OutputFile, as OpenEXR does for its offset
// table). The file appears only on a successful finish(); destroyed before that (or after any
// failure), the writer leaves no file and the previous target untouched.
// Errors: bad arguments std::invalid_argument, calls out of order std::logic_error, a deferred
// attribute that cannot be located in the header std::logic_error, failed writes
// OutputWriteError / std::runtime_error; every message names the file.
class ExrRowWriter {
 public:
  ExrRowWriter(const std::string& path, const ExrImage& layout,
               const std::map<std::string, std::size_t>& deferred = {});
  ~ExrRowWriter();  // without finish(): no file appears (the temporary is removed)
  ExrRowWriter(ExrRowWriter&&) noexcept;
  ExrRowWriter& operator=(ExrRowWriter&&) noexcept;

  // The next `rows` rows (>= 1): one vector per channel of `layout`, in layout order, each
  // rows x width values, row-major.
  void write_rows(const std::vector<std::vector<float>>& channels, int rows);
  // The same from views of the caller's buffers (no copy; write_exr uses it).
  void write_rows_from(const std::vector<std::span<const float>>& channels, int rows);
  // The final value of a deferred attribute: exactly its declared length.
  void set_deferred(const std::string& name, const std::string& value);
  // Throws std::logic_error unless every row was written and every deferred attribute set;
  // then completes the file and renames it over the target. Call once.
  void finish();
  int rows_written() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Rows [first_row, last_row) of the named channels of a single-part scanline EXR, as float,
// row-major (one vector per name, (last_row - first_row) x width values). Rows count from the
// top of the data window (row r is EXR line origin_y + r, as in ExrImage). Reads only the
// blocks holding those rows (bounded memory). Throws std::runtime_error naming the file: a
// missing, repeated or subsampled channel, rows outside the data window, a tiled, deep or
// multi-part file.
std::vector<std::vector<float>> read_exr_rows(const std::string& path,
                                              const std::vector<std::string>& channels,
                                              int first_row, int last_row);

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
