#include "io/exr.h"

#include "core/format.h"
#include "io/output_file.h"

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfInputPart.h>
#include <ImfMatrixAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfTiledInputPart.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <span>
#include <stdexcept>

namespace oceanref {

namespace {
Imath::Box2i data_window(const ExrImage& image) {
  return Imath::Box2i(
      Imath::V2i(image.origin_x, image.origin_y),
      Imath::V2i(image.origin_x + image.width - 1, image.origin_y + image.height - 1));
}

// A float slice of a channel stored row-major at its own sampling: EXR addresses the sample of
// pixel (x, y) at base + (x/s)·xStride + (y/s)·yStride, so Slice::Make offsets the base by the
// data window's origin.
Imf::Slice float_slice(const float* data, const Imath::Box2i& window, int sampling) {
  const int width = window.max.x - window.min.x + 1;
  const std::size_t row = static_cast<std::size_t>(width / sampling) * sizeof(float);
  return Imf::Slice::Make(Imf::FLOAT, data, window, sizeof(float), row, sampling, sampling);
}

void check_size(const ExrImage& image, const std::string& what) {
  if (image.width < 1 || image.height < 1) {
    throw std::invalid_argument(what + ": size " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " is empty");
  }
  for (const ExrChannel& c : image.channels) {
    if (c.sampling < 1 || image.width % c.sampling != 0 || image.height % c.sampling != 0) {
      throw std::invalid_argument(what + ": channel " + c.name + " has sampling " +
                                  std::to_string(c.sampling) + ", which does not divide the size");
    }
    const std::size_t expected = static_cast<std::size_t>(image.width / c.sampling) *
                                 static_cast<std::size_t>(image.height / c.sampling);
    if (c.values.size() != expected) {
      throw std::invalid_argument(what + ": channel " + c.name + " has " +
                                  std::to_string(c.values.size()) + " values, expected " +
                                  std::to_string(expected));
    }
  }
}

// The header of one image: size, ZIP, string and matrix attributes, chromaticities, channels.
Imf::Header make_header(const ExrImage& image) {
  const Imath::Box2i window = data_window(image);
  Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                     Imf::ZIP_COMPRESSION);
  for (const auto& [key, value] : image.attributes) {
    header.insert(key, Imf::StringAttribute(value));
  }
  for (const auto& [key, m] : image.matrices) {
    header.insert(
        key, Imf::M44fAttribute(Imath::M44f(m[0][0], m[0][1], m[0][2], m[0][3], m[1][0], m[1][1],
                                            m[1][2], m[1][3], m[2][0], m[2][1], m[2][2], m[2][3],
                                            m[3][0], m[3][1], m[3][2], m[3][3])));
  }
  if (image.srgb_chromaticities) {
    // Rec. 709 / sRGB primaries and the D65 white (IEC 61966-2-1).
    Imf::addChromaticities(
        header, Imf::Chromaticities(Imath::V2f(0.64f, 0.33f), Imath::V2f(0.30f, 0.60f),
                                    Imath::V2f(0.15f, 0.06f), Imath::V2f(0.3127f, 0.3290f)));
  }
  for (const ExrChannel& c : image.channels) {
    header.channels().insert(c.name, Imf::Channel(Imf::FLOAT, c.sampling, c.sampling, false));
  }
  return header;
}

// The library's frame buffer wants mutable pointers; it only reads them when writing.
Imf::FrameBuffer output_frame(const ExrImage& image) {
  Imf::FrameBuffer frame;
  for (const ExrChannel& c : image.channels) {
    frame.insert(c.name, float_slice(c.values.data(), data_window(image), c.sampling));
  }
  return frame;
}

// Where OpenEXR writes: an OutputFile (io/output_file.h), so every write is checked and the
// file appears only when complete. While `record` is given, the bytes written from the start of
// the file are also appended to it (ExrRowWriter reads the header OpenEXR wrote); a seek ends
// the contiguous record (`recorded_whole` false).
class CheckedStream : public Imf::OStream {
 public:
  explicit CheckedStream(OutputFile& file) : Imf::OStream(file.path().c_str()), file_(file) {}
  void write(const char bytes[], int count) override {
    if (record_ != nullptr) {
      if (file_.position() != record_->size()) recorded_whole_ = false;
      record_->append(bytes, static_cast<std::size_t>(count));
    }
    file_.write(bytes, static_cast<std::size_t>(count));
  }
  std::uint64_t tellp() override { return file_.position(); }
  void seekp(std::uint64_t offset) override { file_.seek(offset); }
  void record(std::string* bytes) { record_ = bytes; }
  bool recorded_whole() const { return recorded_whole_; }

