// SHA-256 (FIPS 180-4), for the pixel-data identity of golden images.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace oceanref {

// The digest of a byte string as 64 lowercase hexadecimal digits.
std::string sha256_hex(const std::vector<std::uint8_t>& data);
std::string sha256_hex(const std::string& data);

// Appends a value's IEEE-754 bits, little-endian (the byte order every hash here uses).
void append_bytes(std::vector<std::uint8_t>& bytes, float v);
void append_bytes(std::vector<std::uint8_t>& bytes, double v);

}  // namespace oceanref
