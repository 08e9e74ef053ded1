// SHA-256 (FIPS 180-4), for the pixel-data identity of golden images.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace oceanref {

// An incremental SHA-256: the digest of the concatenation of every update(), however the bytes
// were split (so a hash over an image can be taken band by band in bounded memory).
class Sha256 {
 public:
  void update(const void* bytes, std::size_t count);
  // The digest as 64 lowercase hexadecimal digits. Call once: afterwards update() and
  // hex_digest() throw std::logic_error.
  std::string hex_digest();

 private:
  void compress(const std::uint8_t* block);
  std::array<std::uint32_t, 8> state_{0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                      0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  std::array<std::uint8_t, 64> block_{};  // bytes of the current, incomplete 64-byte block
  std::size_t buffered_ = 0;              // how many of block_ hold data
  std::uint64_t length_ = 0;              // message length so far, bytes
  bool finished_ = false;
};

// The digest of a byte string as 64 lowercase hexadecimal digits.
std::string sha256_hex(const std::vector<std::uint8_t>& data);
std::string sha256_hex(const std::string& data);

// Appends a value's IEEE-754 bits, little-endian (the byte order every hash here uses).
void append_bytes(std::vector<std::uint8_t>& bytes, float v);
void append_bytes(std::vector<std::uint8_t>& bytes, double v);

}  // namespace oceanref