 private:
  OutputFile& file_;
  std::string* record_ = nullptr;
  bool recorded_whole_ = true;
};

// Rethrows the exception being handled as the EXR writers do: path and write errors unchanged,
// anything else (OpenEXR's exceptions) as a std::runtime_error naming the file.
[[noreturn]] void rethrow_write_error(const std::string& path) {
  try {
    throw;
  } catch (const OutputPathError&) {
    throw;
  } catch (const OutputWriteError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot write the EXR file: " + e.what());
  }
}

// Runs `write` on a stream into a new OutputFile for `path` and commits it; the error names
// the file. `write` must have destroyed its OpenEXR writer (which finishes the file) on return.
void write_through_stream(const std::string& path,
                          const std::function<void(Imf::OStream&)>& write) {
  try {
    OutputFile file(path);
    {
      CheckedStream stream(file);
      write(stream);
    }
    file.commit();
  } catch (...) {
    rethrow_write_error(path);
  }
}

// String and M44f attributes of a header, without the structural `name` and `type`.
void read_attributes(const Imf::Header& header, ExrImage& image) {
  for (auto a = header.begin(); a != header.end(); ++a) {
    const std::string key = a.name();
    if (key == "name" || key == "type") continue;
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) {
      image.attributes[key] = s->value();
    } else if (const auto* m = dynamic_cast<const Imf::M44fAttribute*>(&a.attribute())) {
      ExrMatrix matrix{};
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
          matrix[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] = m->value()[r][c];
        }
      }
      image.matrices[key] = matrix;
    }
  }
}

// Bytes of `lines` rows of `width` pixels of every channel of `header` as floats.
double channel_bytes(const Imf::Header& header, double width, double lines) {
  double bytes = 0.0;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
    const double sampling = std::max(1, c.channel().xSampling);
    bytes += width * lines / (sampling * sampling) * sizeof(float);
  }
  return bytes;
}

// Rows per compressed block of a scanline file: OpenEXR buffers one block.
double rows_per_block(Imf::Compression c) {
  switch (c) {
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION:
      return 16.0;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION:
      return 32.0;
    case Imf::DWAB_COMPRESSION:
      return 256.0;
    default:  // none, RLE, ZIPS
      return 1.0;
  }
}

// Takes `bytes` from the reading budget (the bytes the file may still allocate), or refuses.
void reserve(double& budget, double bytes, const std::string& what) {
  if (bytes > budget) {
    throw MemoryLimitError(what + " need " + mebibytes(bytes) + ", over the " + mebibytes(budget) +
                           " left of the reading limit (--max-memory)");
  }
  budget -= bytes;
}

std::string size_text(const Imf::Header& header, const Imath::Box2i& window) {
  int channels = 0;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) ++channels;
  return std::to_string(static_cast<long long>(window.max.x) - window.min.x + 1) + " x " +
         std::to_string(static_cast<long long>(window.max.y) - window.min.y + 1) + " pixels of " +
         std::to_string(channels) + " channels";
}

// Reserves an image's pixels before OpenEXR or this reader allocates anything for it.
void reserve_image(double& budget, const Imf::Header& header, const Imath::Box2i& window) {
  const double width = static_cast<double>(window.max.x) - window.min.x + 1.0;
  const double height = static_cast<double>(window.max.y) - window.min.y + 1.0;
  reserve(budget, channel_bytes(header, width, height), size_text(header, window));
}

