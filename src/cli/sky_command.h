// `oceanref sky`: the Preetham sky and sun at given directions, the sun disk's radiance, the
// horizontal sky irradiance, or the sky hemisphere as an EXR.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_sky_command(CLI::App& app);

}  // namespace oceanref::cli
