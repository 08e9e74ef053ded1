#include "conformance/report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/png.h"
#include "shading/tone_mapping.h"

namespace oceanref {

namespace {
std::vector<Vec3> colours(const ExrImage& image) {
  const auto pixels =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<Vec3> out(pixels, Vec3{});
  const auto find = [&](const std::string& name) -> const ExrChannel* {
    for (const ExrChannel& c : image.channels) {
      if (c.name == name && c.sampling == 1) return &c;
    }
    return nullptr;
  };
  const ExrChannel* r = find("R");
  const ExrChannel* g = find("G");
  const ExrChannel* b = find("B");
  const ExrChannel* grey = nullptr;
  for (const ExrChannel& c : image.channels) {
    if (c.sampling == 1) {
      grey = &c;
      break;
    }
  }
  for (std::size_t i = 0; i < pixels; ++i) {
    if (r && g && b) {
      out[i] = {static_cast<double>(r->values[i]), static_cast<double>(g->values[i]),
                static_cast<double>(b->values[i])};
    } else if (grey) {
      const double v = std::fabs(static_cast<double>(grey->values[i]));
      out[i] = {v, v, v};
    }
  }
  return out;
}

std::vector<std::uint8_t> tone_map(const std::vector<Vec3>& image, double average, double white) {
  std::vector<std::uint8_t> rgb;
  for (const Vec3& c : image) {
    const Vec3 m = reinhard(c, average, 0.18, white);
    for (const double v : m)
      rgb.push_back(static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(v))));
  }
  return rgb;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}
}  // namespace

void write_report(const std::string& directory, const std::string& golden_name,
                  const std::string& candidate_name, const ExrImage& golden,
                  const ExrImage& candidate, const Comparison& comparison) {
  std::filesystem::create_directories(directory);
  const std::filesystem::path dir(directory);
  ExrImage diff;
  diff.width = golden.width;
  diff.height = golden.height;
  diff.channels = {{"diff", 1, comparison.difference}};
  write_exr((dir / "diff.exr").string(), diff);
  const std::vector<Vec3> a = colours(golden);
  const std::vector<Vec3> b = colours(candidate);
  const double average = log_average_luminance(a);
  double white = 0.0;
  for (const Vec3& c : a)
    white = std::max(white, 0.18 / std::max(average, 1e-30) * relative_luminance(c));
  write_png((dir / "golden.png").string(), golden.width, golden.height,
            tone_map(a, average, white));
  write_png((dir / "candidate.png").string(), golden.width, golden.height,
            tone_map(b, average, white));
  const float largest =
      comparison.difference.empty()
          ? 0.0f
          : *std::max_element(comparison.difference.begin(), comparison.difference.end());
  std::vector<std::uint8_t> heat;
  for (const float d : comparison.difference) {
    const double t = largest > 0.0f ? std::sqrt(static_cast<double>(d / largest)) : 0.0;
    const double r = std::clamp(3.0 * t, 0.0, 1.0);
    const double g = std::clamp(3.0 * t - 1.0, 0.0, 1.0);
    const double bl = std::clamp(3.0 * t - 2.0, 0.0, 1.0);
    for (const double v : {r, g, bl})
      heat.push_back(static_cast<std::uint8_t>(std::lround(255.0 * v)));
  }
  write_png((dir / "diff.png").string(), golden.width, golden.height, heat);
  std::ostringstream html;
  html
      << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>oceanref compare</title>"
      << "<style>body{font-family:sans-serif}td,th{padding:2px 8px;text-align:right}"
      << "img{image-rendering:pixelated;width:32%}</style></head><body>\n"
      << "<h1>" << (comparison.pass ? "PASS" : "FAIL")
      << "</h1>\n<p>golden: " << html_escape(golden_name)
      << "<br>candidate: " << html_escape(candidate_name)
      << "<br>failing pixels: " << comparison.failing_share * 100.0
      << "%<br>largest difference: " << largest
      << " (diff.png: √(|a − b|/largest), black → red → yellow → white)</p>\n"
      << "<p><img src=\"golden.png\" alt=\"golden\"> <img src=\"candidate.png\" alt=\"candidate\"> "
      << "<img src=\"diff.png\" alt=\"difference\"></p>\n<table><tr><th>channel</th><th>max "
         "abs</th>"
      << "<th>max rel</th><th>RMSE</th><th>PSNR dB</th><th>max ULP</th><th>failing</th>"
      << "<th>worst pixel</th></tr>\n";
  for (const ChannelMetrics& m : comparison.channels) {
    html << "<tr><td>" << html_escape(m.name) << "</td><td>" << m.max_absolute << "</td><td>"
         << m.max_relative << "</td><td>" << m.rmse << "</td><td>" << m.psnr << "</td><td>"
         << m.max_ulp << "</td><td>" << m.failing_share << "</td><td>" << m.worst_x << ","
         << m.worst_y << "</td></tr>\n";
  }
  html << "</table></body></html>\n";
  std::ofstream file(dir / "index.html");
  file << html.str();
  if (!file) throw std::runtime_error(directory + ": cannot write index.html");
}

}  // namespace oceanref