// An image with the header's attributes and channels (zero-filled) for the given data window
// (its pixels reserved: reserve_image), and the frame buffer that reads into it.
ExrImage prepare_image(const Imf::Header& header, const Imath::Box2i& window, bool tiled,
                       Imf::FrameBuffer& frame) {
  ExrImage image;
  image.width = window.max.x - window.min.x + 1;
  image.height = window.max.y - window.min.y + 1;
  image.origin_x = window.min.x;
  image.origin_y = window.min.y;
  if (image.width < 1 || image.height < 1) throw std::runtime_error("empty data window");
  read_attributes(header, image);
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
    const int sampling = c.channel().xSampling;
    if (sampling < 1 || c.channel().ySampling != sampling || image.width % sampling != 0 ||
        image.height % sampling != 0 || image.origin_x % sampling != 0 ||
        image.origin_y % sampling != 0 || (tiled && sampling != 1)) {
      throw std::runtime_error(std::string("channel ") + c.name() + " has sampling " +
                               std::to_string(c.channel().xSampling) + "," +
                               std::to_string(c.channel().ySampling) +
                               " (supported: equal x and y sampling dividing the data window)");
    }
    image.channels.push_back(
        {c.name(), sampling,
         allocate_buffer<float>(static_cast<std::size_t>(image.width / sampling) *
                                    static_cast<std::size_t>(image.height / sampling),
                                "channel " + std::string(c.name()) + " of an EXR file read")});
  }
  for (ExrChannel& c : image.channels) {
    frame.insert(c.name, float_slice(c.values.data(), window, c.sampling));
  }
  return image;
}

std::string part_label(const Imf::Header& header, int index) {
  return "part " + std::to_string(index) + (header.hasName() ? " '" + header.name() + "'" : "");
}

void read_part(Imf::MultiPartInputFile& file, int index, std::vector<ExrPart>& out,
               double& budget) {
  const Imf::Header& header = file.header(index);
  const std::string name = header.hasName() ? header.name() : "";
  try {
    if (header.hasType() && Imf::isDeepData(header.type())) {
      throw std::runtime_error("deep data (" + header.type() +
                               ") is not supported: only flat images are read");
    }
    if (!header.hasTileDescription()) {
      const Imath::Box2i window = header.dataWindow();
      // OpenEXR's line buffer (one compressed block of rows), released once the part is read.
      const double line_buffer =
          channel_bytes(header, static_cast<double>(window.max.x) - window.min.x + 1.0,
                        rows_per_block(header.compression()));
      reserve(budget, line_buffer, "the line buffer of " + size_text(header, window));
      reserve_image(budget, header, window);
      Imf::InputPart part(file, index);
      Imf::FrameBuffer frame;
      ExrPart p{name, 0, 0, prepare_image(header, window, false, frame)};
      part.setFrameBuffer(frame);
      part.readPixels(window.min.y, window.max.y);
      out.push_back(std::move(p));
      budget += line_buffer;
      return;
    }
    // OpenEXR's tile buffers (two tiles), released once the part is read.
    const Imf::TileDescription tile = header.tileDescription();
    const double tile_buffers = 2.0 * channel_bytes(header, tile.xSize, tile.ySize);
    reserve(budget, tile_buffers,
            "the tile buffers of " + std::to_string(tile.xSize) + " x " +
                std::to_string(tile.ySize) + " tiles");
    Imf::TiledInputPart part(file, index);
    // ONE_LEVEL: 1 × 1 levels; MIPMAP_LEVELS: (l, l); RIPMAP_LEVELS: every (lx, ly).
    const bool ripmap = part.levelMode() == Imf::RIPMAP_LEVELS;
    const int ny = ripmap ? part.numYLevels() : 1;
    const int nx = part.numXLevels();
    for (int ly = 0; ly < ny; ++ly) {
      for (int lx = 0; lx < nx; ++lx) {
        const int level_y = ripmap ? ly : lx;
        Imf::FrameBuffer frame;
        const Imath::Box2i window = part.dataWindowForLevel(lx, level_y);
        reserve_image(budget, header, window);
        ExrPart p{name, lx, level_y, prepare_image(header, window, true, frame)};
        part.setFrameBuffer(frame);
        part.readTiles(0, part.numXTiles(lx) - 1, 0, part.numYTiles(level_y) - 1, lx, level_y);
        out.push_back(std::move(p));
      }
    }
    budget += tile_buffers;
  } catch (const std::exception& e) {
    throw std::runtime_error(part_label(header, index) + ": " + e.what());
  }
}

std::runtime_error read_error(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": cannot read the EXR file: " + what);
}

// OpenEXR checks a header's data window and tile size against process-wide maxima before it
// allocates its offset tables; set them once (call_once: readers may run on several threads).
void limit_openexr_image_size() {
  static std::once_flag once;
  std::call_once(once, [] {
    Imf::Header::setMaxImageSize(kMaxExrSide, kMaxExrSide);
    Imf::Header::setMaxTileSize(kMaxExrSide, kMaxExrSide);
  });
}

