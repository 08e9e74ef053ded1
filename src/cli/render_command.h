// `oceanref render` (the reference image) and `oceanref probe` (everything behind one pixel).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>
#include <string>

#include "io/exr.h"
#include "raster/renderer.h"
#include "scene/scene.h"

namespace oceanref::cli {

// A scene file rendered to the EXR that `render` writes (attributes included) and its pixel hash.
struct RenderedScene {
  ExrImage exr;
  std::string pixel_sha256;         // the float32 pixels as written
  std::string radiance_f64_sha256;  // the double radiance behind them
  RenderedImage image;
  ImageSettings settings;
};
// The estimated lighting error relative to the radiance, over the channels of the pixels that
// see the sea (`estimated` false when the image carries no estimate).
struct LightingErrorSummary {
  bool estimated = false;
  double max_relative = 0.0;
  double median_relative = 0.0;
};
LightingErrorSummary summarize_lighting_error(const RenderedImage& image);

RenderedScene render_scene(const std::string& path, int threads, int spp, bool aov,
                           bool show_progress);

std::function<void(std::ostream& out)> add_render_command(CLI::App& app);
std::function<void(std::ostream& out)> add_probe_command(CLI::App& app);

}  // namespace oceanref::cli
