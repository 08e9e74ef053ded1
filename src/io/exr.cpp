#include "io/exr.h"

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>

namespace oceanref {

namespace {
// A slice for a subsampled channel: EXR addresses a sample (x, y) at
// base + (x/xs)·xStride + (y/ys)·yStride, so the base is offset for the data window origin (0).
Imf::Slice float_slice(float* data, int width, int sampling) {
  const std::size_t row = static_cast<std::size_t>(width / sampling) * sizeof(float);
  return Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data), sizeof(float), row, sampling,
                    sampling);
}
}  // namespace

void write_exr(const std::string& path, const ExrImage& image) {
  const std::filesystem::path target(path);
  const std::filesystem::path temporary =
      target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()));
  try {
    Imf::Header header(image.width, image.height, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                       Imf::ZIP_COMPRESSION);
    for (const auto& [key, value] : image.attributes) {
      header.insert(key, Imf::StringAttribute(value));
    }
    if (image.srgb_chromaticities) {
      // Rec. 709 / sRGB primaries and the D65 white (IEC 61966-2-1).
      Imf::addChromaticities(
          header, Imf::Chromaticities(Imath::V2f(0.64f, 0.33f), Imath::V2f(0.30f, 0.60f),
                                      Imath::V2f(0.15f, 0.06f), Imath::V2f(0.3127f, 0.3290f)));
    }
    Imf::FrameBuffer frame;
    std::vector<std::vector<float>> copies;  // the library wants mutable pointers
    copies.reserve(image.channels.size());
    for (const ExrChannel& c : image.channels) {
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT, c.sampling, c.sampling, false));
      copies.push_back(c.values);
      frame.insert(c.name, float_slice(copies.back().data(), image.width, c.sampling));
    }
    {
      Imf::OutputFile file(temporary.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }
    std::filesystem::rename(temporary, target);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(path + ": cannot write the EXR file: " + e.what());
  }
}

ExrImage read_exr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    ExrImage image;
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    if (window.min.x != 0 || window.min.y != 0) {
      throw std::runtime_error("data windows not starting at (0, 0) are not supported");
    }
    for (auto a = file.header().begin(); a != file.header().end(); ++a) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) {
        image.attributes[a.name()] = s->value();
      }
    }
    Imf::FrameBuffer frame;
    for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c) {
      const int sampling = c.channel().xSampling;
      if (sampling < 1 || c.channel().ySampling != sampling || image.width % sampling != 0 ||
          image.height % sampling != 0) {
        throw std::runtime_error(std::string("channel ") + c.name() + " has unsupported sampling");
      }
      image.channels.push_back(
          {c.name(), sampling,
           std::vector<float>(static_cast<std::size_t>(image.width / sampling) *
                              static_cast<std::size_t>(image.height / sampling))});
    }
    for (ExrChannel& c : image.channels) {
      frame.insert(c.name, float_slice(c.values.data(), image.width, c.sampling));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot read the EXR file: " + e.what());
  }
}

}  // namespace oceanref