// A little-endian 32-bit integer at the stream's position.
bool read_int32(std::istream& in, std::int32_t& value) {
  unsigned char b[4] = {};
  if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
  value = static_cast<std::int32_t>(
      static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
      static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24);
  return true;
}

// A NUL-terminated name of at most 255 bytes (OpenEXR reads that many whether or not the
// long-names flag is set).
bool read_name(std::istream& in, std::string& name) {
  name.clear();
  for (char c = 0; in.get(c);) {
    if (c == '\0') return true;
    if (name.size() == 255) return false;
    name.push_back(c);
  }
  return false;
}

// The size of each fixed-size attribute type of OpenEXR 3.1: it reads that many bytes whatever
// size the header declares.
std::int32_t fixed_size(const std::string& type) {
  static const std::map<std::string, std::int32_t> sizes{
      {"box2i", 16},    {"box2f", 16},   {"int", 4},      {"float", 4},
      {"double", 8},    {"v2i", 8},      {"v2f", 8},      {"v2d", 16},
      {"v3i", 12},      {"v3f", 12},     {"v3d", 24},     {"m33f", 36},
      {"m33d", 72},     {"m44f", 64},    {"m44d", 128},   {"compression", 1},
      {"lineOrder", 1}, {"envmap", 1},   {"tiledesc", 9}, {"chromaticities", 32},
      {"rational", 8},  {"keycode", 28}, {"timecode", 8}, {"deepImageState", 1}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? -1 : it->second;
}

// The bytes OpenEXR reads for one attribute value must be the `size` the header declares:
// otherwise its reading and this walk part ways, and OpenEXR allocates from misread bytes.
// Fixed-size types must declare their size; a channel list runs to its empty name; a preview
// holds 8 + 4·width·height bytes; a string vector's lengths stay inside the value.
void check_attribute_value(std::istream& in, const std::string& type, std::int32_t size) {
  const std::int32_t fixed = fixed_size(type);
  if (fixed >= 0 && size != fixed) {
    throw std::runtime_error("declares " + std::to_string(size) + " bytes; a " + type + " has " +
                             std::to_string(fixed));
  }
  std::int64_t used = 0;
  if (type == "chlist") {
    for (std::string channel;;) {
      if (!read_name(in, channel)) throw std::runtime_error("a channel name is not terminated");
      used += static_cast<std::int64_t>(channel.size()) + 1;
      if (channel.empty()) break;
      used += 16;  // pixel type, pLinear and reserved, x and y sampling
      if (used > size) break;
      in.seekg(16, std::ios::cur);
    }
  } else if (type == "preview") {
    std::int32_t width = 0, height = 0;
    if (!read_int32(in, width) || !read_int32(in, height)) return;
    // Both unsigned in OpenEXR; their product fits 64 bits, four times it need not.
    const std::uint64_t pixels =
        std::uint64_t{static_cast<std::uint32_t>(width)} * static_cast<std::uint32_t>(height);
    if (pixels > static_cast<std::uint64_t>(size)) {
      throw std::runtime_error("declares " + std::to_string(size) + " bytes, but its preview of " +
                               std::to_string(static_cast<std::uint32_t>(width)) + " x " +
                               std::to_string(static_cast<std::uint32_t>(height)) +
                               " pixels needs more");
    }
    used = 8 + 4 * static_cast<std::int64_t>(pixels);
  } else if (type == "stringvector") {
    for (std::int32_t length = 0; used < size; used += length) {
      if (!read_int32(in, length)) return;
      used += 4;
      if (length < 0 || used + length > size) {
        throw std::runtime_error("holds a string of " + std::to_string(length) +
                                 " bytes past its end");
      }
      in.seekg(length, std::ios::cur);
    }
  } else {
    return;  // strings and other types: OpenEXR reads exactly `size` bytes
  }
  if (used != size) {
    throw std::runtime_error("declares " + std::to_string(size) + " bytes, but its " + type +
                             " value has " + std::to_string(used));
  }
}

// OpenEXR allocates each header attribute's claimed size before it reads the value (a 1 KB file
// can claim a 2 GB attribute). Walk the headers first (magic, version flags, then per header
// name\0 type\0 int32-size value..., an empty name ending it; multi-part files have several
// headers and an empty one at the end) and refuse a size the file cannot hold or one the value
// contradicts (check_attribute_value). Anything else malformed is left to OpenEXR's checks.
void check_header_sizes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in.tellg();
  in.seekg(0);
  unsigned char start[8] = {};
  if (!in.read(reinterpret_cast<char*>(start), 8)) return;
  if (start[0] != 0x76 || start[1] != 0x2f || start[2] != 0x31 || start[3] != 0x01) return;
  const bool multipart = (start[5] & 0x10) != 0;  // version flags: bit 12
  std::string name, type;
  for (int header = 0;; ++header) {
    if (multipart && header > 0 && in.peek() == 0) return;  // the empty header ends the list
    while (true) {
      if (!read_name(in, name)) return;
      if (name.empty()) break;  // the end of this header
      std::int32_t size = 0;
      if (!read_name(in, type) || !read_int32(in, size)) return;
      const std::streamoff value = in.tellg();
      const std::streamoff left = file_size - value;
      const std::string what =
          "header attribute " + escape_value(name) + " (" + escape_value(type) + ") ";
      if (size < 0 || size > left) {
        throw std::runtime_error(what + "claims " + std::to_string(size) + " bytes, but only " +
                                 std::to_string(left) + " bytes of the file follow");
      }
      try {
        check_attribute_value(in, type, size);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(what + e.what());
      }
      in.clear();
      in.seekg(value + size);
    }
    if (!multipart) return;
  }
}

