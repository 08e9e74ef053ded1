#include "io/png.h"

#include <zlib.h>

#include <array>
#include <functional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "io/output_file.h"

namespace oceanref {

namespace {
void put32(std::uint8_t* out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(v >> (8 * (3 - i)));
}

void check_size(int width, int height, const std::string& who) {
  // A row (filter byte and width*3 bytes) must fit zlib's 32-bit counts.
  if (width < 1 || height < 1 || width > (1 << 28)) {
    throw std::invalid_argument(who + ": a " + std::to_string(width) + "x" +
                                std::to_string(height) + " image cannot be written");
  }
}

// The PNG encoder both writers share: signature and IHDR at construction, then each row through
// deflate (level 9, zlib's default window and memory), an IDAT chunk of kPngIdatBytes each time
// the compressed buffer fills, the rest and IEND at finish. Every byte goes to `sink`.
class PngEncoder {
 public:
  using Sink = std::function<void(const std::uint8_t*, std::size_t)>;

  PngEncoder(int width, int height, Sink sink) : width_(width), sink_(std::move(sink)) {
    if (deflateInit(&z_, 9) != Z_OK) throw std::runtime_error("PNG: cannot start zlib deflate");
    initialized_ = true;
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    sink_(kSignature, sizeof kSignature);
    std::uint8_t header[13] = {};
    put32(header, static_cast<std::uint32_t>(width));
    put32(header + 4, static_cast<std::uint32_t>(height));
    header[8] = 8;  // bits per sample
    header[9] = 2;  // truecolour; deflate, no filter method, no interlace: 0
    chunk("IHDR", header, sizeof header);
  }
  ~PngEncoder() {
    if (initialized_) deflateEnd(&z_);
  }
  PngEncoder(const PngEncoder&) = delete;
  PngEncoder& operator=(const PngEncoder&) = delete;

  int rows() const { return rows_; }

  void write_row(const std::uint8_t* rgb) {
    static constexpr std::uint8_t kFilterNone = 0;
    deflate_bytes(&kFilterNone, 1, Z_NO_FLUSH);
    deflate_bytes(rgb, static_cast<std::size_t>(width_) * 3, Z_NO_FLUSH);
    ++rows_;
  }

  void finish() {
    deflate_bytes(nullptr, 0, Z_FINISH);
    if (z_.avail_out < out_.size()) chunk("IDAT", out_.data(), out_.size() - z_.avail_out);
    chunk("IEND", nullptr, 0);
  }

 private:
  // Feeds `count` bytes to deflate; with Z_FINISH, until the stream ends. A full output buffer
  // becomes an IDAT chunk.
  void deflate_bytes(const std::uint8_t* bytes, std::size_t count, int flush) {
    z_.next_in = const_cast<Bytef*>(bytes);  // zlib's input pointer is not const
    z_.avail_in = static_cast<uInt>(count);
    while (true) {
      if (z_.avail_out == 0) {
        if (z_.next_out != nullptr) chunk("IDAT", out_.data(), out_.size());
        z_.next_out = out_.data();
        z_.avail_out = static_cast<uInt>(out_.size());
      }
      const int status = deflate(&z_, flush);
      if (status == Z_STREAM_END) return;
      if (status != Z_OK && status != Z_BUF_ERROR) {
        throw std::runtime_error("PNG: zlib deflate failed (" + std::to_string(status) + ")");
      }
      if (flush == Z_NO_FLUSH && z_.avail_in == 0 && z_.avail_out > 0) return;
    }
  }

  // A chunk: length, type, data, CRC-32 of type and data.
  void chunk(const char* type, const std::uint8_t* data, std::size_t count) {
    std::uint8_t head[8] = {};
    put32(head, static_cast<std::uint32_t>(count));
    for (int i = 0; i < 4; ++i) head[4 + i] = static_cast<std::uint8_t>(type[i]);
    uLong crc = crc32(0L, head + 4, 4);
    if (count > 0) crc = crc32(crc, data, static_cast<uInt>(count));
    std::uint8_t tail[4] = {};
    put32(tail, static_cast<std::uint32_t>(crc));
    sink_(head, sizeof head);
    if (count > 0) sink_(data, count);
    sink_(tail, sizeof tail);
  }

