// `oceanref brdf`: every term of the ocean BRDF and lighting for given directions.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_brdf_command(CLI::App& app);

}  // namespace oceanref::cli