// A single-part file, opened after the header checks (call inside the reader's try: a failure
// becomes its read_error); `multi_part_hint` says where a multi-part file should go.
std::unique_ptr<Imf::MultiPartInputFile> open_single_part(const std::string& path,
                                                          const std::string& multi_part_hint) {
  check_header_sizes(path);
  auto file = std::make_unique<Imf::MultiPartInputFile>(path.c_str());
  if (file->parts() != 1) {
    throw std::runtime_error("it has " + std::to_string(file->parts()) + " parts; " +
                             multi_part_hint);
  }
  return file;
}

void check_readable(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw read_error(path,
                     std::filesystem::exists(path, error) ? "not a regular file" : "no such file");
  }
}
}  // namespace

void write_exr(const std::string& path, const ExrImage& image) {
  check_size(image, path);
  if (std::all_of(image.channels.begin(), image.channels.end(),
                  [](const ExrChannel& c) { return c.sampling == 1; })) {
    ExrRowWriter writer(path, image);
    std::vector<std::span<const float>> channels;
    for (const ExrChannel& c : image.channels) channels.emplace_back(c.values);
    writer.write_rows_from(channels, image.height);
    writer.finish();
    return;
  }
  const Imf::Header header = make_header(image);
  const Imf::FrameBuffer frame = output_frame(image);
  write_through_stream(path, [&](Imf::OStream& stream) {
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  });
}

void write_exr_parts(const std::string& path, const std::vector<ExrPart>& parts) {
  if (parts.empty()) throw std::invalid_argument(path + ": an EXR file needs at least one part");
  std::vector<Imf::Header> headers;
  std::set<std::string> names;
  for (const ExrPart& p : parts) {
    const std::string what = path + ": part '" + p.name + "'";
    if (p.name.empty()) throw std::invalid_argument(path + ": every part needs a name");
    if (!names.insert(p.name).second) {
      throw std::invalid_argument(what + ": part names must be unique");
    }
    if (p.level_x != 0 || p.level_y != 0) {
      throw std::invalid_argument(what + ": only level 0, 0 is written (scanline parts)");
    }
    check_size(p.image, what);
    for (const ExrChannel& c : p.image.channels) {
      if (c.sampling != 1) {
        throw std::invalid_argument(what + ": channel " + c.name +
                                    " is subsampled; multi-part files hold full-resolution "
                                    "channels only (give each resolution its own part)");
      }
    }
    for (const std::string reserved : {"name", "type"}) {
      if (p.image.attributes.contains(reserved) || p.image.matrices.contains(reserved)) {
        throw std::invalid_argument(what + ": attribute '" + reserved + "' is reserved");
      }
    }
    headers.push_back(make_header(p.image));
    headers.back().setName(p.name);
    headers.back().setType(Imf::SCANLINEIMAGE);
  }
  // displayWindow is shared by all parts of a file (OpenEXR rejects differing ones): the bounding
  // box of every part's data window.
  Imath::Box2i display;
  for (const Imf::Header& h : headers) display.extendBy(h.dataWindow());
  for (Imf::Header& h : headers) h.displayWindow() = display;
  write_through_stream(path, [&](Imf::OStream& stream) {
    Imf::MultiPartOutputFile file(stream, headers.data(), static_cast<int>(headers.size()));
    for (std::size_t i = 0; i < parts.size(); ++i) {
      Imf::OutputPart part(file, static_cast<int>(i));
      part.setFrameBuffer(output_frame(parts[i].image));
      part.writePixels(parts[i].image.height);
    }
  });
}