  int width_;
  int rows_ = 0;
  Sink sink_;
  z_stream z_{};
  bool initialized_ = false;
  std::array<std::uint8_t, kPngIdatBytes> out_{};
};
}  // namespace

std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgb) {
  if (width < 1 || height < 1 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    throw std::invalid_argument("PNG: " + std::to_string(rgb.size()) + " bytes for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " image");
  }
  check_size(width, height, "PNG");
  std::vector<std::uint8_t> out;
  PngEncoder encoder(width, height, [&out](const std::uint8_t* bytes, std::size_t count) {
    out.insert(out.end(), bytes, bytes + count);
  });
  const auto row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    encoder.write_row(rgb.data() + static_cast<std::size_t>(y) * row);
  }
  encoder.finish();
  return out;
}

void write_png(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& rgb) {
  if (width < 1 || height < 1 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    throw std::invalid_argument(path + ": PNG: " + std::to_string(rgb.size()) + " bytes for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " image");
  }
  PngRowWriter writer(path, width, height);
  const auto row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    writer.write_row(rgb.data() + static_cast<std::size_t>(y) * row);
  }
  writer.finish();
}

// ---- PngRowWriter ------------------------------------------------------------------------------

struct PngRowWriter::State {
  std::string path;
  int height = 0;
  bool done = false;  // finished, or failed: no further call is accepted
  // Destroyed in reverse order: the encoder, then the file (which removes the temporary unless
  // committed).
  std::unique_ptr<OutputFile> file;
  std::unique_ptr<PngEncoder> encoder;

  void check_open(const char* call) const {
    if (done) {
      throw std::logic_error(path + ": PngRowWriter::" + call +
                             " after finish() or after a failed write");
    }
  }
  // Runs `f`; any failure ends the writer and names the file.
  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (const OutputWriteError&) {
      done = true;
      throw;
    } catch (const std::exception& e) {
      done = true;
      throw std::runtime_error(path + ": cannot write the PNG file: " + e.what());
    }
  }
};

PngRowWriter::PngRowWriter(const std::string& path, int width, int height)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  s.height = height;
  check_size(width, height, path);
  s.file = std::make_unique<OutputFile>(path);
  OutputFile& file = *s.file;
  s.guarded([&] {
    s.encoder = std::make_unique<PngEncoder>(
        width, height,
        [&file](const std::uint8_t* bytes, std::size_t count) { file.write(bytes, count); });
  });
}

PngRowWriter::~PngRowWriter() = default;
PngRowWriter::PngRowWriter(PngRowWriter&&) noexcept = default;
PngRowWriter& PngRowWriter::operator=(PngRowWriter&&) noexcept = default;

int PngRowWriter::rows_written() const {
  return state_ ? state_->encoder->rows() : 0;
}

void PngRowWriter::write_row(const std::uint8_t* rgb) {
  if (!state_) throw std::logic_error("PngRowWriter::write_row on a moved-from writer");
  State& s = *state_;
  s.check_open("write_row");
  if (s.encoder->rows() == s.height) {
    throw std::logic_error(s.path + ": write_row after all " + std::to_string(s.height) + " rows");
  }
  s.guarded([&] { s.encoder->write_row(rgb); });
}

void PngRowWriter::finish() {
  if (!state_) throw std::logic_error("PngRowWriter::finish on a moved-from writer");
  State& s = *state_;
  s.check_open("finish");
  if (s.encoder->rows() != s.height) {
    throw std::logic_error(s.path + ": finish() after " + std::to_string(s.encoder->rows()) +
                           " of " + std::to_string(s.height) + " rows");
  }
  s.done = true;
  s.guarded([&] {
    s.encoder->finish();
    s.file->commit();
  });
}

}  // namespace oceanref
