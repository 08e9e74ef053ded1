// 8-bit RGB PNG output for previews (zlib deflate, written atomically like the EXR files).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace oceanref {

// The PNG file's bytes (8-bit RGB); throws std::invalid_argument when rgb is not w × h × 3.
std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgb);
// rgb: width × height × 3 bytes, rows top to bottom. Throws std::runtime_error naming the file.
void write_png(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& rgb);

}  // namespace oceanref