ExrImage read_exr(const std::string& path, double max_bytes) {
  check_readable(path);
  limit_openexr_image_size();
  try {
    const auto file = open_single_part(path, "read multi-part files with read_exr_parts");
    std::vector<ExrPart> parts;
    read_part(*file, 0, parts, max_bytes);
    return std::move(parts.front().image);  // level 0 of a tiled file
  } catch (const std::exception& e) {
    throw read_error(path, e.what());
  }
}

std::vector<ExrPart> read_exr_parts(const std::string& path, double max_bytes) {
  check_readable(path);
  limit_openexr_image_size();
  try {
    check_header_sizes(path);
    Imf::MultiPartInputFile file(path.c_str());
    std::vector<ExrPart> parts;
    for (int i = 0; i < file.parts(); ++i) read_part(file, i, parts, max_bytes);
    return parts;
  } catch (const std::exception& e) {
    throw read_error(path, e.what());
  }
}

// ---- ExrRowWriter ------------------------------------------------------------------------------

namespace {
// The bytes a deferred attribute holds until set_deferred gives its value.
constexpr char kPlaceholder = '?';
}  // namespace

struct ExrRowWriter::State {
  struct Deferred {
    std::size_t length = 0;
    std::uint64_t offset = 0;  // of the value's first byte in the file
    bool set = false;
    std::string value;
  };
  std::string path;
  int width = 0;
  int height = 0;
  int origin_x = 0;
  int origin_y = 0;
  std::vector<std::string> channels;  // layout order
  std::map<std::string, Deferred> deferred;
  int rows = 0;       // rows written
  bool done = false;  // finished, or failed: no further call is accepted
  // Destroyed in reverse order: OpenEXR's writer (it writes its offset table), its stream, then
  // the file (which removes the temporary unless committed).
  std::unique_ptr<OutputFile> file;
  std::unique_ptr<CheckedStream> stream;
  std::unique_ptr<Imf::OutputFile> exr;

  // Throws std::logic_error (naming the method `call`) once the writer takes no more calls.
  void check_open(const char* call) const {
    if (done) {
      throw std::logic_error(path + ": ExrRowWriter::" + call +
                             " after finish() or after a failed write");
    }
  }
};

