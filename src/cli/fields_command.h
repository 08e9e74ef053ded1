// `oceanref fields SCENE`: every wave field of every cascade as EXR channels (-o), or every
// field at one point from the FFT grid and by direct summation (--at).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>
#include <string>

#include "io/exr.h"
#include "scene/scene.h"

namespace oceanref::cli {

// Every field of every cascade and the combined fields as the EXR `fields -o` writes, and the
// SHA-256 of the double-precision values behind its float32 channels (channels in name order,
// each its name, a zero byte and its values as binary64 little-endian).
struct FieldsImage {
  ExrImage exr;
  std::string f64_sha256;
};
FieldsImage fields_image(const Scene& scene, const Ocean& ocean, int threads);

std::function<void(std::ostream& out)> add_fields_command(CLI::App& app);

}  // namespace oceanref::cli
