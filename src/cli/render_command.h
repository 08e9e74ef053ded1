// `oceanref render` (the reference image) and `oceanref probe` (everything behind one pixel).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_render_command(CLI::App& app);
std::function<void(std::ostream& out)> add_probe_command(CLI::App& app);

}  // namespace oceanref::cli