ExrRowWriter::ExrRowWriter(const std::string& path, const ExrImage& layout,
                           const std::map<std::string, std::size_t>& deferred)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  s.width = layout.width;
  s.height = layout.height;
  s.origin_x = layout.origin_x;
  s.origin_y = layout.origin_y;
  if (layout.width < 1 || layout.height < 1) {
    throw std::invalid_argument(path + ": size " + std::to_string(layout.width) + "x" +
                                std::to_string(layout.height) + " is empty");
  }
  // The layout without its pixels (they may be large and are not needed here).
  ExrImage shape;
  shape.width = layout.width;
  shape.height = layout.height;
  shape.origin_x = layout.origin_x;
  shape.origin_y = layout.origin_y;
  shape.attributes = layout.attributes;
  shape.matrices = layout.matrices;
  shape.srgb_chromaticities = layout.srgb_chromaticities;
  std::set<std::string> names;
  for (const ExrChannel& c : layout.channels) {
    if (c.sampling != 1) {
      throw std::invalid_argument(path + ": channel " + c.name + " has sampling " +
                                  std::to_string(c.sampling) +
                                  "; ExrRowWriter writes full-resolution channels only");
    }
    if (!names.insert(c.name).second) {
      throw std::invalid_argument(path + ": channel " + c.name + " is named twice");
    }
    s.channels.push_back(c.name);
    shape.channels.push_back({c.name, 1, {}});
  }
  for (const auto& [name, length] : deferred) {
    if (!layout.attributes.contains(name)) {
      throw std::logic_error(path + ": the deferred attribute " + name +
                             " is not a string attribute of the layout");
    }
    if (length > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
      throw std::invalid_argument(path + ": the deferred attribute " + name + " is too long");
    }
    shape.attributes[name] = std::string(length, kPlaceholder);
    s.deferred[name].length = length;
  }
  std::string header;  // the bytes OpenEXR writes before the first pixel
  try {
    const Imf::Header exr_header = make_header(shape);
    s.file = std::make_unique<OutputFile>(path);
    s.stream = std::make_unique<CheckedStream>(*s.file);
    s.stream->record(&header);
    s.exr = std::make_unique<Imf::OutputFile>(*s.stream, exr_header);
    s.stream->record(nullptr);
  } catch (...) {
    rethrow_write_error(path);
  }
  if (!s.stream->recorded_whole()) {
    throw std::logic_error(path + ": OpenEXR did not write its header in one piece");
  }
  // Each placeholder: `name\0string\0<int32 length, little-endian><placeholder>`, exactly once.
  for (auto& [name, d] : s.deferred) {
    std::string pattern = name + '\0' + "string" + '\0';
    for (int b = 0; b < 4; ++b) {
      pattern.push_back(static_cast<char>(static_cast<std::uint32_t>(d.length) >> (8 * b)));
    }
    pattern.append(d.length, kPlaceholder);
    int found = 0;
    std::size_t at = 0;
    for (std::size_t p = header.find(pattern); p != std::string::npos;
         p = header.find(pattern, p + 1)) {
      ++found;
      at = p;
    }
    if (found != 1) {
      throw std::logic_error(path + ": the placeholder of the deferred attribute " + name +
                             " is found " + std::to_string(found) +
                             " times in the header written (expected once)");
    }
    d.offset = at + pattern.size() - d.length;
  }
}

ExrRowWriter::~ExrRowWriter() = default;
ExrRowWriter::ExrRowWriter(ExrRowWriter&&) noexcept = default;
ExrRowWriter& ExrRowWriter::operator=(ExrRowWriter&&) noexcept = default;

int ExrRowWriter::rows_written() const {
  return state_ ? state_->rows : 0;
}

void ExrRowWriter::write_rows(const std::vector<std::vector<float>>& channels, int rows) {
  write_rows_from(std::vector<std::span<const float>>(channels.begin(), channels.end()), rows);
}

void ExrRowWriter::write_rows_from(const std::vector<std::span<const float>>& channels, int rows) {
  if (!state_) throw std::logic_error("ExrRowWriter::write_rows on a moved-from writer");
  State& s = *state_;
  s.check_open("write_rows");
  if (channels.size() != s.channels.size()) {
    throw std::invalid_argument(s.path + ": " + std::to_string(channels.size()) +
                                " channels given, the layout has " +
                                std::to_string(s.channels.size()));
  }
  if (rows < 1 || rows > s.height - s.rows) {
    throw std::invalid_argument(s.path + ": " + std::to_string(rows) + " rows given after " +
                                std::to_string(s.rows) + " of " + std::to_string(s.height) +
                                " (1 to " + std::to_string(s.height - s.rows) + " accepted)");
  }
  const std::size_t expected = static_cast<std::size_t>(rows) * static_cast<std::size_t>(s.width);
  for (std::size_t i = 0; i < channels.size(); ++i) {
    if (channels[i].size() != expected) {
      throw std::invalid_argument(
          s.path + ": channel " + s.channels[i] + " has " + std::to_string(channels[i].size()) +
          " values for " + std::to_string(rows) + " rows, expected " + std::to_string(expected));
    }
  }
  // The band's first value is pixel (origin_x, origin_y + rows written).
  const int top = s.origin_y + s.rows;
  const Imath::Box2i band(Imath::V2i(s.origin_x, top),
                          Imath::V2i(s.origin_x + s.width - 1, top + rows - 1));
  Imf::FrameBuffer frame;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    frame.insert(s.channels[i], float_slice(channels[i].data(), band, 1));
  }
  try {
    s.exr->setFrameBuffer(frame);
    s.exr->writePixels(rows);
  } catch (...) {
    s.done = true;
    rethrow_write_error(s.path);
  }
  s.rows += rows;
}

