// `oceanref fields SCENE`: every wave field of every cascade as EXR channels (-o), or every
// field at one point from the FFT grid and by direct summation (--at).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

#include "io/exr.h"
#include "scene/scene.h"

namespace oceanref::cli {

// Every field of every cascade and the combined fields as the EXR `fields -o` writes.
ExrImage fields_image(const Scene& scene, const Ocean& ocean, int threads);

std::function<void(std::ostream& out)> add_fields_command(CLI::App& app);

}  // namespace oceanref::cli
