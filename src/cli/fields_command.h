// `oceanref fields SCENE`: every wave field of every cascade as EXR channels (-o), or every
// field at one point from the FFT grid and by direct summation (--at).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_fields_command(CLI::App& app);

}  // namespace oceanref::cli