void ExrRowWriter::set_deferred(const std::string& name, const std::string& value) {
  if (!state_) throw std::logic_error("ExrRowWriter::set_deferred on a moved-from writer");
  State& s = *state_;
  s.check_open("set_deferred");
  const auto it = s.deferred.find(name);
  if (it == s.deferred.end()) {
    throw std::logic_error(s.path + ": " + name + " is not a deferred attribute of this writer");
  }
  if (value.size() != it->second.length) {
    throw std::invalid_argument(s.path + ": the deferred attribute " + name + " has " +
                                std::to_string(it->second.length) + " bytes; the value given has " +
                                std::to_string(value.size()));
  }
  it->second.value = value;
  it->second.set = true;
}

void ExrRowWriter::finish() {
  if (!state_) throw std::logic_error("ExrRowWriter::finish on a moved-from writer");
  State& s = *state_;
  s.check_open("finish");
  if (s.rows != s.height) {
    throw std::logic_error(s.path + ": finish() after " + std::to_string(s.rows) + " of " +
                           std::to_string(s.height) + " rows");
  }
  for (const auto& [name, d] : s.deferred) {
    if (!d.set) {
      throw std::logic_error(s.path + ": finish() before the deferred attribute " + name +
                             " was set");
    }
  }
  s.done = true;
  try {
    s.exr.reset();  // OpenEXR writes its offset table (a failed write marks the file failed)
    for (const auto& [name, d] : s.deferred) {
      s.file->seek(d.offset);
      s.file->write(d.value);
    }
    s.stream.reset();
    s.file->commit();
  } catch (...) {
    rethrow_write_error(s.path);
  }
}

// ---- read_exr_rows -----------------------------------------------------------------------------

std::vector<std::vector<float>> read_exr_rows(const std::string& path,
                                              const std::vector<std::string>& channels,
                                              int first_row, int last_row) {
  check_readable(path);
  limit_openexr_image_size();
  try {
    const auto owned = open_single_part(path, "read_exr_rows reads single-part files");
    Imf::MultiPartInputFile& file = *owned;
    const Imf::Header& header = file.header(0);
    if ((header.hasType() && header.type() != Imf::SCANLINEIMAGE) || header.hasTileDescription()) {
      throw std::runtime_error("read_exr_rows reads scanline files only (this one is " +
                               (header.hasType() ? header.type() : std::string("tiled")) + ")");
    }
    const Imath::Box2i window = header.dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (width < 1 || height < 1) throw std::runtime_error("empty data window");
    if (first_row < 0 || last_row < first_row || last_row > height) {
      throw std::runtime_error("rows " + std::to_string(first_row) + " to " +
                               std::to_string(last_row) + " (end excluded) are outside the " +
                               std::to_string(height) + " rows of the data window");
    }
    std::set<std::string> names;
    for (const std::string& name : channels) {
      if (!names.insert(name).second) throw std::runtime_error("channel " + name + " asked twice");
      const Imf::Channel* c = header.channels().findChannel(name);
      if (c == nullptr) throw std::runtime_error("no channel " + name);
      if (c->xSampling != 1 || c->ySampling != 1) {
        throw std::runtime_error("channel " + name + " is subsampled (read it with read_exr)");
      }
    }
    const std::size_t count =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(last_row - first_row);
    std::vector<std::vector<float>> out;
    for (const std::string& name : channels) {
      out.push_back(allocate_buffer<float>(count, "rows of channel " + name + " of an EXR file"));
    }
    if (count == 0) return out;
    const int top = window.min.y + first_row;
    const Imath::Box2i band(Imath::V2i(window.min.x, top),
                            Imath::V2i(window.max.x, window.min.y + last_row - 1));
    Imf::FrameBuffer frame;
    for (std::size_t i = 0; i < channels.size(); ++i) {
      frame.insert(channels[i], float_slice(out[i].data(), band, 1));
    }
    Imf::InputPart part(file, 0);
    part.setFrameBuffer(frame);
    part.readPixels(band.min.y, band.max.y);
    return out;
  } catch (const std::exception& e) {
    throw read_error(path, e.what());
  }
}

}  // namespace oceanref
