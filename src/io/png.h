// 8-bit RGB PNG output for previews (zlib deflate, written atomically like the EXR files), whole
// (encode_png/write_png) or row by row in bounded memory (PngRowWriter). Both go through one
// encoder, so they give the same bytes: deflate level 9 fed one row at a time (filter byte 0
// before each row), the compressed stream cut into IDAT chunks of kPngIdatBytes (the last one
// shorter) as it comes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace oceanref {

// The data bytes of every IDAT chunk but the last.
inline constexpr std::size_t kPngIdatBytes = 65536;

// The PNG file's bytes (8-bit RGB); throws std::invalid_argument when rgb is not w × h × 3.
std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgb);
// rgb: width × height × 3 bytes, rows top to bottom. Throws std::runtime_error naming the file.
void write_png(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& rgb);

// A PNG written row by row through an OutputFile (io/output_file.h): the same bytes as
// encode_png of the whole image; the file appears only on a successful finish() (destroyed
// before, the writer leaves no file and the previous target untouched). Bad sizes throw
// std::invalid_argument, calls out of order std::logic_error, failed writes OutputWriteError;
// every message names the file.
class PngRowWriter {
 public:
  PngRowWriter(const std::string& path, int width, int height);
  ~PngRowWriter();
  PngRowWriter(PngRowWriter&&) noexcept;
  PngRowWriter& operator=(PngRowWriter&&) noexcept;

  void write_row(const std::uint8_t* rgb);  // width*3 bytes, rows top to bottom
  void finish();                            // every row written, else throws; call once
  int rows_written() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace oceanref
